#!/usr/bin/env bash
# The floating-point lint (tools/lint_fp.sh) fails on each kind of banned construct and passes what is
# allowed: lint_fp_test.sh LINT WORKDIR
set -euo pipefail
lint=$1; work=$2/lint_fp
fail() { echo "FAIL: $*" >&2; exit 1; }
# The planted files must not outlive the test: a lint of the whole repository run later must not find them
# in a build directory it does not know to skip.
trap 'rm -rf "$work" "$work.out"' EXIT
# expect STATUS TEXT FILE CONTENT: a tree with FILE holding CONTENT makes the lint exit STATUS, naming TEXT.
expect() {
  local want=$1 text=$2 file=$3 content=$4
  rm -rf "$work"; mkdir -p "$work/$(dirname "$file")"
  printf '%s\n' "$content" > "$work/$file"
  local rc=0; bash "$lint" "$work" > "$work.out" 2>&1 || rc=$?
  [ "$rc" = "$want" ] || fail "$file: '$content': exit $rc, expected $want: $(cat "$work.out")"
  grep -qF -- "$text" "$work.out" || fail "$file: '$content': the output lacks '$text': $(cat "$work.out")"
}
expect 1 "fused multiply-add" raster/a.cpp 'float f(float a) { return std::fma(a, a, a); }'
expect 1 "fused multiply-add" mta/b.h 'float g(float a) { return fmaf(a, 2.0f, 1.0f); }'
expect 1 "fused multiply-add" verify/c.cpp 'auto v = hn::MulAdd(a, b, c);'
expect 1 "fused multiply-add" base/d.cpp '__m256 r = _mm256_fmadd_ps(a, b, c);'
expect 1 "approximate reciprocal" batching/e.cpp '__m128 r = _mm_rcp_ps(x);'
expect 1 "approximate reciprocal" rtta/f.cpp 'auto r = hn::ApproximateReciprocalSqrt(v);'
expect 1 "float horizontal reduction" raster/g.cpp 'float s = hn::GetLane(hn::SumOfLanes(d, v));'
expect 1 "float horizontal reduction" raster/h.cpp '__m128 s = _mm_hadd_ps(a, b);'
expect 1 "value-changing float" tools/CMakeLists.txt 'target_compile_options(x PRIVATE -ffast-math)'
expect 1 "value-changing float" cmake/flags.cmake 'set(CMAKE_CXX_FLAGS "${CMAKE_CXX_FLAGS} -ffp-contract=fast")'
# Allowed: integer multiply-add, FMA named in prose, a marked line, a directory outside the scanned ones.
expect 0 "clean" raster/i.cpp '__m128i r = _mm_madd_epi16(a, b);  // exact integer products'
expect 0 "clean" raster/j.glsl '// precise forbids fusing a multiply into an add (FMA)'
expect 0 "clean" raster/k.cpp 'auto n = hn::ReduceSum(di, counts);  // fp-lint: allow integer lanes, exact in any order'
expect 0 "clean" tools/bench/l.cpp 'double s = std::fma(a, b, c);'
echo "lint_fp_test: ok"
