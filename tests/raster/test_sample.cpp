// Texture sampling: wrap modes, NEAREST / LINEAR texel filters with 8-bit weights, LOD computation,
// mip level selection and blending, array layers, buffer fetches and incomplete textures.
// Every expected value is computed by hand from the rules in raster/sample.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "raster/sample.h"
#include "raster/sample_detail.h"
#include "tests/raster/texture_test_util.h"

namespace tessera {
namespace {

using testing::desc2D;
using testing::setF32;

void setU8(TextureData& t, uint32_t level, uint32_t layer, uint32_t x, uint32_t y, std::initializer_list<uint8_t> v) {
  std::copy(v.begin(), v.end(), t.texel(level, layer, x, y));
}
void setU32(TextureData& t, uint32_t level, uint32_t layer, uint32_t x, uint32_t y, uint32_t v) {
  std::memcpy(t.texel(level, layer, x, y), &v, sizeof v);
}
// Fills a whole level (all layers) of an R8 texture with one value.
void fillR8(TextureData& t, uint32_t level, uint8_t v) { std::fill(t.levels[level].begin(), t.levels[level].end(), v); }

TexUnit unit(const TextureData* t, const SamplerState& s) {
  TexUnit u;
  u.tex = t;
  u.sampler = SamplerQ::from(s);
  return u;
}

SamplerState sampler(Filter minF, Filter magF, Wrap wrap = Wrap::ClampToEdge) {
  SamplerState s;
  s.minFilter = minF;
  s.magFilter = magF;
  s.wrapS = s.wrapT = wrap;
  return s;
}

// The unorm8 conversion rule: an exact integer sum with total weight 2^24, converted once.
float unormSum(uint64_t sum) { return float(double(sum) / (255.0 * 16777216.0)); }
float unorm(uint32_t v) { return unormSum(uint64_t(v) << 24); }

std::array<float, 4> at(const TexUnit& u, float s, float t, int32_t lambda8, uint32_t layer = 0) {
  std::array<float, 4> out{};
  sampleAtLambda(u, s, t, layer, lambda8, out.data());
  return out;
}

// An 8x8 R8 texture with 4 levels, each level a constant: 0, 85, 170, 255.
TextureData constantLevelsR8() {
  TextureData t(desc2D(Format::R8, 8, 8, 4));
  const uint8_t values[4] = {0, 85, 170, 255};
  for (uint32_t l = 0; l < 4; ++l) fillR8(t, l, values[l]);
  return t;
}

// --- wrap ----------------------------------------------------------------------------------------

TEST(Wrap, RepeatWrapsNegativeCoordinatesIntoRange) {
  EXPECT_EQ(wrapCoord(Wrap::Repeat, -1, 4), 3);
  EXPECT_EQ(wrapCoord(Wrap::Repeat, -4, 4), 0);
  EXPECT_EQ(wrapCoord(Wrap::Repeat, -5, 4), 3);
  EXPECT_EQ(wrapCoord(Wrap::Repeat, 0, 4), 0);
  EXPECT_EQ(wrapCoord(Wrap::Repeat, 5, 4), 1);
  EXPECT_EQ(wrapCoord(Wrap::Repeat, -1, 3), 2);
  EXPECT_EQ(wrapCoord(Wrap::Repeat, 7, 3), 1);
}

TEST(Wrap, RepeatHandlesCoordinatesFarOutsideTheTexture) {
  EXPECT_EQ(wrapCoord(Wrap::Repeat, 1000000000003LL, 4), 3);
  EXPECT_EQ(wrapCoord(Wrap::Repeat, -1000000000003LL, 4), 1);
  EXPECT_EQ(wrapCoord(Wrap::Repeat, int64_t(1) << 60, 16384), 0);
  EXPECT_EQ(wrapCoord(Wrap::Repeat, -1, 2147483647), 2147483646);
  EXPECT_EQ(wrapCoord(Wrap::MirroredRepeat, -1, 2147483647), 0);
  EXPECT_EQ(wrapCoord(Wrap::MirroredRepeat, 2147483647, 2147483647), 2147483646);
}

TEST(Wrap, MirroredRepeatReflectsEveryOtherPeriod) {
  for (int32_t size : {1, 3, 4}) {
    for (int64_t i = -20; i <= 20; ++i) {
      // Independent formulation: within a period of 2 size, the first half runs forward and the
      // second half backward.
      const int64_t k = ((i % (2 * size)) + 2 * size) % (2 * size);
      const int64_t expected = k < size ? k : 2 * size - 1 - k;
      EXPECT_EQ(wrapCoord(Wrap::MirroredRepeat, i, size), expected) << "i=" << i << " size=" << size;
    }
  }
  EXPECT_EQ(wrapCoord(Wrap::MirroredRepeat, -1, 4), 0);
  EXPECT_EQ(wrapCoord(Wrap::MirroredRepeat, -5, 4), 3);
  EXPECT_EQ(wrapCoord(Wrap::MirroredRepeat, 4, 4), 3);
  EXPECT_EQ(wrapCoord(Wrap::MirroredRepeat, 8, 4), 0);
}

TEST(Wrap, ClampToEdgeClampsToTheFirstAndLastTexel) {
  EXPECT_EQ(wrapCoord(Wrap::ClampToEdge, -1, 4), 0);
  EXPECT_EQ(wrapCoord(Wrap::ClampToEdge, -100, 4), 0);
  EXPECT_EQ(wrapCoord(Wrap::ClampToEdge, 2, 4), 2);
  EXPECT_EQ(wrapCoord(Wrap::ClampToEdge, 4, 4), 3);
  EXPECT_EQ(wrapCoord(Wrap::ClampToEdge, 1LL << 40, 4), 3);
}

TEST(Wrap, ClampToBorderMarksEveryOutsideTexelAsBorder) {
  EXPECT_EQ(wrapCoord(Wrap::ClampToBorder, -1, 4), -1);
  EXPECT_EQ(wrapCoord(Wrap::ClampToBorder, -7, 4), -1);
  EXPECT_EQ(wrapCoord(Wrap::ClampToBorder, 0, 4), 0);
  EXPECT_EQ(wrapCoord(Wrap::ClampToBorder, 3, 4), 3);
  EXPECT_EQ(wrapCoord(Wrap::ClampToBorder, 4, 4), -1);
}

// A 4x1 R8 texture 10, 20, 30, 40 sampled with NEAREST at negative and large coordinates.
TEST(SampleWrap, RepeatNearestReadsNegativeCoordinatesFromTheOppositeEdge) {
  TextureData t(desc2D(Format::R8, 4, 1));
  for (uint32_t x = 0; x < 4; ++x) setU8(t, 0, 0, x, 0, {uint8_t(10 * (x + 1))});
  const TexUnit u = unit(&t, sampler(Filter::Nearest, Filter::Nearest, Wrap::Repeat));
  EXPECT_EQ(at(u, -0.1f, 0.5f, 0)[0], unorm(40));  // u = -0.4 -> -1 -> 3
  EXPECT_EQ(at(u, -0.3f, 0.5f, 0)[0], unorm(30));  // u = -1.2 -> -2 -> 2
  EXPECT_EQ(at(u, -1.1f, 0.5f, 0)[0], unorm(40));  // u = -4.4 -> -5 -> 3
  EXPECT_EQ(at(u, 1.3f, 0.5f, 0)[0], unorm(20));   // u = 5.2 -> 5 -> 1
}

TEST(SampleWrap, MirroredRepeatNearestReflectsNegativeCoordinates) {
  TextureData t(desc2D(Format::R8, 4, 1));
  for (uint32_t x = 0; x < 4; ++x) setU8(t, 0, 0, x, 0, {uint8_t(10 * (x + 1))});
  const TexUnit u = unit(&t, sampler(Filter::Nearest, Filter::Nearest, Wrap::MirroredRepeat));
  EXPECT_EQ(at(u, -0.1f, 0.5f, 0)[0], unorm(10));  // -1 -> 0
  EXPECT_EQ(at(u, -0.3f, 0.5f, 0)[0], unorm(20));  // -2 -> 1
  EXPECT_EQ(at(u, 1.1f, 0.5f, 0)[0], unorm(40));   // 4 -> 3
  EXPECT_EQ(at(u, 1.9f, 0.5f, 0)[0], unorm(10));   // 7 -> 0
}

TEST(SampleWrap, ClampToEdgeLinearAtTheEdgeReturnsTheEdgeTexel) {
  TextureData t(desc2D(Format::R8, 4, 1));
  for (uint32_t x = 0; x < 4; ++x) setU8(t, 0, 0, x, 0, {uint8_t(10 * (x + 1))});
  const TexUnit u = unit(&t, sampler(Filter::Linear, Filter::Linear, Wrap::ClampToEdge));
  EXPECT_EQ(at(u, 0.0f, 0.5f, 0)[0], unorm(10));  // i0 = -1 and i1 = 0 both clamp to 0
  EXPECT_EQ(at(u, -3.0f, 0.5f, 0)[0], unorm(10));
  EXPECT_EQ(at(u, 1.0f, 0.5f, 0)[0], unorm(40));
}

TEST(SampleWrap, RepeatLinearBlendsTheLastAndFirstTexelAcrossTheSeam) {
  TextureData t(desc2D(Format::R8, 4, 1));
  for (uint32_t x = 0; x < 4; ++x) setU8(t, 0, 0, x, 0, {uint8_t(10 * (x + 1))});
  const TexUnit u = unit(&t, sampler(Filter::Linear, Filter::Linear, Wrap::Repeat));
  // s = 0: u = 0, i0 = -1 -> 3 (40), i1 = 0 (10), alpha = 1/2; the row (beta = 0) has weight 256.
  EXPECT_EQ(at(u, 0.0f, 0.5f, 0)[0], unormSum((128ull * 40 + 128ull * 10) * 256 * 256));
}

TEST(SampleWrap, RepeatLinearOnANonPowerOfTwoWidthWrapsTheRightNeighbour) {
  TextureData t(desc2D(Format::R8, 3, 1));
  for (uint32_t x = 0; x < 3; ++x) setU8(t, 0, 0, x, 0, {uint8_t(10 * (x + 1))});
  const TexUnit u = unit(&t, sampler(Filter::Linear, Filter::Linear, Wrap::Repeat));
  // s = 1: u = 3, i0 = 2 (30), i1 = 3 -> 0 (10), alpha = 1/2.
  EXPECT_EQ(at(u, 1.0f, 0.5f, 0)[0], unormSum((128ull * 30 + 128ull * 10) << 16));
  // s = -2: u = -6, i0 = -7 -> 2 (30), i1 = -6 -> 0 (10).
  EXPECT_EQ(at(u, -2.0f, 0.5f, 0)[0], unormSum((128ull * 30 + 128ull * 10) << 16));
  // s = -1/6 (u = -0.5 up to float rounding of s): i0 = -1 -> 2, alpha ~ 0: texel 2.
  EXPECT_EQ(at(u, -1.0f / 6.0f, 0.5f, 0)[0], unorm(30));
}

TEST(SampleWrap, MirroredRepeatLinearAtTheEdgeReadsTheEdgeTexelTwice) {
  TextureData t(desc2D(Format::R8, 4, 1));
  for (uint32_t x = 0; x < 4; ++x) setU8(t, 0, 0, x, 0, {uint8_t(10 * (x + 1))});
  const TexUnit u = unit(&t, sampler(Filter::Linear, Filter::Linear, Wrap::MirroredRepeat));
  EXPECT_EQ(at(u, 0.0f, 0.5f, 0)[0], unorm(10));  // i0 = -1 -> 0, i1 = 0
  EXPECT_EQ(at(u, 1.0f, 0.5f, 0)[0], unorm(40));  // i0 = 3, i1 = 4 -> 3
  // s = -0.25: u = -1, i0 = -2 -> 1 (20), i1 = -1 -> 0 (10), alpha = 1/2.
  EXPECT_EQ(at(u, -0.25f, 0.5f, 0)[0], unormSum((128ull * 20 + 128ull * 10) << 16));
}

TEST(SampleWrap, ClampToBorderLinearBlendsTheBorderColourHalfway) {
  TextureData t(desc2D(Format::R8, 4, 1));
  for (uint32_t x = 0; x < 4; ++x) setU8(t, 0, 0, x, 0, {uint8_t(10 * (x + 1))});
  SamplerState s = sampler(Filter::Linear, Filter::Linear, Wrap::ClampToBorder);
  s.borderColor = {1.0f, 0.0f, 0.0f, 0.0f};
  const TexUnit u = unit(&t, s);
  // Horizontally: border (255) and texel 0 (10) with alpha = 1/2. Vertically (height 1, t = 0.5):
  // beta = 0, the row j0 = 0 has all the weight and the border row j1 = 1 has none.
  EXPECT_EQ(at(u, 0.0f, 0.5f, 0)[0], unormSum((128ull * 255 + 128ull * 10) * 256 * 256));
  // Vertically at the bottom edge (t = 0): half border, half texel.
  EXPECT_EQ(at(u, 0.375f, 0.0f, 0)[0], unormSum((128ull * 255 + 128ull * 20) * 256 * 256));
}

TEST(SampleWrap, ClampToBorderNearestReturnsTheBorderColourConvertedToTheFormat) {
  SamplerState s = sampler(Filter::Nearest, Filter::Nearest, Wrap::ClampToBorder);
  s.borderColor = {0.25f, 0.5f, 0.75f, 0.125f};
  {
    TextureData t(desc2D(Format::RGBA32F, 2, 2));
    const auto o = at(unit(&t, s), -0.5f, 0.5f, 0);
    EXPECT_EQ(o, (std::array<float, 4>{0.25f, 0.5f, 0.75f, 0.125f}));
  }
  {
    TextureData t(desc2D(Format::RG32F, 2, 2));
    const auto o = at(unit(&t, s), 0.5f, 1.5f, 0);
    EXPECT_EQ(o, (std::array<float, 4>{0.25f, 0.5f, 0.0f, 1.0f}));
  }
  {
    // unorm8: the border is quantized to 8 bits, round half to even: 0.5 * 255 = 127.5 -> 128,
    // 0.25 * 255 = 63.75 -> 64; R8 keeps only red and expands to (r, 0, 0, 1).
    TextureData t(desc2D(Format::R8, 2, 2));
    EXPECT_EQ(at(unit(&t, s), -0.5f, 0.5f, 0), (std::array<float, 4>{unorm(64), 0.0f, 0.0f, 1.0f}));
    SamplerState s2 = s;
    s2.borderColor = {0.5f, 2.0f, -1.0f, 1.0f};
    TextureData t4(desc2D(Format::RGBA8, 2, 2));
    EXPECT_EQ(at(unit(&t4, s2), -0.5f, 0.5f, 0), (std::array<float, 4>{unorm(128), 1.0f, 0.0f, 1.0f}));
  }
}

// --- NEAREST / LINEAR within one level ---------------------------------------------------------

// A 2x2 RGBA8 texture; red = 10, 20 (bottom row), 30, 40 (top row), other channels distinct.
TextureData twoByTwoRGBA8() {
  TextureData t(desc2D(Format::RGBA8, 2, 2));
  setU8(t, 0, 0, 0, 0, {10, 1, 100, 255});
  setU8(t, 0, 0, 1, 0, {20, 2, 110, 255});
  setU8(t, 0, 0, 0, 1, {30, 3, 120, 255});
  setU8(t, 0, 0, 1, 1, {40, 4, 130, 0});
  return t;
}

TEST(SampleFilter, NearestReturnsTheTexelContainingTheCoordinate) {
  const TextureData t = twoByTwoRGBA8();
  const TexUnit u = unit(&t, sampler(Filter::Nearest, Filter::Nearest));
  EXPECT_EQ(at(u, 0.25f, 0.25f, 0), (std::array<float, 4>{unorm(10), unorm(1), unorm(100), 1.0f}));
  EXPECT_EQ(at(u, 0.75f, 0.25f, 0), (std::array<float, 4>{unorm(20), unorm(2), unorm(110), 1.0f}));
  EXPECT_EQ(at(u, 0.25f, 0.75f, 0), (std::array<float, 4>{unorm(30), unorm(3), unorm(120), 1.0f}));
  EXPECT_EQ(at(u, 0.75f, 0.75f, 0), (std::array<float, 4>{unorm(40), unorm(4), unorm(130), 0.0f}));
  // floor(u): u = 0.999... stays in texel 0, u = 1 starts texel 1.
  EXPECT_EQ(at(u, 0.4999f, 0.1f, 0)[0], unorm(10));
  EXPECT_EQ(at(u, 0.5f, 0.1f, 0)[0], unorm(20));
}

TEST(SampleFilter, LinearAtTheCentreOfATwoByTwoTextureAveragesAllFourTexelsExactly) {
  const TextureData t = twoByTwoRGBA8();
  const TexUnit u = unit(&t, sampler(Filter::Linear, Filter::Linear));
  // u = v = 1: i0 = j0 = 0, alpha = beta = 1/2: each tap weighs 128 * 128, times the level's 256.
  const uint64_t w = 128ull * 128 * 256;
  const auto o = at(u, 0.5f, 0.5f, 0);
  EXPECT_EQ(o[0], unormSum(w * (10 + 20 + 30 + 40)));
  EXPECT_EQ(o[1], unormSum(w * (1 + 2 + 3 + 4)));
  EXPECT_EQ(o[2], unormSum(w * (100 + 110 + 120 + 130)));
  EXPECT_EQ(o[3], unormSum(w * (255 * 3)));
  EXPECT_EQ(o[0], float(25.0 / 255.0));  // the same rational, converted once
}

TEST(SampleFilter, LinearWeightsAreRoundedToEightBitsHalfToEven) {
  // 2x1 texture 0, 255 with CLAMP_TO_EDGE; at height 1 and t = 0.5 beta is 0. The filtered value is
  // alpha8 / 256 exactly, where alpha8 = round_half_even(256 u) - 128 (u = 2 s).
  TextureData t(desc2D(Format::R8, 2, 1));
  setU8(t, 0, 0, 1, 0, {255});
  const TexUnit u = unit(&t, sampler(Filter::Linear, Filter::Linear));
  const struct {
    double u256;
    int alpha8;
  } cases[] = {{128.5, 0}, {129.5, 2}, {130.5, 2}, {131.5, 4}, {129.25, 1}, {129.75, 2}, {383.25, 255}, {383.5, 256}};
  for (const auto& c : cases) {
    const float s = float(c.u256 / 512.0);  // exact
    EXPECT_EQ(at(u, s, 0.5f, 0)[0], float(c.alpha8 / 256.0)) << "256u = " << c.u256;
    EXPECT_EQ(at(u, s, 0.5f, 0)[0], unormSum(uint64_t(c.alpha8) * 255 * 256 * 256)) << "256u = " << c.u256;
  }
  // 256u = 383.5 -> 384: alpha rounds up to 256, i.e. all the weight on texel 1 (above: 1.0).
}

TEST(SampleFilter, LinearTwoDimensionalWeightsAreProductsOfEightBitWeights) {
  TextureData t(desc2D(Format::R8, 2, 2));
  setU8(t, 0, 0, 0, 0, {0});
  setU8(t, 0, 0, 1, 0, {100});
  setU8(t, 0, 0, 0, 1, {50});
  setU8(t, 0, 0, 1, 1, {200});
  const TexUnit u = unit(&t, sampler(Filter::Linear, Filter::Linear));
  // u = 0.75: alpha = 64; v = 1.25: beta = 192.
  const uint64_t a = 64, b = 192, na = 256 - a, nb = 256 - b;
  const uint64_t sum = (na * nb * 0 + a * nb * 100 + na * b * 50 + a * b * 200) * 256;
  EXPECT_EQ(at(u, 0.375f, 0.625f, 0)[0], unormSum(sum));
  EXPECT_EQ(sum, 4710400ull * 256);
}

// --- LOD, magnification / minification, mip selection -------------------------------------------

TEST(SampleLod, MagnificationFilterAppliesUpToAndIncludingLambdaZero) {
  TextureData t(desc2D(Format::R8, 2, 1));
  setU8(t, 0, 0, 1, 0, {255});
  const TexUnit u = unit(&t, sampler(Filter::Linear, Filter::Nearest));
  // s = 0.375: NEAREST reads texel 0 (0); LINEAR has alpha = 64 -> 0.25.
  EXPECT_EQ(at(u, 0.375f, 0.5f, -1000)[0], 0.0f);
  EXPECT_EQ(at(u, 0.375f, 0.5f, 0)[0], 0.0f);
  EXPECT_EQ(at(u, 0.375f, 0.5f, 1)[0], 0.25f);
  const TexUnit v = unit(&t, sampler(Filter::Nearest, Filter::Linear));
  EXPECT_EQ(at(v, 0.375f, 0.5f, 0)[0], 0.25f);
  EXPECT_EQ(at(v, 0.375f, 0.5f, 1)[0], 0.0f);
}

TEST(SampleLod, MagnificationAlwaysReadsTheBaseLevel) {
  const TextureData t = constantLevelsR8();
  const TexUnit u = unit(&t, sampler(Filter::LinearMipmapLinear, Filter::Linear));
  EXPECT_EQ(at(u, 0.3f, 0.6f, 0)[0], 0.0f);
  EXPECT_EQ(at(u, 0.3f, 0.6f, -5000)[0], 0.0f);
  EXPECT_EQ(at(u, 0.3f, 0.6f, kLodMinusInf)[0], 0.0f);
}

TEST(SampleMip, NonMipmappedMinFiltersReadTheBaseLevel) {
  const TextureData t = constantLevelsR8();
  EXPECT_EQ(at(unit(&t, sampler(Filter::Linear, Filter::Linear)), 0.3f, 0.6f, 2000)[0], 0.0f);
  EXPECT_EQ(at(unit(&t, sampler(Filter::Nearest, Filter::Linear)), 0.3f, 0.6f, 2000)[0], 0.0f);
}

TEST(SampleMip, NearestMipmapSelectsLevelZeroUpToLambdaOneHalf) {
  const TextureData t = constantLevelsR8();
  const TexUnit u = unit(&t, sampler(Filter::NearestMipmapNearest, Filter::Nearest));
  EXPECT_EQ(at(u, 0.3f, 0.6f, 1)[0], unorm(0));
  EXPECT_EQ(at(u, 0.3f, 0.6f, 128)[0], unorm(0));
  EXPECT_EQ(at(u, 0.3f, 0.6f, 129)[0], unorm(85));
}

TEST(SampleMip, NearestMipmapRoundsLambdaKPlusOneHalfDownToLevelK) {
  const TextureData t = constantLevelsR8();
  const TexUnit u = unit(&t, sampler(Filter::LinearMipmapNearest, Filter::Linear));
  // d = ceil(lambda + 1/2) - 1.
  EXPECT_EQ(at(u, 0.3f, 0.6f, 383)[0], unorm(85));   // 1.496
  EXPECT_EQ(at(u, 0.3f, 0.6f, 384)[0], unorm(85));   // 1.5 -> 1
  EXPECT_EQ(at(u, 0.3f, 0.6f, 385)[0], unorm(170));  // 1.504 -> 2
  EXPECT_EQ(at(u, 0.3f, 0.6f, 640)[0], unorm(170));  // 2.5 -> 2
  EXPECT_EQ(at(u, 0.3f, 0.6f, 641)[0], unorm(255));  // 2.504 -> 3
}

TEST(SampleMip, NearestMipmapClampsToTheLastLevel) {
  const TextureData t = constantLevelsR8();
  const TexUnit u = unit(&t, sampler(Filter::NearestMipmapNearest, Filter::Nearest));
  EXPECT_EQ(at(u, 0.3f, 0.6f, 100000)[0], unorm(255));
  EXPECT_EQ(at(u, 0.3f, 0.6f, kLodMax)[0], unorm(255));
}

TEST(SampleMip, LinearMipmapBlendsAdjacentLevelsWithTheEightFractionBitsOfLambda) {
  const TextureData t = constantLevelsR8();
  const TexUnit u = unit(&t, sampler(Filter::NearestMipmapLinear, Filter::Nearest));
  // lambda = 1.25: levels 1 and 2 with weights 192 and 64 (of 256); a NEAREST tap weighs 2^16.
  EXPECT_EQ(at(u, 0.3f, 0.6f, 320)[0], unormSum((192ull * 85 + 64ull * 170) << 16));
  // lambda = 1/256: level 0 with 255, level 1 with 1.
  EXPECT_EQ(at(u, 0.3f, 0.6f, 1)[0], unormSum((255ull * 0 + 1ull * 85) << 16));
  // Integral lambda: exactly one level.
  EXPECT_EQ(at(u, 0.3f, 0.6f, 256)[0], unorm(85));
  EXPECT_EQ(at(u, 0.3f, 0.6f, 512)[0], unorm(170));
}

TEST(SampleMip, LinearMipmapClampsBothLevelsToTheLastLevel) {
  const TextureData t = constantLevelsR8();
  const TexUnit u = unit(&t, sampler(Filter::LinearMipmapLinear, Filter::Linear));
  EXPECT_EQ(at(u, 0.3f, 0.6f, 2 * 256 + 128)[0], unormSum((128ull * 170 + 128ull * 255) << 16));
  EXPECT_EQ(at(u, 0.3f, 0.6f, 3 * 256 + 128)[0], 1.0f);
  EXPECT_EQ(at(u, 0.3f, 0.6f, 40 * 256 + 7)[0], 1.0f);
}

TEST(SampleMip, MipmapFilterOnASingleLevelTextureSamplesLevelZero) {
  TextureData t(desc2D(Format::R8, 4, 4, 1));
  fillR8(t, 0, 77);
  EXPECT_EQ(at(unit(&t, sampler(Filter::LinearMipmapLinear, Filter::Linear)), 0.3f, 0.6f, 900)[0], unorm(77));
  EXPECT_EQ(at(unit(&t, sampler(Filter::NearestMipmapNearest, Filter::Nearest)), 0.3f, 0.6f, 900)[0], unorm(77));
}

TEST(SampleMip, TrilinearCombinesSubtexelAndMipWeightsInExactIntegers) {
  // Level 0 (4x4): v0 = 10 x + 40 y + 5; level 1 (2x2): v1 = 7 x + 90 y + 11. CLAMP_TO_EDGE.
  TextureData t(desc2D(Format::R8, 4, 4, 2));
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 4; ++x) setU8(t, 0, 0, x, y, {uint8_t(10 * x + 40 * y + 5)});
  for (uint32_t y = 0; y < 2; ++y)
    for (uint32_t x = 0; x < 2; ++x) setU8(t, 1, 0, x, y, {uint8_t(7 * x + 90 * y + 11)});
  const TexUnit u = unit(&t, sampler(Filter::LinearMipmapLinear, Filter::Linear));
  // s = 0.3, t = 0.7.
  // Level 0: u = 1.2 -> round(307.2) - 128 = 179: i0 = 0, alpha = 179;
  //          v = 2.8 -> round(716.8) - 128 = 589: j0 = 2, beta = 77. Texels 85, 95, 125, 135.
  const uint64_t l0 = 77ull * 179 * 85 + 179ull * 179 * 95 + 77ull * 77 * 125 + 179ull * 77 * 135;
  // Level 1: u = 0.6 -> round(153.6) - 128 = 26: i0 = 0, alpha = 26;
  //          v = 1.4 -> round(358.4) - 128 = 230: j0 = 0, beta = 230. Texels 11, 18, 101, 108.
  const uint64_t l1 = 230ull * 26 * 11 + 26ull * 26 * 18 + 230ull * 230 * 101 + 26ull * 230 * 108;
  // lambda = 96/256: weights 160 and 96.
  EXPECT_EQ(at(u, 0.3f, 0.7f, 96)[0], unormSum(160 * l0 + 96 * l1));
}

TEST(SampleLod, TwoTimesMinificationGivesLambdaExactlyOne) {
  const SamplerQ q = SamplerQ::from(SamplerState{});
  EXPECT_EQ(computeLambda(2, 0, 0, 2, q, 0.0f), 256);
  EXPECT_EQ(computeLambda(2, 0, 0, 0, q, 0.0f), 256);
  EXPECT_EQ(computeLambda(0, 2, 0, 0, q, 0.0f), 256);
  EXPECT_EQ(computeLambda(1, 0, 0, 1, q, 0.0f), 0);
  EXPECT_EQ(computeLambda(8, 0, 0, 0, q, 0.0f), 768);
  EXPECT_EQ(computeLambda(0.5, 0, 0, 0.5, q, 0.0f), -256);
}

TEST(SampleLod, LambdaIsTheLogOfTheLongerDerivativeVector) {
  const SamplerQ q = SamplerQ::from(SamplerState{});
  // rho = max(|(3, 4)|, |(0, 1)|) = 5; 256 log2 5 = 594.39 -> 594.
  EXPECT_EQ(computeLambda(3, 4, 0, 1, q, 0.0f), 594);
  EXPECT_EQ(computeLambda(0, 1, 4, -3, q, 0.0f), 594);
  // rho = sqrt(2): lambda = 1/2 exactly.
  EXPECT_EQ(computeLambda(1, 1, 0, 0, q, 0.0f), 128);
}

TEST(SampleLod, QuadDerivativesAreCoarseDifferencesScaledByTheBaseSize) {
  // 8x8, levels 0, 85, 170, 255. A quad whose s and t step by 2 texels per pixel: lambda = 1.
  const TextureData t = constantLevelsR8();
  const TexUnit u = unit(&t, sampler(Filter::LinearMipmapLinear, Filter::Linear));
  const float s[4] = {0.25f, 0.5f, 0.25f, 0.9f};  // pixel 3 is not part of the coarse derivatives
  const float tt[4] = {0.25f, 0.25f, 0.5f, 0.1f};
  float out[4][4];
  sampleQuad2D(u, s, tt, 0.0f, out);
  for (int p = 0; p < 4; ++p) EXPECT_EQ(out[p][0], unorm(85)) << p;
  // Four texels per pixel: lambda = 2.
  const float s4[4] = {0.0f, 0.5f, 0.0f, 0.5f};
  const float t4[4] = {0.0f, 0.0f, 0.5f, 0.5f};
  sampleQuad2D(u, s4, t4, 0.0f, out);
  for (int p = 0; p < 4; ++p) EXPECT_EQ(out[p][0], unorm(170)) << p;
  // The shader bias shifts it: lambda = 2 - 0.5 = 1.5.
  sampleQuad2D(u, s4, t4, -0.5f, out);
  for (int p = 0; p < 4; ++p) EXPECT_EQ(out[p][0], unormSum((128ull * 85 + 128ull * 170) << 16)) << p;
}

TEST(SampleLod, EachQuadPixelMatchesASingleLookupAtTheQuadLambda) {
  TextureData t(desc2D(Format::RGBA8, 16, 8, 3));
  for (uint32_t l = 0; l < 3; ++l)
    for (size_t i = 0; i < t.levels[l].size(); ++i) t.levels[l][i] = uint8_t((i * 37 + l * 101) % 251);
  const TexUnit u = unit(&t, sampler(Filter::LinearMipmapLinear, Filter::Linear, Wrap::Repeat));
  const float s[4] = {0.11f, 0.21f, 0.13f, 0.27f};
  const float tt[4] = {0.31f, 0.33f, 0.47f, 0.5f};
  const int32_t lambda = computeLambda((double(s[1]) - s[0]) * 16, (double(tt[1]) - tt[0]) * 8,
                                       (double(s[2]) - s[0]) * 16, (double(tt[2]) - tt[0]) * 8, u.sampler, 0.25f);
  EXPECT_GT(lambda, 0);
  float out[4][4];
  sampleQuad2D(u, s, tt, 0.25f, out);
  for (int p = 0; p < 4; ++p) {
    const auto one = at(u, s[p], tt[p], lambda);
    for (int c = 0; c < 4; ++c) EXPECT_EQ(out[p][c], one[size_t(c)]) << p << "," << c;
  }
}

TEST(SampleLod, SamplerAndShaderBiasAddAndAreClampedToSixteen) {
  SamplerState s;
  s.lodBias = 1.0f;
  EXPECT_EQ(computeLambda(2, 0, 0, 2, SamplerQ::from(s), 0.5f), 256 + 256 + 128);
  s.lodBias = 20.0f;
  EXPECT_EQ(computeLambda(2, 0, 0, 2, SamplerQ::from(s), 0.0f), 256 + 16 * 256);
  EXPECT_EQ(computeLambda(2, 0, 0, 2, SamplerQ::from(s), -10.0f), 256 + 10 * 256);
  s.lodBias = -20.0f;
  EXPECT_EQ(computeLambda(2, 0, 0, 2, SamplerQ::from(s), -20.0f), 256 - 16 * 256);
}

TEST(SampleLod, MinAndMaxLodClampLambda) {
  SamplerState s;
  s.minLod = 2.0f;
  EXPECT_EQ(computeLambda(1, 0, 0, 1, SamplerQ::from(s), 0.0f), 512);
  EXPECT_EQ(computeLambda(16, 0, 0, 1, SamplerQ::from(s), 0.0f), 1024);
  s.minLod = -1000.0f;
  s.maxLod = 0.75f;
  EXPECT_EQ(computeLambda(32, 0, 0, 0, SamplerQ::from(s), 0.0f), 192);
  // The clamp applies after the bias.
  s.lodBias = 4.0f;
  EXPECT_EQ(computeLambda(0.25, 0, 0, 0, SamplerQ::from(s), 0.0f), 192);
  s.maxLod = 4.0f;
  EXPECT_EQ(computeLambda(0.25, 0, 0, 0, SamplerQ::from(s), 0.0f), 512);
}

TEST(SampleLod, LodParametersAreQuantizedToEightBitsHalfToEven) {
  SamplerState s;
  s.lodBias = 1.0f / 512.0f;  // 0.5 -> 0
  EXPECT_EQ(SamplerQ::from(s).bias8, 0);
  s.lodBias = 3.0f / 512.0f;  // 1.5 -> 2
  EXPECT_EQ(SamplerQ::from(s).bias8, 2);
  s.lodBias = -3.0f / 512.0f;  // -1.5 -> -2
  EXPECT_EQ(SamplerQ::from(s).bias8, -2);
  s.lodBias = 0.3f;  // 76.8 -> 77
  EXPECT_EQ(SamplerQ::from(s).bias8, 77);
  s.minLod = 1e30f;
  s.maxLod = -1e30f;
  EXPECT_EQ(SamplerQ::from(s).minLod8, kLodMax);
  EXPECT_EQ(SamplerQ::from(s).maxLod8, kLodMinusInf);
  const SamplerQ d = SamplerQ::from(SamplerState{});
  EXPECT_EQ(d.minLod8, -256000);
  EXPECT_EQ(d.maxLod8, 256000);
  EXPECT_EQ(d.bias8, 0);
  // A shader bias is quantized the same way: 1/512 is a tie that rounds to 0.
  EXPECT_EQ(computeLambda(2, 0, 0, 2, d, 1.0f / 512.0f), 256);
  EXPECT_EQ(computeLambda(2, 0, 0, 2, d, 3.0f / 512.0f), 258);
}

TEST(SampleLod, ZeroDerivativesGiveMinusInfinityLambda) {
  SamplerState s;
  s.minLod = -1e30f;
  EXPECT_EQ(computeLambda(0, 0, 0, 0, SamplerQ::from(s), 0.0f), kLodMinusInf);
  EXPECT_EQ(computeLambda(0, -0.0, 0, 0, SamplerQ::from(s), 0.0f), kLodMinusInf);
  // With the default MIN_LOD the clamp lifts it to -1000.
  EXPECT_EQ(computeLambda(0, 0, 0, 0, SamplerQ::from(SamplerState{}), 0.0f), -256000);
  // A bias cannot turn rho = 0 into minification.
  EXPECT_LT(computeLambda(0, 0, 0, 0, SamplerQ::from(s), 16.0f), 0);
}

TEST(SampleLod, NanOrInfiniteDerivativesGiveTheMostMinifiedLambda) {
  SamplerState s;
  s.maxLod = 1e30f;
  const SamplerQ q = SamplerQ::from(s);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(computeLambda(nan, 0, 0, 0, q, 0.0f), kLodMax);
  EXPECT_EQ(computeLambda(0, 0, 0, nan, q, 0.0f), kLodMax);
  EXPECT_EQ(computeLambda(0, -inf, 0, 0, q, 0.0f), kLodMax);
  EXPECT_EQ(computeLambda(1e300, 0, 0, 0, q, 0.0f), kLodMax);  // rho^2 overflows
  EXPECT_EQ(computeLambda(nan, 0, 0, 0, SamplerQ::from(SamplerState{}), 0.0f), 256000);
}

TEST(SampleLod, NanQuadCoordinatesSampleTheLastLevel) {
  const TextureData t = constantLevelsR8();
  const TexUnit u = unit(&t, sampler(Filter::LinearMipmapLinear, Filter::Linear, Wrap::Repeat));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float s[4] = {0.1f, nan, 0.1f, 0.2f};
  const float tt[4] = {0.1f, 0.1f, 0.2f, 0.2f};
  float out[4][4];
  sampleQuad2D(u, s, tt, 0.0f, out);
  for (int p = 0; p < 4; ++p) EXPECT_EQ(out[p][0], 1.0f) << p;
}

// --- log2Fixed -----------------------------------------------------------------------------------

TEST(Log2Fixed, IsExactOnPowersOfTwo) {
  for (int e = -1074; e <= 1023; ++e) {
    const double x = std::ldexp(1.0, e);
    for (int fb : {0, 1, 7, 8, 16, 24}) EXPECT_EQ(log2Fixed(x, fb), int64_t(e) * (int64_t(1) << fb)) << e << " " << fb;
  }
}

TEST(Log2Fixed, RoundsKnownValuesToNearest) {
  EXPECT_EQ(log2Fixed(3.0, 8), 406);       // 405.75
  EXPECT_EQ(log2Fixed(5.0, 7), 297);       // 297.21
  EXPECT_EQ(log2Fixed(0.75, 8), -106);     // -106.25
  EXPECT_EQ(log2Fixed(1.5, 8), 150);       // 149.75
  EXPECT_EQ(log2Fixed(10.0, 0), 3);        // 3.32
  EXPECT_EQ(log2Fixed(12.0, 0), 4);        // 3.58
  EXPECT_EQ(log2Fixed(1.5, 24), 9814042);  // floor(2^24 log2 1.5) = floor(9814042.23)
}

TEST(Log2Fixed, TheThresholdTableGivesTheLoopsBitsAtEveryThresholdAndBetween) {
  using sample_detail::log2BitsLoop;
  using sample_detail::log2BitsTable;
  constexpr uint64_t kOne = uint64_t(1) << 62, kTwo = uint64_t(1) << 63;
  // Every step of the table: the least mantissa with loop value k (found here by the loop, with no
  // table) and its neighbours on both sides.
  std::vector<uint64_t> ms = {kOne, kOne + 1, kTwo - 1, kTwo - 2};
  for (int k = 1; k < 256; ++k) {
    uint64_t lo = kOne, hi = kTwo - 1;
    while (lo < hi) {
      const uint64_t mid = lo + (hi - lo) / 2;
      if (log2BitsLoop(mid, 8) >= k) {
        hi = mid;
      } else {
        lo = mid + 1;
      }
    }
    for (uint64_t d = 0; d < 4; ++d) ms.insert(ms.end(), {lo + d, lo - 1 - d});
  }
  // The edges of the table's 4096 buckets (sample_lod.cpp: a bucket's first mantissa and the last of
  // the one before).
  for (uint64_t b = 0; b < 4096; ++b) ms.insert(ms.end(), {kOne + (b << 50), kOne + (b << 50) + 1, kTwo - 1 - (b << 50)});
  std::mt19937_64 rng(8);
  for (int i = 0; i < 2000000; ++i) ms.push_back(kOne | (rng() & (kOne - 1)));
  for (uint64_t m : ms) ASSERT_EQ(log2BitsTable(m), log2BitsLoop(m, 8)) << std::hex << m;
}

TEST(Log2Fixed, LambdaFromRho2MatchesLog2FixedOverTheWholeDoubleRange) {
  std::mt19937_64 rng(9);
  std::vector<double> xs = {std::numeric_limits<double>::min(), std::numeric_limits<double>::max(),
                            std::numeric_limits<double>::denorm_min(), 1.0, 2.0, 0.5, 3.0};
  for (int i = 0; i < 1000000; ++i) {
    // Random finite positive doubles over every exponent (subnormals included).
    const uint64_t bits = rng() & ~(uint64_t(1) << 63);
    double x;
    std::memcpy(&x, &bits, sizeof x);
    if (std::isfinite(x) && x > 0.0) xs.push_back(x);
  }
  for (double x : xs) ASSERT_EQ(sample_detail::lambdaBaseFromRho2(x), int32_t(log2Fixed(x, 7))) << x;
}

TEST(Log2Fixed, HandlesSubnormalInputs) {
  const double x = std::ldexp(1.5, -1070);  // subnormal
  ASSERT_LT(x, std::numeric_limits<double>::min());
  EXPECT_EQ(log2Fixed(x, 8), -1070 * 256 + 150);
  EXPECT_EQ(log2Fixed(std::numeric_limits<double>::denorm_min(), 8), -1074 * 256);
}

TEST(Log2Fixed, IsMonotonic) {
  std::vector<double> xs;
  for (double x = 1e-6; x < 1e6; x *= 1.0007) xs.push_back(x);
  // Dense runs around 1 and around a power of two.
  for (double c : {1.0, 1024.0, 0.125}) {
    double lo = c, hi = c;
    for (int i = 0; i < 2000; ++i) {
      lo = std::nextafter(lo, 0.0);
      hi = std::nextafter(hi, 2.0 * c);
      xs.push_back(lo);
      xs.push_back(hi);
    }
  }
  std::sort(xs.begin(), xs.end());
  for (int fb : {7, 8, 24}) {
    int64_t prev = std::numeric_limits<int64_t>::min();
    for (double x : xs) {
      const int64_t v = log2Fixed(x, fb);
      ASSERT_GE(v, prev) << "x = " << x << " fb = " << fb;
      prev = v;
    }
  }
}

TEST(Log2Fixed, MatchesStdLog2WithinOneLsb) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> mant(1.0, 2.0);
  std::uniform_int_distribution<int> expo(-60, 60);
  int exact = 0, total = 0;
  for (int i = 0; i < 200000; ++i) {
    const double x = std::ldexp(mant(rng), expo(rng));
    for (int fb : {7, 8}) {
      const double ref = std::floor(std::ldexp(std::log2(x), fb) + 0.5);
      const int64_t v = log2Fixed(x, fb);
      ASSERT_LE(std::fabs(double(v) - ref), 1.0) << "x = " << x << " fb = " << fb;
      exact += double(v) == ref;
      ++total;
    }
  }
  // log2Fixed is correctly rounded; std::log2's last-ulp error can only disagree at near-ties.
  EXPECT_GE(exact, total - total / 10000);
}

