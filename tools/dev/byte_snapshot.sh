#!/usr/bin/env bash
# byte_snapshot.sh TESSERA OUT: every output a speed change must keep, for diffing before and after.
#
# For every built-in scene: the image, the stats JSON and the .tframe at 7 threads, a check that 1 thread
# gives the same image_sha256, and the cpu,cpu cross-check report (provenance path). Timing keys are
# removed from the JSON files (they differ from run to run); the HTML reports keep their times, so
# compare those by their JSON twins. Ends with OUT/SHA256SUMS and `tessera golden check` run from the
# source tree of this script.
#
#   tools/dev/byte_snapshot.sh old/build/tessera /tmp/snap-old
#   tools/dev/byte_snapshot.sh build/tessera /tmp/snap-new
#   diff /tmp/snap-old/SHA256SUMS /tmp/snap-new/SHA256SUMS | grep -v index.html   # empty: same bytes
#
# About a minute in a Release build on 2 cores. CONTRIBUTING.md, "A speed change must keep every
# output byte".
set -euo pipefail
usage() { sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; }
if [ "${1:-}" = "-h" ] || [ "${1:-}" = "--help" ]; then usage; exit 0; fi
if [ $# -ne 2 ]; then usage >&2; echo "byte_snapshot: expected 2 arguments, got $#" >&2; exit 2; fi
T=$(realpath "$1") OUT=$2
SRC=$(cd "$(dirname "$0")/../.." && pwd)
[ -x "$T" ] || { echo "byte_snapshot: $1: not an executable tessera binary" >&2; exit 2; }
if [ -e "$OUT" ] && [ -n "$(ls -A "$OUT")" ]; then
  echo "byte_snapshot: $OUT: exists and is not empty (choose a new directory)" >&2
  exit 2
fi
mkdir -p "$OUT"
cd "$OUT"
status=0
scenes=$("$T" scenes | awk '{print $1}')
n=$(echo "$scenes" | wc -w) i=0
for s in $scenes; do
  i=$((i + 1))
  echo "[$i/$n] $s" >&2
  "$T" render "$s" --threads 7 -o "$s.png" --stats "$s.json" --record "$s.tframe" > /dev/null
  "$T" render "$s" --threads 1 --record "$s.t1.tframe" --stats "$s.t1.json" > /dev/null
  if ! python3 - "$s.json" "$s.t1.json" <<'PY'
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:])
keys = [k for k in a if 'sha' in k or 'hash' in k]
sys.exit(0 if keys and all(a[k] == b[k] for k in keys) else 1)
PY
  then
    echo "byte_snapshot: $s: 7 threads and 1 thread give different hashes" >&2
    status=1
  fi
  rm -f "$s.t1.json" "$s.t1.tframe"
  "$T" crosscheck "$s" --backends cpu,cpu --report "xc_$s" > /dev/null 2>&1 || true
done
python3 - <<'PY'
import glob, json, re
def strip(o):
    if isinstance(o, dict):
        return {k: strip(v) for k, v in o.items()
                if not re.search(r'(_ms|_s|seconds|time|duration|host|date|version|path|binary|timing|stages)$', k)}
    if isinstance(o, list):
        return [strip(v) for v in o]
    return o
for f in glob.glob('*.json') + glob.glob('xc_*/*.json'):
    d = json.load(open(f))
    json.dump(strip(d), open(f, 'w'), indent=1, sort_keys=True)
PY
find . -type f ! -name SHA256SUMS | sort | xargs sha256sum > SHA256SUMS
if (cd "$SRC" && "$T" golden check > /dev/null); then
  echo "byte_snapshot: golden check ok; $(wc -l < SHA256SUMS) files in $OUT/SHA256SUMS" >&2
else
  echo "byte_snapshot: tessera golden check FAILED" >&2
  status=1
fi
exit $status
