// The inline bit counts of the rasterizer's counters (raster/rast.h: quadPixels for a quad's 4-bit
// mask, popcount64 for an 8x8 block's 64-bit mask) against std::popcount: the counters the stats
// JSON reports are sums of them.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>

#include "raster/rast.h"

namespace tessera::detail {
namespace {

TEST(MaskCounts, Popcount64CountsEveryMaskAsStdPopcountDoes) {
  std::mt19937_64 rng(64);
  for (int k = 0; k < 64; ++k) {
    const uint64_t one = uint64_t(1) << k;
    ASSERT_EQ(popcount64(one), 1u) << k;
    ASSERT_EQ(popcount64(~one), 63u) << k;
    ASSERT_EQ(popcount64(one - 1), uint64_t(k)) << k;
  }
  EXPECT_EQ(popcount64(0), 0u);
  EXPECT_EQ(popcount64(~uint64_t(0)), 64u);
  for (int i = 0; i < 100000; ++i) {
    uint64_t m = rng();
    if (i % 3 == 1) m &= rng();  // sparse masks
    if (i % 3 == 2) m |= rng();  // dense masks
    ASSERT_EQ(popcount64(m), uint64_t(std::popcount(m))) << std::hex << m;
  }
}

TEST(MaskCounts, QuadPixelsCountsTheFourBitsOfAQuadMask) {
  for (uint32_t m = 0; m < 64; ++m) EXPECT_EQ(quadPixels(m), uint64_t(std::popcount(m & 0xfu))) << m;
}

}  // namespace
}  // namespace tessera::detail