// --- arrays --------------------------------------------------------------------------------------

TEST(ArrayLayer, LayerIsFloorOfRPlusOneHalfClampedToTheLayerRange) {
  EXPECT_EQ(selectLayer(0.0f, 4), 0u);
  EXPECT_EQ(selectLayer(0.49f, 4), 0u);
  EXPECT_EQ(selectLayer(1.2f, 4), 1u);
  EXPECT_EQ(selectLayer(2.51f, 4), 3u);
  EXPECT_EQ(selectLayer(3.7f, 4), 3u);
  EXPECT_EQ(selectLayer(100.0f, 4), 3u);
  EXPECT_EQ(selectLayer(-0.49f, 4), 0u);
  EXPECT_EQ(selectLayer(-0.5f, 4), 0u);
  EXPECT_EQ(selectLayer(-7.0f, 4), 0u);
  EXPECT_EQ(selectLayer(5.0f, 1), 0u);
  EXPECT_EQ(selectLayer(std::numeric_limits<float>::quiet_NaN(), 4), 0u);
  EXPECT_EQ(selectLayer(std::numeric_limits<float>::infinity(), 4), 3u);
  EXPECT_EQ(selectLayer(-std::numeric_limits<float>::infinity(), 4), 0u);
  EXPECT_EQ(selectLayer(1e30f, 2048), 2047u);
}

