// The block coverage kernel on every Highway target and its scalar reference
// (raster/coverage_simd.h says what the mask is and why every target gives the same one). Highway
// compiles this file once per target; HWY_ONCE holds the dispatch and the reference.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "raster/coverage_simd.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "raster/coverage_simd.h"

HWY_BEFORE_NAMESPACE();
namespace tessera::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

uint64_t BlockCoverage(const BlockEdges& b) {
  const hn::CappedTag<int64_t, 8> d;  // a row of the block per vector on AVX-512, less elsewhere
  const size_t n = hn::Lanes(d);
  uint64_t mask = 0;
  for (int y = b.rowBegin; y < b.rowEnd; ++y) {
    for (size_t x = 0; x < 8; x += n) {
      // e_i(x, y) - bias_i = (e0_i + y dy_i) + (x dx_i - bias_i), exact.
      const auto d0 = hn::Add(hn::Set(d, b.e0[0] + int64_t(y) * b.dy[0]), hn::Load(d, b.stepX[0] + x));
      const auto d1 = hn::Add(hn::Set(d, b.e0[1] + int64_t(y) * b.dy[1]), hn::Load(d, b.stepX[1] + x));
      const auto d2 = hn::Add(hn::Set(d, b.e0[2] + int64_t(y) * b.dy[2]), hn::Load(d, b.stepX[2] + x));
      // Covered iff no difference is negative: the OR's sign bit is clear.
      const auto inside = hn::Not(hn::Lt(hn::Or(hn::Or(d0, d1), d2), hn::Zero(d)));
      uint8_t bits[8] = {};
      hn::StoreMaskBits(d, inside, bits);
      mask |= uint64_t(bits[0] & ((1u << n) - 1)) << (8 * y + int(x));
    }
  }
  return mask;
}

BlockCoverageFn GetBlockCoverage() { return &BlockCoverage; }

}  // namespace HWY_NAMESPACE
}  // namespace tessera::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE

#include "raster/simd_targets.h"

namespace tessera::detail {

HWY_EXPORT(GetBlockCoverage);

namespace {

// The reference: each pixel's three edge tests, as the fill rule states them.
uint64_t scalarBlockCoverage(const BlockEdges& b) {
  uint64_t mask = 0;
  for (int y = b.rowBegin; y < b.rowEnd; ++y)
    for (int x = 0; x < 8; ++x) {
      bool covered = true;
      for (int i = 0; i < 3; ++i) covered = covered && b.e0[i] + x * b.dx[i] + y * b.dy[i] >= b.bias[i];
      if (covered) mask |= uint64_t(1) << (8 * y + x);
    }
  return mask;
}

}  // namespace

BlockCoverageFn blockCoverageKernel() {
  return simd::kernelsOn() ? HWY_DYNAMIC_DISPATCH(GetBlockCoverage)() : &scalarBlockCoverage;
}

}  // namespace tessera::detail

#endif  // HWY_ONCE
