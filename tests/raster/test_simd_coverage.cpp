// The block coverage kernel (raster/coverage_simd.h) on every SIMD target this build compiled and this
// CPU runs, and the scalar reference of "reference": the mask the fill rule gives pixel by pixel, for
// random edges of every size the guard band allows, edges through pixel centres (e = 0, where the bias
// decides), and every range of rows.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "raster/coverage_simd.h"
#include "raster/simd_targets.h"

namespace tessera {
namespace {

using detail::BlockEdges;

// Bit 8 y + x iff e_i(x, y) >= bias_i for every edge, y in the row range: the fill rule as stated.
uint64_t coverageByTheRule(const BlockEdges& b) {
  uint64_t mask = 0;
  for (int y = b.rowBegin; y < b.rowEnd; ++y)
    for (int x = 0; x < 8; ++x) {
      bool in = true;
      for (int i = 0; i < 3; ++i) in = in && b.e0[i] + x * b.dx[i] + y * b.dy[i] - b.bias[i] >= 0;
      if (in) mask |= uint64_t(1) << (8 * y + x);
    }
  return mask;
}

BlockEdges randomBlockEdges(std::mt19937_64& rng) {
  BlockEdges b;
  for (int i = 0; i < 3; ++i) {
    // Steps up to the guard band's 2^35 per pixel, small ones often, so that edges cross the block.
    const int stepBits = rng() % 3 ? 10 : 35;
    const int64_t range = int64_t(1) << stepBits;
    b.dx[i] = int64_t(rng() % uint64_t(2 * range)) - range;
    b.dy[i] = int64_t(rng() % uint64_t(2 * range)) - range;
    const int64_t spread = 8 * (range + 1);
    b.e0[i] = rng() % 8 == 0 ? int64_t(rng() >> 10) - (int64_t(1) << 53)  // far from the block: all or nothing
                             : int64_t(rng() % uint64_t(2 * spread)) - spread;
    // An edge through a pixel centre: e = 0 there, so the bias decides.
    if (rng() % 4 == 0) b.e0[i] = -(int64_t(rng() % 8) * b.dx[i] + int64_t(rng() % 8) * b.dy[i]);
    b.bias[i] = int64_t(rng() % 2);
  }
  b.rowBegin = rng() % 3 ? 0 : int32_t(rng() % 8);
  b.rowEnd = rng() % 3 ? 8 : b.rowBegin + int32_t(rng() % uint64_t(9 - b.rowBegin));
  b.setSteps();
  return b;
}

TEST(SimdCoverage, EveryTargetAndTheReferenceGiveTheFillRulesMask) {
  for (const std::string& target : simd::availableTargets()) {
    simd::forceTarget(target);
    const detail::BlockCoverageFn kernel = detail::blockCoverageKernel();
    ASSERT_NE(kernel, nullptr) << target;
    std::mt19937_64 rng(31);
    for (int iter = 0; iter < 20000; ++iter) {
      const BlockEdges b = randomBlockEdges(rng);
      ASSERT_EQ(kernel(b), coverageByTheRule(b)) << "target " << target << ", case " << iter;
    }
  }
  simd::forceTarget("best");
}

}  // namespace
}  // namespace tessera