TEST(ArrayLayer, RExactlyHalfwaySelectsTheUpperLayer) {
  // floor(k + 1/2 + 1/2) = k + 1 (llvmpipe's round-half-even would pick the even neighbour).
  EXPECT_EQ(selectLayer(0.5f, 8), 1u);
  EXPECT_EQ(selectLayer(1.5f, 8), 2u);
  EXPECT_EQ(selectLayer(2.5f, 8), 3u);
  EXPECT_EQ(selectLayer(6.5f, 8), 7u);
  EXPECT_EQ(selectLayer(7.5f, 8), 7u);  // clamped
}

TEST(ArrayLayer, QuadLookupsReadEachPixelsOwnLayerAndLayersAreNotPartOfLambda) {
  // 4x4 array with 3 layers and 2 levels: layer k level 0 = 10 (k + 1), level 1 = 100 + k.
  TextureData t(desc2D(Format::R8, 4, 4, 2, 3));
  for (uint32_t k = 0; k < 3; ++k)
    for (uint32_t y = 0; y < 4; ++y)
      for (uint32_t x = 0; x < 4; ++x) {
        setU8(t, 0, k, x, y, {uint8_t(10 * (k + 1))});
        if (x < 2 && y < 2) setU8(t, 1, k, x, y, {uint8_t(100 + k)});
      }
  const TexUnit u = unit(&t, sampler(Filter::NearestMipmapNearest, Filter::Nearest));
  // s, t step by a quarter texel: magnification, whatever r does.
  const float s[4] = {0.5f, 0.5625f, 0.5f, 0.5625f};
  const float tt[4] = {0.5f, 0.5f, 0.5625f, 0.5625f};
  const float r[4] = {0.0f, 1.2f, 2.6f, -3.0f};
  float out[4][4];
  sampleQuad2DArray(u, s, tt, r, 0.0f, out);
  EXPECT_EQ(out[0][0], unorm(10));
  EXPECT_EQ(out[1][0], unorm(20));
  EXPECT_EQ(out[2][0], unorm(30));
  EXPECT_EQ(out[3][0], unorm(10));
  // Two texels per pixel: level 1, still per-pixel layers.
  const float s2[4] = {0.0f, 0.5f, 0.0f, 0.5f};
  const float t2[4] = {0.0f, 0.0f, 0.5f, 0.5f};
  sampleQuad2DArray(u, s2, t2, r, 0.0f, out);
  EXPECT_EQ(out[0][0], unorm(100));
  EXPECT_EQ(out[1][0], unorm(101));
  EXPECT_EQ(out[2][0], unorm(102));
  EXPECT_EQ(out[3][0], unorm(100));
}

