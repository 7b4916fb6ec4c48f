// The S3TC encoder (raster/bc_encode.h): the format choice, determinism at any thread count, edge
// replication of partial blocks, and round trips of texels a BC1/BC3 block can hold exactly.
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cstdint>
#include <vector>

#include "raster/bc_decode.h"
#include "raster/bc_encode.h"
#include "base/error.h"

namespace tessera {
namespace {

// A deterministic image with gradients, edges and (optionally) varying alpha: enough variety that every
// block takes stb_dxt's PCA and refinement path, not only its constant-colour table.
std::vector<uint8_t> patternImage(uint32_t w, uint32_t h, bool alpha) {
  std::vector<uint8_t> px(size_t(w) * h * 4);
  uint32_t state = 12345;
  for (size_t i = 0; i < size_t(w) * h; ++i) {
    state = state * 1664525u + 1013904223u;
    const uint32_t x = uint32_t(i % w), y = uint32_t(i / w);
    px[4 * i + 0] = uint8_t(x * 7 + (state >> 28));
    px[4 * i + 1] = uint8_t(y * 5 + ((x / 3) & 1) * 90);
    px[4 * i + 2] = uint8_t((x ^ y) * 3);
    px[4 * i + 3] = alpha ? uint8_t(255 - ((x + y) * 11 & 255)) : 255;
  }
  return px;
}

std::vector<uint8_t> encodeWithThreads(int threads, BcFormat f, uint32_t w, uint32_t h, const std::vector<uint8_t>& px) {
  // oneTBB caps an arena at the machine's cores unless a global_control allows more (CONTRIBUTING: N means N).
  tbb::global_control allow(tbb::global_control::max_allowed_parallelism, size_t(threads));
  tbb::task_arena arena(threads);
  std::vector<uint8_t> out;
  arena.execute([&] { out = encodeBcLevel(f, w, h, px); });
  return out;
}

TEST(BcEncode, AnImageWhoseAlphaIsAll255PicksBc1AndOneTexelBelowPicksBc3) {
  std::vector<uint8_t> px = patternImage(9, 7, false);
  EXPECT_EQ(chooseBcFormat(px), BcFormat::BC1);
  px[4 * 62 + 3] = 254;  // the last texel
  EXPECT_EQ(chooseBcFormat(px), BcFormat::BC3);
}

TEST(BcEncode, TheBytesAreTheSameAtOneAndSevenThreadsAndOnARepeatedRun) {
  for (const bool alpha : {false, true}) {
    const BcFormat f = alpha ? BcFormat::BC3 : BcFormat::BC1;
    const std::vector<uint8_t> px = patternImage(67, 45, alpha);
    const std::vector<uint8_t> one = encodeWithThreads(1, f, 67, 45, px);
    ASSERT_EQ(one.size(), bcLevelBytes(f, 67, 45));
    EXPECT_EQ(encodeWithThreads(7, f, 67, 45, px), one) << bcFormatName(f);
    EXPECT_EQ(encodeWithThreads(2, f, 67, 45, px), one) << bcFormatName(f);
  }
}

TEST(BcEncode, LevelsSmallerThanABlockReplicateTheirEdgeTexelsSoSolidColoursRoundTripExactly) {
  // Colours exact in RGB565 (bit-replicated codes), one per level: 1x1, 2x1 and 3x2 each fill a whole block
  // by replication, which must not mix in zeros.
  for (const auto& [w, h] : {std::pair{1u, 1u}, std::pair{2u, 1u}, std::pair{3u, 2u}}) {
    std::vector<uint8_t> px;
    for (uint32_t i = 0; i < w * h; ++i) px.insert(px.end(), {255, 0, 132, 255});
    const std::vector<uint8_t> blocks = encodeBcLevel(BcFormat::BC1, w, h, px);
    ASSERT_EQ(blocks.size(), 8u);
    EXPECT_EQ(decodeBcLevel(BcFormat::BC1, w, h, blocks), px) << w << "x" << h;
  }
}

TEST(BcEncode, AnEdgeBlockIsFittedToItsOwnTexelsOnly) {
  // 5 x 4: columns 0..3 blue, column 4 red. The second block holds only column 4 (replicated), so it decodes
  // to pure red; zero padding would have put black into the fit.
  std::vector<uint8_t> px;
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 5; ++x) px.insert(px.end(), {uint8_t(x == 4 ? 255 : 0), 0, uint8_t(x == 4 ? 0 : 255), 255});
  EXPECT_EQ(decodeBcLevel(BcFormat::BC1, 5, 4, encodeBcLevel(BcFormat::BC1, 5, 4, px)), px);
}

TEST(BcEncode, Bc3KeepsAConstantAlphaExactly) {
  std::vector<uint8_t> px = patternImage(16, 16, true);
  for (size_t i = 0; i < 16 * 16; ++i) px[4 * i + 3] = 77;
  const std::vector<uint8_t> out = decodeBcLevel(BcFormat::BC3, 16, 16, encodeBcLevel(BcFormat::BC3, 16, 16, px));
  for (size_t i = 0; i < 16 * 16; ++i) ASSERT_EQ(out[4 * i + 3], 77) << "texel " << i;
}

TEST(BcEncode, AnImageOfTheWrongByteCountIsRefused) {
  const std::vector<uint8_t> px(4 * 5, 0);
  EXPECT_THROW(encodeBcLevel(BcFormat::BC1, 2, 3, px), Error);
}

}  // namespace
}  // namespace tessera
