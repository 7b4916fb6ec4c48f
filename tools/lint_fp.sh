#!/usr/bin/env bash
# The floating-point lint (CONTRIBUTING.md, "Bit-reproducible"; issue 13 section 3): the oracle's bytes
# must not depend on the SIMD target or the compiler's contraction choices, so the sources of the
# bit-exact libraries may not use
#   - fused multiply-add: std::fma, fma/fmaf/fmal, __builtin_fma*, _mm*_fmadd/fmsub/fnmadd/fnmsub/
#     fmaddsub/fmsubadd*, Highway's MulAdd / NegMulAdd / MulSub / NegMulSub / MulAddSub;
#   - approximate reciprocals: _mm*_rcp*, _mm*_rsqrt*, Highway's ApproximateReciprocal(Sqrt);
#   - float horizontal reductions (their order is the target's): Highway's ReduceSum / SumOfLanes,
#     _mm*_hadd_ps / _pd, _mm512_reduce_add / mul_ps / pd;
# and no CMake file of the repository may turn on -ffast-math, -ffp-contract=fast, -Ofast or
# -funsafe-math-optimizations.
# A line that must name one of these (an integer reduction, say) carries the marker `fp-lint: allow`
# with its reason in the same comment.
#
# Usage: tools/lint_fp.sh [ROOT]   (ROOT defaults to the repository). Exit 0: clean; 1: violations,
# listed as file:line: text.
set -uo pipefail
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
cd "$root" || { echo "lint_fp: cannot enter $root" >&2; exit 2; }
dirs=()
for d in raster mta batching rtta verify base; do [ -d "$d" ] && dirs+=("$d"); done
status=0
report() {  # report TITLE: lines from stdin that lack the allow marker
  local hits
  hits=$(grep -v 'fp-lint: allow' || true)
  if [ -n "$hits" ]; then
    echo "lint_fp: $1:" >&2
    echo "$hits" >&2
    status=1
  fi
}
src_pattern_fma='std::fma\b|(^|[^A-Za-z0-9_.])fma[fl]?[[:space:]]*\(|__builtin_fma|_mm[0-9]*_(fn?m(add|sub)|fmaddsub|fmsubadd)|\b(Neg)?Mul(Add|Sub)\b|\bMulAddSub\b'
src_pattern_rcp='_mm[0-9]*_(rcp|rsqrt)[0-9a-z_]*|ApproximateReciprocal'
src_pattern_red='\bReduceSum\b|\bSumOfLanes\b|_mm[0-9]*_hadd_p[sd]|_mm512_reduce_(add|mul)_p[sd]'
if [ ${#dirs[@]} -gt 0 ]; then
  includes=(--include='*.h' --include='*.hpp' --include='*.cpp' --include='*.cc' --include='*.inl' --include='*.glsl')
  # Process substitution, not a pipe: report() must run in this shell to set the status.
  report "fused multiply-add (bits differ from a separate multiply and add)" \
    < <(grep -rnE "${includes[@]}" "$src_pattern_fma" "${dirs[@]}")
  report "approximate reciprocal (bits differ between targets)" < <(grep -rnE "${includes[@]}" "$src_pattern_rcp" "${dirs[@]}")
  report "float horizontal reduction (order differs between targets)" \
    < <(grep -rnE "${includes[@]}" "$src_pattern_red" "${dirs[@]}")
fi
report "compiler flags that allow value-changing float optimisations" \
  < <(find . \( -name 'build' -o -name 'build-*' -o -name .git -o -name _deps \) -prune -o \
        \( -name CMakeLists.txt -o -name '*.cmake' -o -name CMakePresets.json \) -type f -print0 |
      xargs -0 -r grep -HnE -- '-ffast-math|-ffp-contract=fast|-Ofast|-funsafe-math-optimizations')
[ $status -eq 0 ] && echo "lint_fp: clean"
exit $status