TEST(SampleGrad, ExplicitDerivativesSelectTheLevelAndTheSamplerBiasStillApplies) {
  TextureData t(desc2D(Format::R8, 8, 8, 4, 2));
  const uint8_t values[4] = {0, 85, 170, 255};
  for (uint32_t l = 0; l < 4; ++l) fillR8(t, l, values[l]);
  SamplerState smp = sampler(Filter::LinearMipmapLinear, Filter::Linear);
  const float s[4] = {0.1f, 0.2f, 0.3f, 0.4f};
  const float tt[4] = {0.4f, 0.3f, 0.2f, 0.1f};
  const float r[4] = {0.0f, 1.0f, 0.0f, 1.0f};
  float out[4][4];
  sampleGrad2DArray(unit(&t, smp), s, tt, r, 2.0f / 8.0f, 0.0f, 0.0f, 2.0f / 8.0f, out);
  for (int p = 0; p < 4; ++p) EXPECT_EQ(out[p][0], unorm(85)) << p;
  smp.lodBias = 1.0f;
  sampleGrad2DArray(unit(&t, smp), s, tt, r, 2.0f / 8.0f, 0.0f, 0.0f, 2.0f / 8.0f, out);
  for (int p = 0; p < 4; ++p) EXPECT_EQ(out[p][0], unorm(170)) << p;
}

