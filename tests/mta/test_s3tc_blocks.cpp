// S3TC blocks in the atlas tree's paging file (issue 14 §1, mta/block_encoding.h): exact size estimates for
// raw and S3TC builds, the bytes at any thread count, and the sizes of stored chains derived by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "mta/build.h"
#include "mta/build_plan.h"
#include "mta/output_size.h"
#include "mta/paging_file.h"
#include "mta_file_edit.h"
#include "mta_test_scene.h"

namespace tessera::mta {
namespace {

using testing::gridScene;
using testing::TempFile;

BuildParams s3tcParams(BlockEncoding e, uint32_t threads = 2) {
  BuildParams p;
  p.atlasSize = 64;
  p.border = 2;
  p.tanHalfFov = 0.5;
  p.screenWidth = 256;
  p.dMin = 2.0;
  p.threads = threads;
  p.encoding = e;
  return p;
}

// Two trees (RGB and RGBA quads) and two layers: both BC1 and BC3 chains, atlases and originals.
Scene scene() { return gridScene(8, 8, 32, 2.0f, true, true); }

TEST(S3tcBlocks, TheSizeEstimateIsTheFilesSizeToTheByteForRawAndForS3tc) {
  uint64_t sizes[2] = {};
  for (BlockEncoding e : {BlockEncoding::Raw, BlockEncoding::S3tc}) {
    SCOPED_TRACE(blockEncodingName(e));
    const BuildParams p = s3tcParams(e);
    const OutputEstimate planned = estimateOutput(planBuild(scene(), p));
    TempFile out("tree.mta");
    buildMta(scene(), p, out.path);
    const uint64_t size = std::filesystem::file_size(out.path);
    EXPECT_EQ(planned.totalBytes, size);
    const PagingFile f(out.path);
    EXPECT_EQ(f.meta().encoding, e);
    EXPECT_EQ(planned.pieces, f.meta().pieces.size());
    sizes[int(e)] = size;
  }
  // An RGB atlas is 64² · 3 = 12,288 bytes raw and 2,744 as BC1 (343 blocks of 8 bytes over 7 levels).
  EXPECT_LT(sizes[1], sizes[0] / 2);
}

// Hand-derived: a 64² BC1 chain is 256 + 64 + 16 + 4 + 1 + 1 + 1 = 343 blocks of 8 bytes, a BC3 one 343
// of 16; an image's chain is its levels' blocks.
TEST(S3tcBlocks, AtlasAndImageBlocksHoldWholeMipChainsOfBc1ForRgbAndBc3ForRgba) {
  TempFile out("tree.mta");
  buildMta(scene(), s3tcParams(BlockEncoding::S3tc), out.path);
  const PagingFile f(out.path);
  const MtaMeta& m = f.meta();
  ASSERT_EQ(m.trees.size(), 2u);
  size_t atlases = 0, images = 0;
  for (const BlockInfo& b : m.blocks) {
    if (b.kind == BlockKind::Atlas) {
      EXPECT_EQ(b.size, m.trees[b.tree].alpha ? 343u * 16 : 343u * 8);
      ++atlases;
    } else {
      const ImageRecord& r = m.images[b.node];
      uint64_t blocks = 0;  // every level down to 1 x 1, ceil(w/4) x ceil(h/4) blocks each
      for (uint32_t w = r.width, h = r.height;; w = std::max(1u, w / 2), h = std::max(1u, h / 2)) {
        blocks += uint64_t((w + 3) / 4) * ((h + 3) / 4);
        if (w == 1 && h == 1) break;
      }
      EXPECT_EQ(b.size, blocks * (r.channels == 4 ? 16 : 8)) << r.name;
      ++images;
    }
  }
  EXPECT_GT(atlases, 0u);
  EXPECT_GT(images, 0u);
  for (const ImageRecord& r : m.images)
    if (r.pieceCount) { EXPECT_EQ(r.pieceCount, 1u) << r.name; }
}

TEST(S3tcBlocks, TheFileHasTheSameBytesAtOneTwoAndSevenThreads) {
  std::vector<uint8_t> first;
  for (uint32_t threads : {1u, 2u, 7u}) {
    TempFile out("tree.mta");
    buildMta(scene(), s3tcParams(BlockEncoding::S3tc, threads), out.path);
    const std::vector<uint8_t> bytes = testing::readBytes(out.path);
    if (first.empty()) first = bytes;
    else EXPECT_TRUE(bytes == first) << threads << " threads";
  }
  EXPECT_FALSE(first.empty());
}

// Layer 1 starts white (blankAtlas): a white area encodes exactly, so the decoded layer-1 atlas of a node
// whose meshes have no layer-1 texture is white everywhere.
TEST(S3tcBlocks, AnAtlasDecodesToLevelZeroWithinTheEncodersErrorAndWhiteStaysWhite) {
  TempFile raw("raw.mta"), s3tc("s3tc.mta");
  buildMta(scene(), s3tcParams(BlockEncoding::Raw), raw.path);
  buildMta(scene(), s3tcParams(BlockEncoding::S3tc), s3tc.path);
  const PagingFile a(raw.path), b(s3tc.path);
  const std::vector<uint8_t> ra = a.readAtlas(0, 0, 0), sa = b.readAtlas(0, 0, 0);
  ASSERT_EQ(ra.size(), sa.size());
  int worst = 0;
  uint64_t sum = 0;
  for (size_t i = 0; i < ra.size(); ++i) {
    const int d = std::abs(int(ra[i]) - int(sa[i]));
    worst = std::max(worst, d), sum += uint64_t(d);
  }
  EXPECT_GT(worst, 0) << "S3TC should not be lossless on these facades";
  // The test facades are noise-like (17.5 measured); a decoder reading the wrong block or level gives errors
  // of the texels' own spread (about 85 for uniform noise) on average.
  EXPECT_LT(double(sum) / double(ra.size()), 32.0) << "worst " << worst;
  const std::vector<uint8_t> white = std::vector<uint8_t>(ra.size(), 255);
  if (a.readAtlas(0, 0, 1) == white) { EXPECT_EQ(b.readAtlas(0, 0, 1), white); }
}

}  // namespace
}  // namespace tessera::mta
