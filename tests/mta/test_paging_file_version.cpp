// Paging file format versions (docs/mta-format.md, "Versions"): since version 2 every original image starts
// blocks of its own; version 3 records the block encoding (raw or S3TC) in the header. Version 1 and 2 files
// are refused with a message that says to rebuild them, an unknown encoding is refused, and a file whose
// metadata packs two images into one block is refused naming the piece, though its checksums are valid.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "base/error.h"
#include "mta/build.h"
#include "mta/paging_file.h"
#include "mta_file_edit.h"
#include "grid_tree_file.h"
#include "mta_test_scene.h"

namespace tessera::mta {
namespace {

using testing::TempFile;

using testing::errorOf;
using testing::expectRefused;
using testing::good;

TEST(PagingFileVersion, AVersion1FileIsRefusedWithAMessageToRebuildIt) {
  TempFile old("old.mta");
  std::vector<uint8_t> bytes = testing::readBytes(good().file.path);
  const uint32_t one = 1;
  std::memcpy(bytes.data() + 8, &one, 4);
  testing::fixHeader(bytes);
  testing::writeBytes(old.path, bytes);
  const std::string m = errorOf(old.path);
  EXPECT_EQ(m.rfind(old.path + ": format version 1: its original images share blocks", 0), 0u) << m;
  EXPECT_NE(m.find("rebuild it with `tessera mta build`"), std::string::npos) << m;
}

TEST(PagingFileVersion, AVersion2FileIsRefusedWithAMessageToRebuildIt) {
  TempFile old("v2.mta");
  std::vector<uint8_t> bytes = testing::readBytes(good().file.path);
  const uint32_t two = 2;
  std::memcpy(bytes.data() + 8, &two, 4);
  testing::fixHeader(bytes);
  testing::writeBytes(old.path, bytes);
  const std::string m = errorOf(old.path);
  EXPECT_EQ(m.rfind(old.path + ": format version 2: its header does not record the block encoding", 0), 0u) << m;
  EXPECT_NE(m.find("rebuild it with `tessera mta build`"), std::string::npos) << m;
}

TEST(PagingFileVersion, AnUnknownBlockEncodingInTheHeaderIsRefused) {
  TempFile bad("encoding.mta");
  std::vector<uint8_t> bytes = testing::readBytes(good().file.path);
  const uint32_t two = 2;  // 0 raw and 1 S3TC are the only encodings
  std::memcpy(bytes.data() + 72, &two, 4);
  testing::fixHeader(bytes);
  testing::writeBytes(bad.path, bytes);
  const std::string m = errorOf(bad.path);
  EXPECT_EQ(m, bad.path + ": header.encoding: 2 is not 0 (raw) or 1 (S3TC)") << m;
}

TEST(PagingFileVersion, TwoImagesInOneOriginalBlockAreRefused) {
  // The version 1 layout: the first two images packed into the first original block. Blocks 0 and 1
  // hold one image each and follow each other without padding, so merging them into block 0 (and
  // renumbering the later blocks) gives a directory that is valid in every other respect.
  const MtaMeta& g = good().meta();
  ASSERT_EQ(g.blocks[0].kind, BlockKind::Original);
  ASSERT_EQ(g.blocks[1].kind, BlockKind::Original);
  ASSERT_EQ(g.pieces[0].block, 0u);
  ASSERT_EQ(g.pieces[1].block, 1u);
  ASSERT_NE(g.pieces[0].image, g.pieces[1].image);
  ASSERT_EQ(g.blocks[0].offset + g.blocks[0].size, g.blocks[1].offset) << "block 0 should need no padding";
  expectRefused(
      [](MtaMeta& m) {
        const uint64_t first = m.blocks[0].size;
        m.blocks[0].size += m.blocks[1].size;
        m.blocks.erase(m.blocks.begin() + 1);
        m.pieces[1].block = 0;
        m.pieces[1].offset = first;
        for (size_t j = 2; j < m.pieces.size(); ++j) --m.pieces[j].block;
        for (Tree& t : m.trees)
          for (uint32_t& b : t.atlasBlocks) b -= b > 1 ? 1 : 0;
      },
      "pieces[1].block",
      "0, which already holds pieces[0] (image " + std::to_string(g.pieces[0].image) +
          "): every original-texture block holds one piece, so each image starts blocks of its own (format version 2)");
}

}  // namespace
}  // namespace tessera::mta