// --- buffers -------------------------------------------------------------------------------------

TextureData bufferTexture(Format f, const BufferData* b) {
  TextureDesc d;
  d.kind = TextureKind::Buffer;
  d.format = f;
  TextureData t(d);
  t.buffer = b;
  return t;
}

template <class T>
BufferData bufferOf(std::initializer_list<T> values) {
  BufferData b;
  b.kind = BufferKind::Texel;
  b.bytes.resize(values.size() * sizeof(T));
  std::memcpy(b.bytes.data(), values.begin(), b.bytes.size());
  return b;
}

TEST(BufferFetch, ReturnsTexelsInsideTheBufferAndZeroOutside) {
  const BufferData b = bufferOf<uint32_t>({7u, 0xffffffffu, 42u});
  const TextureData t = bufferTexture(Format::R32UI, &b);
  TexUnit u;
  u.tex = &t;
  EXPECT_EQ(fetchBufferUint(u, 0), 7u);
  EXPECT_EQ(fetchBufferUint(u, 1), 0xffffffffu);
  EXPECT_EQ(fetchBufferUint(u, 2), 42u);
  EXPECT_EQ(fetchBufferUint(u, 3), 0u);
  EXPECT_EQ(fetchBufferUint(u, -1), 0u);
  EXPECT_EQ(fetchBufferUint(u, int64_t(1) << 40), 0u);
  float out[4];
  fetchBuffer(u, 2, out);
  EXPECT_EQ((std::array<float, 4>{out[0], out[1], out[2], out[3]}), (std::array<float, 4>{42.0f, 0.0f, 0.0f, 1.0f}));
  fetchBuffer(u, 3, out);
  EXPECT_EQ((std::array<float, 4>{out[0], out[1], out[2], out[3]}), (std::array<float, 4>{0.0f, 0.0f, 0.0f, 0.0f}));
  fetchBuffer(u, -1, out);
  EXPECT_EQ((std::array<float, 4>{out[0], out[1], out[2], out[3]}), (std::array<float, 4>{0.0f, 0.0f, 0.0f, 0.0f}));
}

