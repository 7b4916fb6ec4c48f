// The oracle's S3TC decoder (raster/bc_decode.h): hand-made blocks whose texels were worked out by hand from
// EXT_texture_compression_s3tc and the rounding of docs/spec-choices.md C1-C4. Each block is chosen so that
// truncating instead of rounding to nearest (or rounding a half down) gives a different byte.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "base/error.h"
#include "raster/bc_decode.h"

namespace tessera {
namespace {

using Texel = std::array<uint8_t, 4>;

Texel texelOf(const uint8_t* out, int i) { return {out[4 * i], out[4 * i + 1], out[4 * i + 2], out[4 * i + 3]}; }

// Codes 0, 1, 2, 3 for texels 0..3 and 0 for the rest: 0b11'10'01'00.
constexpr uint8_t kCodes0123 = 0xE4;

TEST(BcDecode, Bc1FourColourModeRoundsTheThirdsToNearestFromBitReplicatedEndpoints) {
  // color0 = (r5 1, g6 1, b5 1) = 0x0821 -> (8, 4, 8); color1 = 0 -> black. color0 > color1: four colours.
  // code 2 = (2*c0 + c1)/3 = (5.33, 2.67, 5.33) -> (5, 3, 5); code 3 = (c0 + 2*c1)/3 = (2.67, 1.33, 2.67) -> (3, 1, 3).
  const uint8_t block[8] = {0x21, 0x08, 0x00, 0x00, kCodes0123, 0, 0, 0};
  uint8_t out[64];
  decodeBc1Block(block, out);
  EXPECT_EQ(texelOf(out, 0), (Texel{8, 4, 8, 255}));
  EXPECT_EQ(texelOf(out, 1), (Texel{0, 0, 0, 255}));
  EXPECT_EQ(texelOf(out, 2), (Texel{5, 3, 5, 255}));
  EXPECT_EQ(texelOf(out, 3), (Texel{3, 1, 3, 255}));
  for (int i = 4; i < 16; ++i) EXPECT_EQ(texelOf(out, i), (Texel{8, 4, 8, 255})) << "texel " << i;
}

TEST(BcDecode, Bc1ThreeColourModeRoundsTheHalfUpAndCodeThreeIsOpaqueBlack) {
  // color0 = 0x0800 -> (8, 0, 0); color1 = (r5 4, g6 16, b5 4) = 0x2204 -> (33, 65, 33). color0 <= color1.
  // code 2 = (c0 + c1)/2 = (20.5, 32.5, 16.5) -> (21, 33, 17); code 3 = black, alpha 255 (the RGB DXT1 format).
  const uint8_t block[8] = {0x00, 0x08, 0x04, 0x22, kCodes0123, 0, 0, 0};
  uint8_t out[64];
  decodeBc1Block(block, out);
  EXPECT_EQ(texelOf(out, 0), (Texel{8, 0, 0, 255}));
  EXPECT_EQ(texelOf(out, 1), (Texel{33, 65, 33, 255}));
  EXPECT_EQ(texelOf(out, 2), (Texel{21, 33, 17, 255}));
  EXPECT_EQ(texelOf(out, 3), (Texel{0, 0, 0, 255}));
}

TEST(BcDecode, Bc1EndpointsExpandByBitReplicationSoTheLargestCodeIs255) {
  // color0 = 0xFFFF -> white, color1 = (r5 16, g6 32, b5 16) = 0x8410 -> (132, 130, 132).
  const uint8_t block[8] = {0xFF, 0xFF, 0x10, 0x84, 0x04, 0, 0, 0};  // texel 1 uses code 1
  uint8_t out[64];
  decodeBc1Block(block, out);
  EXPECT_EQ(texelOf(out, 0), (Texel{255, 255, 255, 255}));
  EXPECT_EQ(texelOf(out, 1), (Texel{132, 130, 132, 255}));
}

TEST(BcDecode, Bc3ColourIgnoresTheThreeColourModeAndAlphaEightValueModeRoundsSevenths) {
  // Alpha 200 > 100: code i = ((8 - i)*200 + (i - 1)*100)/7 = 185.71, 171.43, 157.14, 142.86, 128.57, 114.29.
  // Codes 0..7 for texels 0..7, three bits each: 0xFAC688.
  // Colour as in the three-colour BC1 block above, but decoded with four colours:
  // code 2 = (2*c0 + c1)/3 = (16.33, 21.67, 11) -> (16, 22, 11); code 3 = (c0 + 2*c1)/3 = (24.67, 43.33, 22) -> (25, 43, 22).
  const uint8_t block[16] = {200, 100, 0x88, 0xC6, 0xFA, 0, 0, 0, 0x00, 0x08, 0x04, 0x22, kCodes0123, 0, 0, 0};
  uint8_t out[64];
  decodeBc3Block(block, out);
  const uint8_t alpha[8] = {200, 100, 186, 171, 157, 143, 129, 114};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(out[4 * i + 3], alpha[i]) << "texel " << i;
  for (int i = 8; i < 16; ++i) EXPECT_EQ(out[4 * i + 3], 200) << "texel " << i;
  EXPECT_EQ(texelOf(out, 0), (Texel{8, 0, 0, 200}));
  EXPECT_EQ(texelOf(out, 1), (Texel{33, 65, 33, 100}));
  EXPECT_EQ(texelOf(out, 2), (Texel{16, 22, 11, 186}));
  EXPECT_EQ(texelOf(out, 3), (Texel{25, 43, 22, 171}));
}

TEST(BcDecode, Bc3AlphaSixValueModeRoundsFifthsAndEndsWithZeroAnd255) {
  // Alpha 10 <= 21: code i in 2..5 = ((6 - i)*10 + (i - 1)*21)/5 = 12.2, 14.4, 16.6, 18.8; code 6 = 0, code 7 = 255.
  const uint8_t block[16] = {10, 21, 0x88, 0xC6, 0xFA, 0, 0, 0, 0xFF, 0xFF, 0x00, 0x00, 0, 0, 0, 0};
  uint8_t out[64];
  decodeBc3Block(block, out);
  const uint8_t alpha[8] = {10, 21, 12, 14, 17, 19, 0, 255};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(out[4 * i + 3], alpha[i]) << "texel " << i;
}

TEST(BcDecode, ALevelDropsTheTexelsOfEdgeBlocksPastItsSizeAndKeepsBlockRowOrder) {
  // 5 x 5 texels = 2 x 2 blocks, each a single colour (code 0 everywhere): 0x001F blue, 0xF800 red,
  // 0x07E0 green, 0xFFFF white, in block order (0,0), (1,0), (0,1), (1,1).
  std::vector<uint8_t> blocks;
  for (uint16_t c : {uint16_t(0x001F), uint16_t(0xF800), uint16_t(0x07E0), uint16_t(0xFFFF)})
    for (uint8_t b : {uint8_t(c & 0xFF), uint8_t(c >> 8), uint8_t(0), uint8_t(0), uint8_t(0), uint8_t(0), uint8_t(0), uint8_t(0)})
      blocks.push_back(b);
  const std::vector<uint8_t> out = decodeBcLevel(BcFormat::BC1, 5, 5, blocks);
  ASSERT_EQ(out.size(), 5u * 5u * 4u);
  auto at = [&](int x, int y) { return texelOf(out.data(), y * 5 + x); };
  EXPECT_EQ(at(3, 3), (Texel{0, 0, 255, 255}));
  EXPECT_EQ(at(4, 0), (Texel{255, 0, 0, 255}));
  EXPECT_EQ(at(0, 4), (Texel{0, 255, 0, 255}));
  EXPECT_EQ(at(4, 4), (Texel{255, 255, 255, 255}));
}

TEST(BcDecode, ALevelOfTheWrongByteCountIsRefusedNamingTheSizes) {
  const std::vector<uint8_t> blocks(15, 0);
  try {
    decodeBcLevel(BcFormat::BC3, 2, 2, blocks);
    FAIL() << "accepted 15 bytes for one BC3 block";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("BC3 level of 2x2 needs 16 bytes, got 15"), std::string::npos) << e.what();
  }
}

TEST(BcDecode, DecodingIntoALevelGivesTheSameBytesAndTouchesNothingOutsideIt) {
  // The backend decodes straight into a texture's level (cpu_backend.cpp); 5 x 3 leaves partial blocks.
  std::vector<uint8_t> blocks(bcLevelBytes(BcFormat::BC3, 5, 3));
  for (size_t i = 0; i < blocks.size(); ++i) blocks[i] = uint8_t(i * 37 + 11);
  const std::vector<uint8_t> expected = decodeBcLevel(BcFormat::BC3, 5, 3, blocks);
  std::vector<uint8_t> storage(8 + expected.size() + 8, 0xA5);
  decodeBcLevelInto(BcFormat::BC3, 5, 3, blocks, std::span<uint8_t>(storage.data() + 8, expected.size()));
  EXPECT_EQ(std::vector<uint8_t>(storage.begin() + 8, storage.end() - 8), expected);
  for (size_t i = 0; i < 8; ++i) {
    EXPECT_EQ(storage[i], 0xA5) << i;
    EXPECT_EQ(storage[storage.size() - 1 - i], 0xA5) << i;
  }
}

TEST(BcDecode, AnOutputOfTheWrongSizeIsRefusedNamingBothSizes) {
  const std::vector<uint8_t> blocks(16, 0);
  std::vector<uint8_t> out(15);
  try {
    decodeBcLevelInto(BcFormat::BC3, 2, 2, blocks, out);
    FAIL() << "decoded a 2x2 level into 15 bytes";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("2x2 level decodes to 16 bytes, but the output holds 15"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace tessera
