// The blend shortcuts of raster/fragops.h give writeFragment()'s generic bytes: the destination table
// holds the quotients i / 255.0, and the source-over form equals blend() + toUnorm8 for every
// destination byte and every kind of source value (in and out of [0, 1], ±0, ±Inf, NaN, denormals).
// A difference would change the bytes of any blended golden.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "raster/fragops.h"

namespace tessera::detail {
namespace {

// The generic path, as writeFragment() took it before the table: divide, blend(), convert.
void genericSourceOver(const float src[4], uint8_t texel[4]) {
  BlendState b;
  b.enabled = true;
  b.srcRgb = b.srcAlpha = BlendFactor::SrcAlpha;
  b.dstRgb = b.dstAlpha = BlendFactor::OneMinusSrcAlpha;
  volatile double denominator = 255.0;  // a run-time division
  double dst[4], out[4];
  for (int k = 0; k < 4; ++k) dst[k] = texel[k] / denominator;
  blend(b, true, src, dst, out);
  for (int k = 0; k < 4; ++k) texel[k] = toUnorm8(out[k]);
}

std::vector<float> sourceValues() {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<float> v = {0.0f, -0.0f, 1.0f, 0.5f, 0.25f, 0.75f, 1.0f / 255.0f, 254.0f / 255.0f, -1.0f, 2.0f,
                          inf, -inf, nan, std::numeric_limits<float>::denorm_min(), 1e-30f, 0.99999994f,
                          1.0000001f};
  for (int i = 0; i <= 255; ++i) {  // every unorm8 value and the points halfway between
    v.push_back(float(i) / 255.0f);
    v.push_back((float(i) + 0.5f) / 255.0f);
  }
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> unit(-0.1f, 1.1f);
  for (int i = 0; i < 200; ++i) v.push_back(unit(rng));
  return v;
}

}  // namespace

TEST(Blend, TheUnorm8TableHoldsTheRunTimeQuotientOfEveryByte) {
  volatile double denominator = 255.0;
  for (int i = 0; i < 256; ++i)
    EXPECT_EQ(std::bit_cast<uint64_t>(kUnorm8ToDouble.v[i]), std::bit_cast<uint64_t>(double(i) / denominator)) << i;
}

TEST(Blend, OnlyGlBlendFuncSrcAlphaOneMinusSrcAlphaWithAddIsSourceOver) {
  BlendState b;
  b.enabled = true;
  b.srcRgb = b.srcAlpha = BlendFactor::SrcAlpha;
  b.dstRgb = b.dstAlpha = BlendFactor::OneMinusSrcAlpha;
  EXPECT_TRUE(isSourceOver(b));
  BlendState off = b;
  off.enabled = false;
  EXPECT_FALSE(isSourceOver(off));
  BlendState sep = b;
  sep.dstAlpha = BlendFactor::One;  // glBlendFuncSeparate with another alpha factor
  EXPECT_FALSE(isSourceOver(sep));
  BlendState sub = b;
  sub.eqAlpha = BlendEq::Subtract;
  EXPECT_FALSE(isSourceOver(sub));
  BlendState rev = b;
  rev.srcRgb = BlendFactor::OneMinusSrcAlpha;
  EXPECT_FALSE(isSourceOver(rev));
}

TEST(Blend, SourceOverGivesTheGenericBytesForEveryDestinationByteAndSourceValue) {
  const std::vector<float> values = sourceValues();
  std::mt19937 rng(7);
  size_t cases = 0;
  for (float alpha : values)
    for (size_t i = 0; i < values.size(); i += 11) {
      const float src[4] = {values[i], values[(i + 1) % values.size()], values[(i + 7) % values.size()], alpha};
      for (int d = 0; d < 256; ++d) {
        // Every byte in every channel; the other channels vary so that a channel mix-up shows.
        const uint8_t dst[4] = {uint8_t(d), uint8_t(255 - d), uint8_t(d * 7), uint8_t(rng())};
        uint8_t fast[4], slow[4];
        std::memcpy(fast, dst, 4);
        std::memcpy(slow, dst, 4);
        blendSourceOverRgba8(src, fast);
        genericSourceOver(src, slow);
        ASSERT_EQ(std::memcmp(fast, slow, 4), 0)
            << "src " << src[0] << " " << src[1] << " " << src[2] << " " << src[3] << ", dst " << int(d) << ": fast "
            << int(fast[0]) << " " << int(fast[1]) << " " << int(fast[2]) << " " << int(fast[3]) << ", generic "
            << int(slow[0]) << " " << int(slow[1]) << " " << int(slow[2]) << " " << int(slow[3]);
        ++cases;
      }
    }
  EXPECT_GT(cases, size_t(10000000));
}

TEST(Blend, WriteFragmentOfAnRgba8TargetUsesTheGenericRulesForOtherForms) {
  // A form that is not source over still goes through blend(): ONE, ONE adds and clamps.
  BlendState b;
  b.enabled = true;
  b.srcRgb = b.srcAlpha = b.dstRgb = b.dstAlpha = BlendFactor::One;
  uint8_t texel[4] = {200, 100, 0, 255};
  const float src[4] = {0.25f, 0.25f, 0.25f, 0.25f};
  uint32_t bits[4];
  std::memcpy(bits, src, sizeof bits);
  writeFragment(Format::RGBA8, texel, bits, b);
  // 200/255 + 0.25 > 1 -> 255; (100/255 + 0.25) * 255 = 163.75 -> 164; 0.25 * 255 = 63.75 -> 64.
  EXPECT_EQ(texel[0], 255);
  EXPECT_EQ(texel[1], 164);
  EXPECT_EQ(texel[2], 64);
  EXPECT_EQ(texel[3], 255);
}

}  // namespace tessera::detail