TEST(BufferFetch, CountsOnlyWholeTexels) {
  // 40 bytes of RGBA32F = 2.5 texels: N = 2.
  BufferData b = bufferOf<float>({1, 2, 3, 4, 5, 6, 7, 8, 9, 10});
  const TextureData t = bufferTexture(Format::RGBA32F, &b);
  TexUnit u;
  u.tex = &t;
  float out[4];
  fetchBuffer(u, 1, out);
  EXPECT_EQ((std::array<float, 4>{out[0], out[1], out[2], out[3]}), (std::array<float, 4>{5, 6, 7, 8}));
  fetchBuffer(u, 2, out);
  EXPECT_EQ((std::array<float, 4>{out[0], out[1], out[2], out[3]}), (std::array<float, 4>{0, 0, 0, 0}));
}

TEST(BufferFetch, ExpandsFormatsLikeTextureLookups) {
  TexUnit u;
  float out[4];
  const BufferData b8 = bufferOf<uint8_t>({0, 51, 128, 255, 7, 8, 9, 10});
  const TextureData rgba8 = bufferTexture(Format::RGBA8, &b8);
  u.tex = &rgba8;
  fetchBuffer(u, 0, out);
  EXPECT_EQ((std::array<float, 4>{out[0], out[1], out[2], out[3]}),
            (std::array<float, 4>{0.0f, 0.2f, unorm(128), 1.0f}));
  const TextureData r8 = bufferTexture(Format::R8, &b8);
  u.tex = &r8;
  fetchBuffer(u, 2, out);
  EXPECT_EQ((std::array<float, 4>{out[0], out[1], out[2], out[3]}), (std::array<float, 4>{unorm(128), 0, 0, 1}));
  fetchBuffer(u, 8, out);
  EXPECT_EQ((std::array<float, 4>{out[0], out[1], out[2], out[3]}), (std::array<float, 4>{0, 0, 0, 0}));
  const BufferData bf = bufferOf<float>({0.5f, -2.0f, 3.25f, 1e20f});
  const TextureData rg = bufferTexture(Format::RG32F, &bf);
  u.tex = &rg;
  fetchBuffer(u, 1, out);
  EXPECT_EQ((std::array<float, 4>{out[0], out[1], out[2], out[3]}), (std::array<float, 4>{3.25f, 1e20f, 0, 1}));
  EXPECT_EQ(fetchBufferUint(u, 1), 0u);  // not an integer format
}

