// Texture storage and the deterministic mip-chain box filter (raster/texture.h): odd sizes use the
// exact three-tap weights (m - i, m, i + 1)/n, unorm8 results are rounded half to even once, floats
// are computed in double and rounded once, R32UI takes texel (2i, 2j).
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "raster/texture.h"
#include "tests/raster/texture_test_util.h"

namespace tessera {
namespace {

using testing::desc2D;
using testing::setF32;

std::vector<uint8_t> texelU8(const TextureData& t, uint32_t level, uint32_t layer, uint32_t x, uint32_t y) {
  const uint8_t* p = t.texel(level, layer, x, y);
  return std::vector<uint8_t>(p, p + texelBytes(t.desc.format));
}
std::vector<float> texelF32(const TextureData& t, uint32_t level, uint32_t layer, uint32_t x, uint32_t y) {
  std::vector<float> v(size_t(channelCount(t.desc.format)));
  std::memcpy(v.data(), t.texel(level, layer, x, y), v.size() * sizeof(float));
  return v;
}
uint32_t texelU32(const TextureData& t, uint32_t level, uint32_t x, uint32_t y) {
  uint32_t v;
  std::memcpy(&v, t.texel(level, 0, x, y), 4);
  return v;
}

TEST(TextureStorage, AllocatesZeroedLevelsForEveryLayer) {
  const TextureData t(desc2D(Format::RGBA8, 5, 3, 3, 2));
  ASSERT_EQ(t.levels.size(), 3u);
  EXPECT_EQ(t.levels[0].size(), 5u * 3 * 4 * 2);
  EXPECT_EQ(t.levels[1].size(), 2u * 1 * 4 * 2);
  EXPECT_EQ(t.levels[2].size(), 1u * 1 * 4 * 2);
  for (const auto& level : t.levels)
    for (uint8_t b : level) EXPECT_EQ(b, 0);
  // Layer 1 of level 0 starts right after layer 0; rows are tightly packed.
  EXPECT_EQ(t.texel(0, 1, 0, 0) - t.texel(0, 0, 0, 0), 5 * 3 * 4);
  EXPECT_EQ(t.texel(0, 0, 0, 1) - t.texel(0, 0, 0, 0), 5 * 4);
}

TEST(TextureStorage, BufferTexturesHaveNoLevels) {
  TextureDesc d;
  d.kind = TextureKind::Buffer;
  d.format = Format::RGBA32F;
  const TextureData t(d);
  EXPECT_TRUE(t.levels.empty());
  EXPECT_EQ(t.buffer, nullptr);
}

TEST(MipChain, OddFiveByThreeReducesToTwoByOneThenOneByOneWithExactWeights) {
  TextureData t(desc2D(Format::RGBA8, 5, 3, 3));
  for (uint32_t y = 0; y < 3; ++y)
    for (uint32_t x = 0; x < 5; ++x) {
      uint8_t* p = t.texel(0, 0, x, y);
      p[0] = uint8_t(30 * x + 3 * y);  // a linear ramp
      p[3] = 255;
    }
  t.texel(0, 0, 0, 0)[1] = 100;
  t.texel(0, 0, 4, 2)[1] = 8;
  t.texel(0, 0, 0, 0)[2] = 112;
  t.texel(0, 0, 2, 0)[2] = 1;
  generateMipChain(t);
  // Level 1 (2x1): x weights (2, 2, 1)/5 and (1, 2, 2)/5, y weights (1, 1, 1)/3; denominator 15.
  // R: sum_y 2 (3y) + 2 (30 + 3y) + (60 + 3y) = sum_y (120 + 15y) = 405 -> 27;
  //    sum_y (60 + 3y) + 2 (90 + 3y) + 2 (120 + 3y) = sum_y (480 + 15y) = 1485 -> 99.
  // G: 2 * 100 / 15 = 13.33 -> 13;  2 * 8 / 15 = 1.07 -> 1.
  // B: (2 * 112 + 1) / 15 = 15;  1 / 15 -> 0.
  EXPECT_EQ(texelU8(t, 1, 0, 0, 0), (std::vector<uint8_t>{27, 13, 15, 255}));
  EXPECT_EQ(texelU8(t, 1, 0, 1, 0), (std::vector<uint8_t>{99, 1, 0, 255}));
  // Level 2 (1x1): x weights (1, 1)/2, the height-1 axis is copied.
  // R: 126 / 2 = 63. G: 14 / 2 = 7. B: 15 / 2 = 7.5 -> 8 (half to even).
  EXPECT_EQ(texelU8(t, 2, 0, 0, 0), (std::vector<uint8_t>{63, 7, 8, 255}));
}

TEST(MipChain, SevenTexelsUseWeightsThreeThreeOneThenTwoThreeTwoThenOneThreeThree) {
  TextureData t(desc2D(Format::R8, 7, 1, 3));
  const uint8_t row[7] = {7, 0, 0, 14, 0, 0, 70};
  std::memcpy(t.levels[0].data(), row, 7);
  generateMipChain(t);
  // (3*7)/7 = 3; (3*14)/7 = 6; (3*70)/7 = 30.
  EXPECT_EQ(t.levels[1], (std::vector<uint8_t>{3, 6, 30}));
  EXPECT_EQ(t.levels[2], (std::vector<uint8_t>{13}));  // 39 / 3
}

TEST(MipChain, ThreeTapAveragesRoundToNearest) {
  TextureData t(desc2D(Format::RGBA8, 3, 1, 2));
  const uint8_t texels[12] = {0, 1, 254, 10, 0, 1, 255, 10, 1, 0, 255, 11};
  std::memcpy(t.levels[0].data(), texels, 12);
  generateMipChain(t);
  // 1/3 -> 0, 2/3 -> 1, 764/3 -> 255, 31/3 -> 10.
  EXPECT_EQ(t.levels[1], (std::vector<uint8_t>{0, 1, 255, 10}));
}

TEST(MipChain, EvenAveragesRoundHalfToEven) {
  TextureData t(desc2D(Format::RGBA8, 2, 2, 2));
  // R: 2/4 = 0.5 -> 0. G: 6/4 = 1.5 -> 2. B: 10/4 = 2.5 -> 2. A: 3/4 -> 1.
  const uint8_t texels[16] = {2, 3, 5, 1, 0, 3, 5, 1, 0, 0, 0, 1, 0, 0, 0, 0};
  std::memcpy(t.levels[0].data(), texels, 16);
  generateMipChain(t);
  EXPECT_EQ(t.levels[1], (std::vector<uint8_t>{0, 2, 2, 1}));
}

TEST(MipChain, AnAxisOfOneTexelIsCopiedWhileTheOtherIsReduced) {
  TextureData t(desc2D(Format::R8, 1, 4, 3));
  const uint8_t column[4] = {10, 20, 30, 41};
  std::memcpy(t.levels[0].data(), column, 4);
  generateMipChain(t);
  EXPECT_EQ(t.levels[1], (std::vector<uint8_t>{15, 36}));  // 35.5 -> 36
  EXPECT_EQ(t.levels[2], (std::vector<uint8_t>{26}));      // 25.5 -> 26
}

TEST(MipChain, ConstantImageStaysConstantThroughTheChain) {
  TextureData t(desc2D(Format::RGBA8, 13, 7, fullMipCount(13, 7)));
  for (uint32_t y = 0; y < 7; ++y)
    for (uint32_t x = 0; x < 13; ++x) std::memcpy(t.texel(0, 0, x, y), "\x11\xc8\xff\x03", 4);
  generateMipChain(t);
  ASSERT_EQ(t.levels.size(), 4u);  // 13x7, 6x3, 3x1, 1x1
  for (uint32_t l = 1; l < 4; ++l)
    for (uint32_t y = 0; y < levelHeight(t.desc, l); ++y)
      for (uint32_t x = 0; x < levelWidth(t.desc, l); ++x)
        EXPECT_EQ(texelU8(t, l, 0, x, y), (std::vector<uint8_t>{17, 200, 255, 3})) << l << " " << x << " " << y;

  TextureData f(desc2D(Format::RGBA32F, 13, 7, 4));
  for (uint32_t y = 0; y < 7; ++y)
    for (uint32_t x = 0; x < 13; ++x) setF32(f, 0, 0, x, y, {0.1f, -3.7f, 1e-3f, 12345.678f});
  generateMipChain(f);
  for (uint32_t l = 1; l < 4; ++l)
    for (uint32_t y = 0; y < levelHeight(f.desc, l); ++y)
      for (uint32_t x = 0; x < levelWidth(f.desc, l); ++x)
        EXPECT_EQ(texelF32(f, l, 0, x, y), (std::vector<float>{0.1f, -3.7f, 1e-3f, 12345.678f})) << l;
}

TEST(MipChain, FloatFormatsAverageInDoubleAndRoundToFloatOnce) {
  TextureData t(desc2D(Format::RG32F, 3, 1, 2));
  setF32(t, 0, 0, 0, 0, {1.0f, 0.1f});
  setF32(t, 0, 0, 1, 0, {2.0f, 0.2f});
  setF32(t, 0, 0, 2, 0, {4.0f, 0.3f});
  generateMipChain(t);
  EXPECT_EQ(texelF32(t, 1, 0, 0, 0),
            (std::vector<float>{float(7.0 / 3.0), float((double(0.1f) + double(0.2f) + double(0.3f)) / 3.0)}));

  // 5x1 RGBA32F, first destination texel: (2 a + 2 b + c) / 5.
  TextureData f(desc2D(Format::RGBA32F, 5, 1, 2));
  setF32(f, 0, 0, 0, 0, {1.0f, 0.0f, 1e30f, 0.5f});
  setF32(f, 0, 0, 1, 0, {2.0f, 0.0f, -1e30f, 0.5f});
  setF32(f, 0, 0, 2, 0, {3.0f, 1.0f, 5.0f, 0.5f});
  setF32(f, 0, 0, 3, 0, {0.0f, 0.0f, 0.0f, 0.5f});
  setF32(f, 0, 0, 4, 0, {0.0f, 0.0f, 0.0f, 0.5f});
  generateMipChain(f);
  // B: summed in the fixed order x = 0, 1, 2: 2e30 - 2e30 + 5 = 5 exactly, / 5 = 1.
  EXPECT_EQ(texelF32(f, 1, 0, 0, 0), (std::vector<float>{float(9.0 / 5.0), float(1.0 / 5.0), 1.0f, 0.5f}));
  EXPECT_EQ(texelF32(f, 1, 0, 1, 0), (std::vector<float>{float(3.0 / 5.0), float(1.0 / 5.0), 1.0f, 0.5f}));
}

TEST(MipChain, IntegerTexturesTakeTheEvenTexelWithoutFiltering) {
  TextureData t(desc2D(Format::R32UI, 5, 3, 3));
  for (uint32_t y = 0; y < 3; ++y)
    for (uint32_t x = 0; x < 5; ++x) {
      const uint32_t v = 1000000000u + 10 * y + x;
      std::memcpy(t.texel(0, 0, x, y), &v, 4);
    }
  generateMipChain(t);
  EXPECT_EQ(texelU32(t, 1, 0, 0), 1000000000u);
  EXPECT_EQ(texelU32(t, 1, 1, 0), 1000000002u);
  EXPECT_EQ(texelU32(t, 2, 0, 0), 1000000000u);
}

TEST(MipChain, ArrayLayersAreReducedIndependently) {
  TextureData t(desc2D(Format::R8, 4, 2, 3, 3));
  for (uint32_t k = 0; k < 3; ++k)
    for (uint32_t y = 0; y < 2; ++y)
      for (uint32_t x = 0; x < 4; ++x) t.texel(0, k, x, y)[0] = uint8_t(50 * k + x);
  generateMipChain(t);
  // Level 1 (2x1): (0 + 1 + 0 + 1)/4 = 0.5 -> 0 and (2 + 3 + 2 + 3)/4 = 2.5 -> 2, plus 50 k.
  EXPECT_EQ(t.levels[1], (std::vector<uint8_t>{0, 2, 50, 52, 100, 102}));
  // Level 2 (1x1): 1, 51, 101.
  EXPECT_EQ(t.levels[2], (std::vector<uint8_t>{1, 51, 101}));
}

TEST(MipChain, BuildMipChainRGBA8ReturnsTheFullChain) {
  std::vector<uint8_t> img(5 * 3 * 4);
  for (size_t i = 0; i < img.size(); ++i) img[i] = uint8_t(i * 13 % 256);
  const auto levels = buildMipChainRGBA8(5, 3, img);
  ASSERT_EQ(levels.size(), 3u);
  EXPECT_EQ(levels[0], img);
  EXPECT_EQ(levels[1].size(), 2u * 1 * 4);
  EXPECT_EQ(levels[2].size(), 4u);
  TextureData t(desc2D(Format::RGBA8, 5, 3, 3));
  t.levels[0] = img;
  generateMipChain(t);
  EXPECT_EQ(levels, t.levels);
}

TEST(MipChain, BuildMipChainRGBA8RejectsAWrongSizedImage) {
  std::vector<uint8_t> img(5 * 3 * 4 - 1);
  EXPECT_THROW(buildMipChainRGBA8(5, 3, img), Error);
  EXPECT_THROW(buildMipChainRGBA8(0, 3, {}), Error);
}

}  // namespace
}  // namespace tessera
