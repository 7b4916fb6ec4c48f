// Build to a paging file and read it back: round trip, determinism, atlas texels, corruption.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "mta/atlas_image.h"
#include "mta/build.h"
#include "mta/info.h"
#include "mta/paging_file.h"
#include "mta_test_scene.h"
#include "base/error.h"
#include "raster/texture.h"

namespace tessera::mta {
namespace {

using testing::gridScene;
using testing::TempFile;

BuildParams pagingParams(uint32_t threads = 0) {
  BuildParams p;
  p.atlasSize = 64;
  p.border = 2;
  p.tanHalfFov = 0.5;
  p.screenWidth = 256;
  p.dMin = 2.0;
  p.threads = threads;
  p.encoding = BlockEncoding::Raw;  // the round trip compares exact texels (test_s3tc_blocks.cpp: S3TC)
  return p;
}

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}
void spit(const std::string& path, const std::string& bytes) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(bytes.data(), std::streamsize(bytes.size()));
}

TEST(PagingFile, RoundTripKeepsTheTreeTheImagesAndEveryChecksum) {
  const Scene s = gridScene(8, 8, 32, 2.0f, false, true);
  TempFile out("tree.mta");
  buildMta(s, pagingParams(), out.path);
  const PagingFile f(out.path);
  const MtaMeta& m = f.meta();
  ASSERT_EQ(m.trees.size(), 2u);  // RGB and RGBA
  EXPECT_EQ(m.trees[0].alpha, 0);
  EXPECT_EQ(m.trees[1].alpha, 1);
  EXPECT_EQ(m.trees[0].geometry.triangleCount() + m.trees[1].geometry.triangleCount(), m.stats.trianglesOut);
  for (uint32_t b = 0; b < m.blocks.size(); ++b) EXPECT_NO_THROW(f.readBlock(b));
  // Every stored image equals the source, with the tree's channel count.
  for (uint32_t i = 0; i < m.images.size(); ++i) {
    ASSERT_GT(m.images[i].pieceCount, 0u);
    const std::vector<uint8_t> px = f.readImage(i);
    const model::Image src = s.loadImage(i);
    const uint32_t C = m.images[i].channels;
    EXPECT_EQ(C, i % 5 == 0 ? 4u : 3u);
    for (size_t t = 0; t < size_t(src.width) * src.height; ++t)
      for (uint32_t c = 0; c < C; ++c) ASSERT_EQ(px[t * C + c], src.rgba[t * 4 + c]);
  }
  // Inner atlases are the children downsampled 2x into their quadrants.
  const uint32_t A = m.params.atlasSize;
  for (uint32_t ti = 0; ti < m.trees.size(); ++ti) {
    const Tree& t = m.trees[ti];
    for (uint32_t n = 0; n < t.nodes.size(); ++n) {
      if (t.nodes[n].leaf()) continue;
      std::vector<uint8_t> expect(size_t(A) * A * t.channels(), 0);
      for (int q = 0; q < 4; ++q)
        if (t.nodes[n].children[q] >= 0)
          downsampleIntoQuadrant(f.readAtlas(ti, t.nodes[n].children[q]).data(), expect.data(), A, t.channels(), q);
      ASSERT_EQ(f.readAtlas(ti, n), expect) << "tree " << ti << " node " << n;
    }
  }
  const nlohmann::json j = describe(f, true);
  EXPECT_EQ(j["blocks_verified"].get<size_t>(), m.blocks.size());
  EXPECT_GT(j["trees"][0]["leaf_atlas_coverage_mean"].get<double>(), 0.0);
}

TEST(PagingFile, TheBytesDoNotDependOnTheThreadCount) {
  const Scene s = gridScene(6, 6, 32, 3.0f, true);
  TempFile a("a.mta"), b("b.mta");
  buildMta(s, pagingParams(1), a.path);
  buildMta(s, pagingParams(2), b.path);
  EXPECT_EQ(slurp(a.path), slurp(b.path));
}