TEST(BufferFetch, BufferTextureWithoutABufferReadsZero) {
  const TextureData t = bufferTexture(Format::RGBA32F, nullptr);
  TexUnit u;
  u.tex = &t;
  float out[4] = {9, 9, 9, 9};
  fetchBuffer(u, 0, out);
  EXPECT_EQ((std::array<float, 4>{out[0], out[1], out[2], out[3]}), (std::array<float, 4>{0, 0, 0, 0}));
}

TEST(BufferFetch, NoTextureBoundReturnsOpaqueBlack) {
  TexUnit u;
  float out[4];
  fetchBuffer(u, 0, out);
  EXPECT_EQ((std::array<float, 4>{out[0], out[1], out[2], out[3]}), (std::array<float, 4>{0, 0, 0, 1}));
  EXPECT_EQ(fetchBufferUint(u, 0), 0u);
}

TEST(BufferFetch, ReadsLevelZeroOfATwoDTextureByLinearIndex) {
  TextureData t(desc2D(Format::R32UI, 3, 2, 2));
  for (uint32_t y = 0; y < 2; ++y)
    for (uint32_t x = 0; x < 3; ++x) setU32(t, 0, 0, x, y, 100 * y + x);
  TexUnit u;
  u.tex = &t;
  EXPECT_EQ(fetchBufferUint(u, 4), 101u);
  EXPECT_EQ(fetchBufferUint(u, 5), 102u);
  EXPECT_EQ(fetchBufferUint(u, 6), 0u);
}

