#!/usr/bin/env bash
# Counts the instructions of one benchmark with callgrind (docs/bench.md, "Counting instructions
# instead of time"): exact, and the same on a loaded machine, where timed runs are not.
#
# Usage: tools/dev/callgrind.sh BENCH_RASTER FILTER OUT
#   BENCH_RASTER  a bench_raster binary, best from a Release build with -g (build-prof, docs/bench.md)
#   FILTER        a --benchmark_filter regex, e.g. '^tiny_tris_100k/1/'
#   OUT           the callgrind output file; then `callgrind_annotate --inclusive=yes OUT`
#
# libhwy probes its timer with RDTSCP when it loads. valgrind decodes that instruction only on a CPU
# that has it, and some VMs hide it ("unhandled instruction bytes: 0xF 0x1 0xF9"), so the run preloads a
# stand-in for hwy::platform::TimerResolution(), built here once. The oracle never calls it; only
# Highway's own benchmark helpers do.
set -euo pipefail
[ $# -eq 3 ] || { sed -n '2,14p' "$0" >&2; exit 2; }
bench=$1 filter=$2 out=$3
[ -x "$bench" ] || { echo "callgrind.sh: $bench: not an executable" >&2; exit 2; }
command -v valgrind > /dev/null || { echo "callgrind.sh: valgrind is not installed (apt-get install valgrind)" >&2; exit 2; }
shim_dir=${XDG_CACHE_HOME:-$HOME/.cache}/tessera
shim=$shim_dir/libhwy_timer_shim.so
if [ ! -f "$shim" ]; then
  mkdir -p "$shim_dir"
  src=$(mktemp --suffix=.cpp)
  trap 'rm -f "$src"' EXIT
  printf '%s\n' '#include <cstdint>' \
    'namespace hwy { namespace platform { uint64_t TimerResolution() { return 1; } } }' > "$src"
  g++ -O2 -shared -fPIC -o "$shim.tmp" "$src" && mv "$shim.tmp" "$shim"
fi
LD_PRELOAD=$shim valgrind --tool=callgrind --callgrind-out-file="$out" "$bench" \
  --benchmark_filter="$filter" --benchmark_min_time=0.01
echo "callgrind.sh: $out written; callgrind_annotate --inclusive=yes $out | less" >&2
