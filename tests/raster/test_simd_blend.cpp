// The source-over blend kernel of the colour write (raster/fragops_simd.h) on every SIMD target this
// build compiled and this CPU runs: blendSourceOverRgba8's bytes (fragops.h, itself checked against the
// generic blend() in test_blend.cpp) for every destination byte in every channel and every kind of
// source value (random bit patterns, so NaNs, infinities, denormals and huge values; 0, 1, every unorm8
// value and the points halfway between; alphas that make a tie after the blend likely).
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "raster/fragops.h"
#include "raster/fragops_simd.h"
#include "raster/simd_targets.h"

namespace tessera {
namespace {

std::vector<float> blendSourceValues() {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<float> v = {0.0f, -0.0f, 1.0f, 0.5f, 0.25f, 0.75f, -1.0f, 2.0f, inf, -inf, nan,
                          std::numeric_limits<float>::denorm_min(), 0.99999994f, 1.0000001f};
  for (int i = 0; i <= 255; ++i) {
    v.push_back(float(i) / 255.0f);
    v.push_back((float(i) + 0.5f) / 255.0f);
  }
  std::mt19937 rng(11);
  for (int i = 0; i < 600; ++i) {
    const uint32_t bits = rng();
    float f;
    std::memcpy(&f, &bits, sizeof f);
    v.push_back(f);
  }
  std::uniform_real_distribution<float> unit(-0.1f, 1.1f);
  for (int i = 0; i < 600; ++i) v.push_back(unit(rng));
  return v;
}

TEST(SimdBlend, EveryTargetGivesBlendSourceOverRgba8sBytesForEveryDestinationByte) {
  const std::vector<float> values = blendSourceValues();
  std::mt19937 rng(12);
  // Quads: each pixel's source from the values (its alpha too), each destination byte 0..255 in every
  // channel of some pixel, the other bytes random.
  std::vector<float> src;
  std::vector<uint8_t> dst;
  for (size_t i = 0; i < values.size(); ++i)
    for (int d = 0; d < 256; d += 3) {
      for (int p = 0; p < 4; ++p) {
        for (int k = 0; k < 4; ++k) src.push_back(values[(i + size_t(5 * p + 7 * k) + size_t(d)) % values.size()]);
        for (int k = 0; k < 4; ++k) dst.push_back(k == p ? uint8_t(d) : uint8_t(rng()));
      }
    }
  std::vector<uint8_t> expect = dst;
  for (size_t q = 0; q < src.size() / 16; ++q)
    for (int p = 0; p < 4; ++p) detail::blendSourceOverRgba8(&src[16 * q + 4 * size_t(p)], &expect[16 * q + 4 * size_t(p)]);
  for (const std::string& target : simd::availableTargets()) {
    simd::forceTarget(target);
    const detail::BlendSourceOverQuadFn kernel = detail::blendSourceOverQuadKernel();
    std::vector<uint8_t> got = dst;
    for (size_t q = 0; q < src.size() / 16; ++q) kernel(&src[16 * q], &got[16 * q], &got[16 * q + 8]);
    for (size_t i = 0; i < got.size(); ++i)
      ASSERT_EQ(int(got[i]), int(expect[i])) << "target " << target << ", value " << i << ": source " << src[i]
                                             << ", alpha " << src[i | 3] << ", destination " << int(dst[i]);
  }
  simd::forceTarget("best");
  EXPECT_GT(src.size() / 16, size_t(100000));
}

}  // namespace
}  // namespace tessera