// --- completeness --------------------------------------------------------------------------------

TEST(Incomplete, NoTextureBoundSamplesOpaqueBlack) {
  TexUnit u;
  const std::array<float, 4> black{0, 0, 0, 1};
  EXPECT_EQ(at(u, 0.5f, 0.5f, 0), black);
  const float s[4] = {0, 1, 0, 1}, t[4] = {0, 0, 1, 1}, r[4] = {0, 0, 0, 0};
  float out[4][4];
  sampleQuad2D(u, s, t, 0.0f, out);
  for (auto& o : out) EXPECT_EQ((std::array<float, 4>{o[0], o[1], o[2], o[3]}), black);
  sampleQuad2DArray(u, s, t, r, 0.0f, out);
  for (auto& o : out) EXPECT_EQ((std::array<float, 4>{o[0], o[1], o[2], o[3]}), black);
  sampleGrad2DArray(u, s, t, r, 1, 0, 0, 1, out);
  for (auto& o : out) EXPECT_EQ((std::array<float, 4>{o[0], o[1], o[2], o[3]}), black);
}

TEST(Incomplete, IntegerTextureWithAnyLinearFilterSamplesOpaqueBlack) {
  TextureData t(desc2D(Format::R32UI, 2, 2, 2));
  setU32(t, 0, 0, 0, 0, 5);
  const std::array<float, 4> black{0, 0, 0, 1};
  EXPECT_EQ(at(unit(&t, sampler(Filter::Nearest, Filter::Linear)), 0.25f, 0.25f, 0), black);
  EXPECT_EQ(at(unit(&t, sampler(Filter::Linear, Filter::Nearest)), 0.25f, 0.25f, 0), black);
  EXPECT_EQ(at(unit(&t, sampler(Filter::NearestMipmapLinear, Filter::Nearest)), 0.25f, 0.25f, 0), black);
  EXPECT_EQ(at(unit(&t, sampler(Filter::LinearMipmapNearest, Filter::Nearest)), 0.25f, 0.25f, 0), black);
  EXPECT_EQ(at(unit(&t, SamplerState{}), 0.25f, 0.25f, 0), black);  // GL's default filters
}

TEST(Incomplete, IntegerTextureWithNearestFiltersReturnsTheIntegerAsFloat) {
  TextureData t(desc2D(Format::R32UI, 2, 2, 2));
  setU32(t, 0, 0, 0, 0, 123456789);
  setU32(t, 1, 0, 0, 0, 77);
  const TexUnit u = unit(&t, sampler(Filter::NearestMipmapNearest, Filter::Nearest));
  EXPECT_EQ(at(u, 0.25f, 0.25f, 0), (std::array<float, 4>{123456792.0f, 0, 0, 1}));  // float(123456789)
  EXPECT_EQ(at(u, 0.25f, 0.25f, 256), (std::array<float, 4>{77.0f, 0, 0, 1}));
  EXPECT_EQ(at(unit(&t, sampler(Filter::Nearest, Filter::Nearest)), 0.25f, 0.25f, 256),
            (std::array<float, 4>{123456792.0f, 0, 0, 1}));
}

TEST(Incomplete, BufferTexturesCannotBeSampledWithFilters) {
  const BufferData b = bufferOf<float>({1, 2, 3, 4});
  const TextureData t = bufferTexture(Format::RGBA32F, &b);
  EXPECT_EQ(at(unit(&t, sampler(Filter::Nearest, Filter::Nearest)), 0.1f, 0.1f, 0), (std::array<float, 4>{0, 0, 0, 1}));
}

// --- float formats -------------------------------------------------------------------------------

TEST(SampleFloat, LinearFiltersInDoubleAndRoundsToFloatOnce) {
  TextureData t(desc2D(Format::RG32F, 2, 1));
  const float onePlusUlp = 1.0f + std::ldexp(1.0f, -23);
  setF32(t, 0, 0, 0, 0, {1.0f, 0.0f});
  setF32(t, 0, 0, 1, 0, {onePlusUlp, 3.0f});
  const TexUnit u = unit(&t, sampler(Filter::Linear, Filter::Linear));
  // alpha = 1/2: 1 + 2^-24 is a tie between 1 and 1 + 2^-23 -> even (1).
  EXPECT_EQ(at(u, 0.5f, 0.5f, 0), (std::array<float, 4>{1.0f, 1.5f, 0.0f, 1.0f}));
  // alpha = 3/4: 1 + 0.75 * 2^-23 -> 1 + 2^-23.
  EXPECT_EQ(at(u, 0.625f, 0.5f, 0), (std::array<float, 4>{onePlusUlp, 2.25f, 0.0f, 1.0f}));
  // alpha = 1/4: 1 + 0.25 * 2^-23 -> 1.
  EXPECT_EQ(at(u, 0.375f, 0.5f, 0), (std::array<float, 4>{1.0f, 0.75f, 0.0f, 1.0f}));
}

TEST(SampleFloat, ThirdsAreRoundedOnceFromTheExactWeightedSum) {
  // alpha = 85/256 between 0 and 1: exactly 85/256 (representable), and between 0 and 0.1f the
  // double sum 0.1f * 85 * 2^16 / 2^24 rounds to float once.
  TextureData t(desc2D(Format::RGBA32F, 2, 1));
  setF32(t, 0, 0, 0, 0, {0.0f, 0.0f, 1.0f, 1.0f});
  setF32(t, 0, 0, 1, 0, {1.0f, 0.1f, 1.0f, 1.0f});
  const TexUnit u = unit(&t, sampler(Filter::Linear, Filter::Linear));
  const float s = float((128.0 + 85.0) / 512.0);  // 256 u = 213 -> alpha = 85
  const auto o = at(u, s, 0.5f, 0);
  EXPECT_EQ(o[0], 85.0f / 256.0f);
  EXPECT_EQ(o[1], float(double(0.1f) * 85.0 / 256.0));
  EXPECT_EQ(o[2], 1.0f);
}

TEST(SampleFloat, TrilinearOnFloatTexturesUsesTheEightBitMipWeight) {
  TextureData t(desc2D(Format::RGBA32F, 2, 2, 2));
  for (uint32_t y = 0; y < 2; ++y)
    for (uint32_t x = 0; x < 2; ++x) setF32(t, 0, 0, x, y, {1.0f, 1.0f, 1.0f, 1.0f});
  setF32(t, 1, 0, 0, 0, {3.0f, -1.0f, 0.0f, 1.0f});
  const TexUnit u = unit(&t, sampler(Filter::LinearMipmapLinear, Filter::Linear));
  EXPECT_EQ(at(u, 0.3f, 0.6f, 64), (std::array<float, 4>{1.5f, 0.5f, 0.75f, 1.0f}));
}

TEST(SampleFloat, DepthTexturesSampleAsRedOnly) {
  TextureData t(desc2D(Format::D32F, 1, 1));
  setF32(t, 0, 0, 0, 0, {0.625f});
  EXPECT_EQ(at(unit(&t, sampler(Filter::Linear, Filter::Linear)), 0.5f, 0.5f, 0),
            (std::array<float, 4>{0.625f, 0.0f, 0.0f, 1.0f}));
}

}  // namespace
}  // namespace tessera