TEST(PagingFile, SecondLayerSharesTheParameterization) {
  const Scene s = gridScene(3, 3, 32, 1.0f, true);
  TempFile out("layers.mta");
  BuildParams p = pagingParams();
  p.dMin = 1000.0;  // one leaf
  buildMta(s, p, out.path);
  const PagingFile f(out.path);
  ASSERT_EQ(f.meta().layerCount, 2u);
  const std::vector<uint8_t> l0 = f.readAtlas(0, 0, 0), l1 = f.readAtlas(0, 0, 1);
  EXPECT_NE(l0, l1);
  size_t nonZero = 0;
  for (uint8_t x : l1) nonZero += x != 0;
  EXPECT_GT(nonZero, 0u);
}

TEST(AtlasImage, DownsamplingIsTheBoxFilterOfTheMipChain) {
  const uint32_t A = 64;
  std::vector<uint8_t> img(A * A * 4);
  uint32_t seed = 7;
  for (uint8_t& x : img) seed = seed * 1103515245u + 12345u, x = uint8_t(seed >> 16);
  const auto chain = buildMipChainRGBA8(A, A, img);
  std::vector<uint8_t> parent(A * A * 4, 0);
  downsampleIntoQuadrant(img.data(), parent.data(), A, 4, 3);
  for (uint32_t y = 0; y < A / 2; ++y)
    for (uint32_t x = 0; x < A / 2; ++x)
      for (int c = 0; c < 4; ++c)
        ASSERT_EQ(parent[((y + A / 2) * A + x + A / 2) * 4 + c], chain[1][(y * (A / 2) + x) * 4 + c]);
}

TEST(PagingFile, CorruptionIsAClearErrorNeverACrash) {
  const Scene s = gridScene(4, 4);
  TempFile out("c.mta"), bad("bad.mta");
  buildMta(s, pagingParams(), out.path);
  const std::string good = slurp(out.path);
  auto expectError = [&](const std::string& bytes, const std::string& what, bool onBlocks) {
    spit(bad.path, bytes);
    try {
      const PagingFile f(bad.path);
      if (onBlocks)
        for (uint32_t b = 0; b < f.meta().blocks.size(); ++b) f.readBlock(b);
      ADD_FAILURE() << "no error for " << what;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(bad.path), std::string::npos) << e.what();
    }
  };
  expectError(good.substr(0, good.size() / 2), "truncated", false);
  expectError(good.substr(0, 100), "truncated", false);
  expectError(std::string(), "truncated", false);
  std::string flipped = good;
  flipped[200] ^= 0x40;  // inside the first block
  expectError(flipped, "checksum mismatch", true);
  flipped = good;
  flipped[good.size() - 10] ^= 1;  // metadata
  expectError(flipped, "metadata checksum mismatch", false);
  flipped = good;
  flipped[20] ^= 1;  // header
  expectError(flipped, "header checksum mismatch", false);
  flipped = good;
  flipped[0] = 'X';
  expectError(flipped, "bad magic", false);
  // Every single-byte flip at a stride inside the header, a block or the metadata is detected.
  const PagingFile ref(out.path);
  auto covered = [&](size_t i) {
    if (i < 128) return true;
    for (const BlockInfo& b : ref.meta().blocks)
      if (i >= b.offset && i < b.offset + b.size) return true;
    return i >= ref.meta().blocks.back().offset + ref.meta().blocks.back().size + 16;  // metadata (after padding)
  };
  size_t checked = 0;
  for (size_t i = 0; i < good.size(); i += 331) {
    if (!covered(i)) continue;
    std::string x = good;
    x[i] ^= 0x10;
    spit(bad.path, x);
    bool detected = false;
    try {
      const PagingFile f(bad.path);
      for (uint32_t b = 0; b < f.meta().blocks.size(); ++b) f.readBlock(b);
    } catch (const Error&) {
      detected = true;
    }
    EXPECT_TRUE(detected) << "flip at byte " << i;
    ++checked;
  }
  EXPECT_GT(checked, 10u);
}

TEST(PagingFile, MissingOutputDirectoryLeavesNothingBehind) {
  const Scene s = gridScene(2, 2);
  EXPECT_THROW(buildMta(s, pagingParams(), "/nonexistent_dir_mta/x.mta"), Error);
  BuildParams p = pagingParams();
  p.atlasSize = 100;
  TempFile out("p.mta");
  EXPECT_THROW(buildMta(s, p, out.path), Error);
  EXPECT_FALSE(std::filesystem::exists(out.path));
}

}  // namespace
}  // namespace tessera::mta
