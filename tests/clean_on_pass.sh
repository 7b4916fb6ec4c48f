#!/usr/bin/env bash
# clean_on_pass.sh DIR COMMAND...: runs COMMAND; if it passes, removes DIR (its output), so that a full
# `make test` does not keep gigabytes of passing outputs on a CI disk (stop 21 ran out of space). A
# failing command keeps DIR for inspection and its exit status is passed on.
set -uo pipefail
dir=$1; shift
"$@"; rc=$?
if [ $rc = 0 ]; then rm -rf "$dir"; else echo "kept for inspection: $dir" >&2; fi
exit $rc
