#!/usr/bin/env bash
# oiio_on_demand.sh MODULE BINARY...: OpenImageIO is loaded on demand (raster/image_module.h), so no
# binary may load it at start: Debian's OIIO brings ~260 shared libraries, ~0.5 s of CPU per process.
# MODULE (libtessera_image_module.so) must list it, which shows that the check below can see it.
set -euo pipefail
module=$1; shift
# (ldd's output is kept before grep reads it: grep -q stops early, and under pipefail ldd's SIGPIPE
# would read as a failure.)
mod=$(ldd "$module")
grep -qF libOpenImageIO <<< "$mod" || { echo "FAIL: $module does not list libOpenImageIO: the check is blind" >&2; exit 1; }
for bin in "$@"; do
  out=$(ldd "$bin") || { echo "FAIL: ldd $bin failed" >&2; exit 1; }
  if grep -F libOpenImageIO <<< "$out"; then
    echo "FAIL: $bin loads OpenImageIO at start: some code of it calls OIIO directly; go through raster/image_module.h (CONTRIBUTING.md, "Code")" >&2
    exit 1
  fi
  echo "ok: $bin ($(wc -l <<< "$out") shared objects at start)"
done
