// Hostile paging files whose checksums are valid: each test changes one metadata field of a valid file,
// recomputes both checksums (mta_file_edit.h) and expects PagingFile to refuse the file with an Error
// naming the file, the record and field, and the reason, before any consumer sees it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>

#include "base/error.h"
#include "mta/build.h"
#include "mta/paging_file.h"
#include "mta/runtime_geometry.h"
#include "mta/traversal.h"
#include "mta_file_edit.h"
#include "grid_tree_file.h"
#include "mta_test_scene.h"

namespace tessera::mta {
namespace {

using testing::TempFile;

using testing::errorOf;
using testing::expectRefused;
using testing::good;

const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// The first leaf of tree t, and the first inner node other than the root.
uint32_t firstLeaf(const MtaMeta& m, size_t t = 0) {
  for (uint32_t i = 0; i < m.trees[t].nodes.size(); ++i)
    if (m.trees[t].nodes[i].leaf()) return i;
  ADD_FAILURE() << "no leaf";
  return 0;
}

TEST(PagingFileValidation, TheUneditedFileIsAcceptedAndTheHelperKeepsItsBytes) {
  EXPECT_EQ(errorOf(good().file.path), "");
  TempFile same("same.mta");
  testing::rewriteMetadata(good().file.path, same.path, [](MtaMeta&) {});
  EXPECT_EQ(testing::readBytes(same.path), testing::readBytes(good().file.path));
  ASSERT_EQ(good().meta().trees.size(), 2u);
  ASSERT_EQ(good().meta().layerCount, 2u);
  // Every image is smaller than a block (4 · 64² bytes), so each stored image is one piece in one block.
  uint64_t stored = 0, originalBlocks = 0;
  for (const ImageRecord& r : good().meta().images) stored += r.pieceCount != 0;
  for (const BlockInfo& b : good().meta().blocks) originalBlocks += b.kind == BlockKind::Original;
  EXPECT_EQ(good().meta().pieces.size(), stored);
  EXPECT_EQ(originalBlocks, stored);
}

TEST(PagingFileValidation, ImageRowsLongerThanABlockAreStoredOneRowPerBlockAndAccepted) {
  // A 6000 x 3 RGB image has 18000-byte rows, more than a 64² atlas's 4 · 64² = 16384-byte block: the
  // builder stores each row as a block of its own, the one case where a block exceeds that size.
  Scene s = testing::gridScene(1, 1);
  s.images[0] = SceneImage{6000, 3, "wide"};
  s.loadImage = [](uint32_t) {
    model::Image img;
    img.width = 6000, img.height = 3;
    img.rgba.assign(size_t(6000) * 3 * 4, 200);
    return img;
  };
  BuildParams p;
  p.atlasSize = 64;
  p.border = 2;
  p.dMin = 1000.0;
  p.encoding = BlockEncoding::Raw;  // row pieces exist in raw files only
  TempFile f("wide.mta");
  buildMta(s, p, f.path);
  EXPECT_EQ(errorOf(f.path), "");
  const PagingFile file(f.path);
  ASSERT_EQ(file.meta().images[0].pieceCount, 3u);
  for (uint32_t k = 0; k < 3; ++k) {
    const PieceRecord& pc = file.meta().pieces[k];
    EXPECT_EQ(pc.rows, 1u);
    EXPECT_EQ(file.meta().blocks[pc.block].size, 18000u);
  }
  EXPECT_EQ(file.readImage(0), std::vector<uint8_t>(size_t(6000) * 3 * 3, 200));
}

// ---- the node table ------------------------------------------------------------------------------------

TEST(PagingFile, ChildIndicesOutOfRangeAreRefusedEvenWithValidChecksums) {
  // The outside fuzz campaign's finding: the root's four children -5 made the root a leaf covering every
  // triangle, on top of the real leaves, and buildRuntimeGeometry wrote past its vertex array.
  expectRefused(
      [](MtaMeta& m) {
        m.trees[0].nodes[0].children = {-5, -5, -5, -5};
      },
      "trees[0].nodes[0].children[0]", "-5 is neither -1 (no child) nor the index of a later node");
  expectRefused([](MtaMeta& m) { m.trees[1].nodes[0].children[2] = int32_t(m.trees[1].nodes.size()); },
                "trees[1].nodes[0].children[2]", "is neither -1");
}

TEST(PagingFile, AChildIndexNamingItsOwnNodeIsRefused) {
  expectRefused([](MtaMeta& m) { m.trees[0].nodes[1].children[0] = 1; }, "trees[0].nodes[1].children[0]",
                "1 is neither -1");
}

TEST(PagingFile, AChildIndexPointingBackToAnAncestorIsRefused) {
  // nodes[2] is a child of nodes[1]: a link back to 1 would make a cycle.
  ASSERT_EQ(good().meta().trees[0].nodes[2].parent, 1);
  expectRefused([](MtaMeta& m) { m.trees[0].nodes[2].children[0] = 1; }, "trees[0].nodes[2].children[0]",
                "1 is neither -1");
}

TEST(PagingFile, ANodeListedAsTheChildOfTwoParentsIsRefused) {
  // nodes[8] is the first child of nodes[7]; nodes[2], in a sibling subtree, claiming it too makes a DAG.
  const Tree& t = good().meta().trees[0];
  ASSERT_EQ(t.nodes[8].parent, 7);
  ASSERT_EQ(t.nodes[2].children[3], 6);
  expectRefused([&](MtaMeta& m) { m.trees[0].nodes[2].children[3] = 8; }, "trees[0].nodes[8].parent",
                "7, but trees[0].nodes[2] lists it as child 3");
  // A link to an earlier node is refused as such: in pre-order a second parent always comes later.
  expectRefused([&](MtaMeta& m) { m.trees[0].nodes[33].children[0] = 3; }, "trees[0].nodes[33].children[0]",
                "3 is neither -1");
}

TEST(PagingFile, ALeafThatNoParentListsIsRefused) {
  // A copy of a leaf appended as an orphan: its triangles would be drawn twice and written twice into the
  // runtime vertex array.
  expectRefused(
      [](MtaMeta& m) {
        Tree& t = m.trees[0];
        t.nodes.push_back(t.nodes[firstLeaf(m)]);
        for (uint32_t l = 0; l < m.layerCount; ++l)
          t.atlasBlocks.push_back(t.atlasBlocks[firstLeaf(m) * m.layerCount + l]);
      },
      "trees[0].nodes[125]", "is not reachable from the root");
}

TEST(PagingFile, NodesNotInDepthFirstPreOrderAreRefused) {
  // The root's first two subtrees' top records swapped (and the root's links with them): still a tree,
  // but leaves would no longer come in the order of their triangle ranges.
  expectRefused(
      [](MtaMeta& m) {
        Tree& t = m.trees[0];
        const int32_t a = t.nodes[0].children[0], b = t.nodes[0].children[1];
        std::swap(t.nodes[size_t(a)], t.nodes[size_t(b)]);
        std::swap(t.nodes[0].children[0], t.nodes[0].children[1]);
      },
      "trees[0].nodes[32]", "is reached at position 1 of the depth-first walk");
}

TEST(PagingFile, AChildWhoseParentFieldNamesAnotherNodeIsRefused) {
  expectRefused([](MtaMeta& m) { m.trees[0].nodes[2].parent = 7; }, "trees[0].nodes[2].parent",
                "7, but trees[0].nodes[1] lists it as child 0");
}

TEST(PagingFile, AChildOnTheWrongLevelIsRefused) {
  expectRefused([](MtaMeta& m) { m.trees[0].nodes[2].level = 5; }, "trees[0].nodes[2].level", "5, but");
}

TEST(PagingFile, ANonFiniteNodeBoundIsRefused) {
  expectRefused([](MtaMeta& m) { m.trees[0].nodes[3].bounds[4] = float(kNan); }, "trees[0].nodes[3].bounds",
                "is not finite");
}

TEST(PagingFile, LeafBoundsThatMissAVertexAreRefused) {
  // Culling would drop a visible triangle.
  expectRefused([](MtaMeta& m) { m.trees[0].nodes[3].bounds[3] -= 0.25f; }, "trees[0].nodes[3].bounds",
                "does not contain vertex");
}

TEST(PagingFile, InnerBoundsThatMissAChildAreRefused) {
  expectRefused([](MtaMeta& m) { m.trees[0].nodes[2].bounds[0] += 0.25f; }, "trees[0].nodes[2].bounds",
                "does not contain child");
}

TEST(PagingFile, ANegativeMinDistanceIsRefused) {
  expectRefused([](MtaMeta& m) { m.trees[0].nodes[3].minDistance = -1.0f; }, "trees[0].nodes[3].min_distance",
                "-1 is not a finite number > 0");
}

TEST(PagingFile, AnInnerMinDistanceBelowTwiceAChildsIsRefused) {
  expectRefused([](MtaMeta& m) { m.trees[0].nodes[2].minDistance = m.trees[0].nodes[3].minDistance; },
                "trees[0].nodes[2].min_distance", "is less than twice child 3's");
}

TEST(PagingFile, ACoverageAboveOneIsRefused) {
  expectRefused([](MtaMeta& m) { m.trees[0].nodes[3].coverage = 1.5f; }, "trees[0].nodes[3].coverage",
                "1.5 is outside [0, 1]");
}

TEST(PagingFile, ALeafRangePastTheVertexArrayIsRefused) {
  // Caught where the ranges nest: at its parent, whose children then end past its own range.
  ASSERT_EQ(good().meta().trees[0].nodes[124].parent, 118);
  expectRefused([](MtaMeta& m) { m.trees[0].nodes[124].triangleCount = 1000; }, "trees[0].nodes[118].triangle_count",
                "its children's triangles end at 1100, its own range at 102");
  expectRefused([](MtaMeta& m) { m.trees[0].nodes[0].triangleCount = 1000; }, "trees[0].nodes[0].triangle_count",
                "not every triangle [0, 102)");
}

TEST(PagingFile, AnEmptyChildIsRefused) {
  expectRefused(
      [](MtaMeta& m) {
        m.trees[0].nodes[5].triangleCount = 0;  // nodes[6] takes its triangles
        m.trees[0].nodes[6].firstTriangle = 2, m.trees[0].nodes[6].triangleCount = 4;
      },
      "trees[0].nodes[5].first_triangle", "triangles [2, +0) do not continue");
}

TEST(PagingFile, ALeafImageListMissingAnImageItsTrianglesUseIsRefused) {
  // The memory manager would not load that image before the leaf is drawn with its original textures.
  const uint32_t leaf = firstLeaf(good().meta());
  ASSERT_EQ(good().meta().trees[0].nodes[leaf].imageCount, 2u);
  const uint32_t lacking = good().meta().trees[0].leafImages[good().meta().trees[0].nodes[leaf].imageFirst + 1];
  expectRefused([&](MtaMeta& m) { m.trees[0].nodes[leaf].imageCount = 1; },
                "trees[0].nodes[" + std::to_string(leaf) + "].image_count",
                "its triangles use image " + std::to_string(lacking) + ", which its image list lacks");
}

TEST(PagingFile, ALeafImageOutOfRangeIsRefused) {
  expectRefused([](MtaMeta& m) { m.trees[0].leafImages[1] = 5000; }, "trees[0].nodes[3].images[1]",
                "5000 is out of range");
}

TEST(PagingFile, ALeafImageListRunningPastTheTableIsRefused) {
  expectRefused([](MtaMeta& m) { m.trees[1].nodes[2].imageCount = 1000; }, "trees[1].nodes[2].image_count",
                "run past the tree's 42 leaf image entries");
}

TEST(PagingFile, ANodeDeeperThanTheFormatAllowsIsRefused) {
  // A chain of single children, each on the next level: what the format allows is 60 levels below the
  // root. One untextured triangle, so that no images are needed; every node has its atlas block.
  auto chain = [](uint32_t levels, const std::string& path) {
    MtaMeta m;
    m.params.atlasSize = 64;
    m.params.border = 2;
    m.params.tanHalfFov = 0.5;
    m.params.dMin = 1.0;
    m.layerCount = 1;
    m.stats.trianglesIn = m.stats.trianglesOut = 1;
    m.stats.dMinRequested = m.stats.dMinUsed = 1.0;
    Tree t;
    t.geometry.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    t.geometry.source = {0};
    t.geometry.alpha = {0};
    t.geometry.layers.resize(1);
    t.geometry.layers[0].texture = {-1};
    t.geometry.layers[0].uv.assign(3, glm::vec2{0.5f, 0.5f});
    t.atlasUV.assign(3, glm::vec2{0.5f, 0.5f});
    PagingFileWriter w(path);
    const std::vector<uint8_t> atlas(64 * 64 * 3, 0);
    for (uint32_t i = 0; i <= levels; ++i) {
      Node n;
      n.bounds = {0, 0, 0, 1, 1, 0};
      n.minDistance = std::ldexp(1.0f, int(levels - i));
      n.level = i;
      n.parent = int32_t(i) - 1;
      n.triangleCount = 1;
      if (i < levels) n.children[0] = int32_t(i) + 1;
      t.nodes.push_back(n);
      t.atlasBlocks.push_back(w.addBlock(BlockKind::Atlas, 0, 0, i, atlas));
    }
    m.trees.push_back(t);
    w.finish(m);
  };
  TempFile deepest("deepest.mta"), tooDeep("too_deep.mta");
  chain(kMaxNodeLevel, deepest.path);
  EXPECT_EQ(errorOf(deepest.path), "");
  chain(kMaxNodeLevel + 1, tooDeep.path);
  const std::string m = errorOf(tooDeep.path);
  EXPECT_NE(m.find("trees[0].nodes[61].level: 61: deeper than the format's 60 levels"), std::string::npos) << m;
}

// ---- the parameters and statistics ---------------------------------------------------------------------

TEST(PagingFile, AFieldOfViewOf200DegreesIsRefused) {
  expectRefused([](MtaMeta& m) { m.params.fovDegrees = 200.0; }, "parameters.fov_degrees", "200 is outside (0, 180)");
}

TEST(PagingFile, ANanFieldOfViewIsRefused) {
  expectRefused([](MtaMeta& m) { m.params.fovDegrees = kNan; }, "parameters.fov_degrees", "nan is outside (0, 180)");
}

TEST(PagingFile, AScreenWidthOf0xffffffffIsRefused) {
  expectRefused([](MtaMeta& m) { m.params.screenWidth = 0xffffffffu; }, "parameters.screen_width",
                "4294967295 is outside [1, 16384]");
}

TEST(PagingFile, AScreenWidthOf0IsRefused) {
  expectRefused([](MtaMeta& m) { m.params.screenWidth = 0; }, "parameters.screen_width", "0 is outside [1, 16384]");
}

TEST(PagingFile, ANanTauIsRefused) {
  expectRefused([](MtaMeta& m) { m.params.tau = kNan; }, "parameters.tau", "nan is not a finite number > 0");
}

TEST(PagingFile, ATauOf0IsRefused) {
  expectRefused([](MtaMeta& m) { m.params.tau = 0.0; }, "parameters.tau", "0 is not a finite number > 0");
}

TEST(PagingFile, AnInfiniteDMinIsRefused) {
  expectRefused([](MtaMeta& m) { m.params.dMin = kInf; }, "parameters.d_min", "inf is not a finite number >= 0");
}

TEST(PagingFile, ANegativeDMinDivisorIsRefused) {
  expectRefused([](MtaMeta& m) { m.params.dMinDivisor = -72.0; }, "parameters.d_min_divisor",
                "-72 is not a finite number > 0");
}

TEST(PagingFile, ATanHalfFovOf0IsRefused) {
  // A file stores the value used; 0 ("derive it from the field of view") is an option of the build only.
  expectRefused([](MtaMeta& m) { m.params.tanHalfFov = 0.0; }, "parameters.tan_half_fov",
                "0 is outside [1e-06, 1000000]");
}

TEST(PagingFile, AnInfiniteTanHalfFovIsRefused) {
  expectRefused([](MtaMeta& m) { m.params.tanHalfFov = kInf; }, "parameters.tan_half_fov", "inf is outside");
}

TEST(PagingFile, AnAtlasSizeOf100IsRefused) {
  expectRefused([](MtaMeta& m) { m.params.atlasSize = 100; }, "parameters.atlas_size",
                "100 is not a power of two in [64, 8192]");
}

TEST(PagingFile, ABorderThatDoesNotFitHalfAnAtlasIsRefused) {
  expectRefused([](MtaMeta& m) { m.params.border = 16; }, "parameters.border", "must fit in half an atlas");
}

TEST(PagingFile, ACriticalThresholdAboveOneIsRefused) {
  expectRefused([](MtaMeta& m) { m.params.criticalThreshold = 1.5; }, "parameters.critical_threshold",
                "1.5 is outside [0, 1]");
}

TEST(PagingFile, ALayerCountOf17IsRefused) {
  TempFile bad("bad.mta");
  testing::rewriteMetadataBytes(good().file.path, bad.path, [](std::vector<uint8_t>& meta) { meta[0] = 17; });
  const std::string m = errorOf(bad.path);
  EXPECT_NE(m.find("layer_count: 17 outside [1, 16]"), std::string::npos) << m;
}

TEST(PagingFile, ANanSceneDiagonalIsRefused) {
  expectRefused([](MtaMeta& m) { m.stats.sceneDiagonal = kNan; }, "stats.scene_diagonal",
                "nan is not a finite number >= 0");
}

TEST(PagingFile, ADMinUsedBelowTheRequestedOneIsRefused) {
  expectRefused([](MtaMeta& m) { m.stats.dMinUsed = 1.0; }, "stats.d_min_used",
                "1 is not a finite number >= d_min_requested (2)");
}

TEST(PagingFile, ATriangleCountThatDisagreesWithTheTreesIsRefused) {
  expectRefused(
      [](MtaMeta& m) {
        m.stats.trianglesOut += 1;
        m.stats.trianglesAdded += 1;
      },
      "stats.triangles_out", "129, but the trees hold 128 triangles");
}

// ---- geometry --------------------------------------------------------------------------------------------

TEST(PagingFile, NanTexcoordsAreRefused) {
  expectRefused([](MtaMeta& m) { m.trees[0].geometry.layers[1].uv[7].y = float(kNan); }, "trees[0].layers[1].uv[7]",
                "not finite");
}

TEST(PagingFile, InfiniteAtlasTexcoordsAreRefused) {
  expectRefused([](MtaMeta& m) { m.trees[1].atlasUV[4].x = float(kInf); }, "trees[1].atlas_uv[4]", "not finite");
}

TEST(PagingFile, NanPositionsAreRefused) {
  expectRefused([](MtaMeta& m) { m.trees[0].geometry.positions[5].z = float(kNan); }, "trees[0].positions[5]",
                "not finite");
}

TEST(PagingFile, ATextureIndexOfMinus2IsRefused) {
  expectRefused([](MtaMeta& m) { m.trees[0].geometry.layers[0].texture[9] = -2; }, "trees[0].layers[0].texture[9]",
                "-2 is neither -1 (none) nor a texture index (128 textures)");
}

TEST(PagingFile, ATextureIndexPastTheTexturesIsRefused) {
  expectRefused([](MtaMeta& m) { m.trees[1].geometry.layers[0].texture[0] = 192; }, "trees[1].layers[0].texture[0]",
                "192 is neither -1");
}

TEST(PagingFile, ATextureNamingAMissingImageIsRefused) {
  expectRefused([](MtaMeta& m) { m.textures[3].image = 192; }, "textures[3].image", "192 is out of range (128 images)");
}

// ---- the block directory ---------------------------------------------------------------------------------

size_t firstBlockOf(const MtaMeta& m, BlockKind kind) {
  for (size_t i = 0; i < m.blocks.size(); ++i)
    if (m.blocks[i].kind == kind) return i;
  ADD_FAILURE() << "no block of kind " << int(kind);
  return 0;
}

TEST(PagingFile, ABlockDirectoryEntryNamingAMissingNodeIsRefused) {
  const size_t b = firstBlockOf(good().meta(), BlockKind::Atlas);
  expectRefused([&](MtaMeta& m) { m.blocks[b].node = 125; }, "blocks[" + std::to_string(b) + "].node",
                "125 is out of range (tree 0 has 125 nodes)");
}

TEST(PagingFile, ABlockDirectoryEntryNamingAMissingTreeIsRefused) {
  const size_t b = firstBlockOf(good().meta(), BlockKind::Atlas);
  expectRefused([&](MtaMeta& m) { m.blocks[b].tree = 2; }, "blocks[" + std::to_string(b) + "].tree",
                "2 is out of range (2 trees)");
}

TEST(PagingFile, ABlockDirectoryEntryNamingAMissingLayerIsRefused) {
  const size_t b = firstBlockOf(good().meta(), BlockKind::Atlas);
  expectRefused([&](MtaMeta& m) { m.blocks[b].layer = 2; }, "blocks[" + std::to_string(b) + "].layer",
                "2 is out of range (2 layers)");
}

TEST(PagingFile, TwoAtlasBlocksForOneNodeAreRefused) {
  // Block b claims to be the layer-0 atlas of the node whose atlas block is another one.
  const MtaMeta& g = good().meta();
  const size_t b = firstBlockOf(g, BlockKind::Atlas);
  const uint32_t other = g.blocks[b].node == 3 ? 4 : 3;
  expectRefused(
      [&](MtaMeta& m) {
        m.blocks[b].node = other;
        m.blocks[b].layer = 0;
      },
      "blocks[" + std::to_string(b) + "].node",
      "whose atlas is blocks[" + std::to_string(g.trees[0].atlasBlocks[other * 2]) + "]");
}

TEST(PagingFile, AnAtlasTableEntryNamingAnOriginalBlockIsRefused) {
  const size_t o = firstBlockOf(good().meta(), BlockKind::Original);
  expectRefused([&](MtaMeta& m) { m.trees[1].atlasBlocks[0] = uint32_t(o); },
                "blocks[" + std::to_string(good().meta().trees[1].atlasBlocks[0]) + "].node",
                "whose atlas is blocks[" + std::to_string(o) + "]");
}

TEST(PagingFile, AnAtlasBlockOfTheWrongSizeIsRefused) {
  const size_t b = firstBlockOf(good().meta(), BlockKind::Atlas);
  expectRefused([&](MtaMeta& m) { m.blocks[b].size -= 16; }, "blocks[" + std::to_string(b) + "].size",
                "expected 12288 (64² texels of 3 bytes)");
}

TEST(PagingFile, ABlockWhoseOffsetPlusSizeOverflowsIsRefused) {
  const size_t b = good().meta().blocks.size() - 1;
  expectRefused([&](MtaMeta& m) { m.blocks[b].size = UINT64_MAX - m.blocks[b].offset + 1; },
                "blocks[" + std::to_string(b) + "].size", "runs past the block area");
}

TEST(PagingFile, OverlappingBlocksAreRefused) {
  expectRefused([](MtaMeta& m) { m.blocks[1].offset = m.blocks[0].offset; }, "blocks[1].offset",
                "expected " + std::to_string(good().meta().blocks[1].offset));
}

TEST(PagingFile, ABlockOfAnUnknownKindIsRefused) {
  expectRefused([](MtaMeta& m) { m.blocks[2].kind = BlockKind(7); }, "blocks[2].kind",
                "7 is not 1 (atlas) or 2 (original)");
}

TEST(PagingFile, ABlockWithANonZeroPaddingByteIsRefused) {
  TempFile bad("bad.mta");
  const size_t at =
      testing::blockDirectoryOffset(good().meta()) + 56 * 3 + 19;  // blocks[3]: offset, size, kind, tree, layer, pad
  testing::rewriteMetadataBytes(good().file.path, bad.path, [&](std::vector<uint8_t>& meta) { meta[at] = 1; });
  const std::string m = errorOf(bad.path);
  EXPECT_NE(m.find("blocks[3].pad: 1 (must be 0)"), std::string::npos) << m;
}

// ---- images and pieces -------------------------------------------------------------------------------------

TEST(PagingFile, AnImageWiderThan65536IsRefused) {
  expectRefused([](MtaMeta& m) { m.images[4].width = 70000; }, "images[4].width", "70000 is outside [1, 65536]");
}

TEST(PagingFile, AnImageOfHeight0IsRefused) {
  expectRefused([](MtaMeta& m) { m.images[4].height = 0; }, "images[4].height", "0 is outside [1, 65536]");
}

TEST(PagingFile, AnImageWithFiveChannelsIsRefused) {
  expectRefused([](MtaMeta& m) { m.images[4].channels = 5; }, "images[4].channels", "5 is not 3 or 4");
}

TEST(PagingFile, AnImageChannelCountThatDisagreesWithItsStoredBytesIsRefused) {
  // Image 1 (32 x 32) is stored with 3 channels, 3072 bytes, alone in block 0: with 4 channels its piece
  // would fill 4096 bytes, more than the block holds.
  ASSERT_EQ(good().meta().images[1].channels, 3u);
  ASSERT_EQ(good().meta().images[1].firstPiece, 0u);
  ASSERT_EQ(good().meta().pieces[0].block, 0u);
  expectRefused([](MtaMeta& m) { m.images[1].channels = 4; }, "blocks[0].size",
                "3072, but its piece (pieces[0]: 32 rows of 128 bytes) fills 4096 bytes");
}

TEST(PagingFile, AnImageWidthThatDisagreesWithItsStoredBytesIsRefused) {
  // Wider rows than stored: a read of the image would copy past its piece's bytes.
  expectRefused([](MtaMeta& m) { m.images[1].width = 64; }, "blocks[0].size",
                "3072, but its piece (pieces[0]: 32 rows of 192 bytes) fills 6144 bytes");
}

TEST(PagingFile, APieceRunningPastItsImageRowsIsRefused) {
  const ImageRecord& r = good().meta().images[1];
  const uint32_t last = r.firstPiece + r.pieceCount - 1;
  expectRefused([&](MtaMeta& m) { m.pieces[last].rows += 1; }, "pieces[" + std::to_string(last) + "].rows",
                "are not a non-empty range inside the image's 32 rows");
}

TEST(PagingFile, APieceOutsideItsBlockIsRefused) {
  const ImageRecord& r = good().meta().images[1];
  expectRefused([&](MtaMeta& m) { m.pieces[r.firstPiece].offset += 1u << 20; },
                "pieces[" + std::to_string(r.firstPiece) + "].offset", "expected 0 (a block holds one piece)");
}

TEST(PagingFile, APieceInAnAtlasBlockIsRefused) {
  const ImageRecord& r = good().meta().images[1];
  const uint32_t atlas = good().meta().trees[0].atlasBlocks[0];
  expectRefused([&](MtaMeta& m) { m.pieces[r.firstPiece].block = atlas; },
                "pieces[" + std::to_string(r.firstPiece) + "].block",
                "(pieces fill the original-texture blocks in directory order)");
}

TEST(PagingFile, TooManyLeafBlockReferencesAreRefused) {
  // Every leaf counts the pieces of each image it lists (what the memory manager's block index holds).
  uint64_t refs = 0;
  for (const Tree& t : good().meta().trees)
    for (const Node& n : t.nodes)
      for (uint32_t k = 0; n.leaf() && k < n.imageCount; ++k)
        refs += good().meta().images[t.leafImages[n.imageFirst + k]].pieceCount;
  ASSERT_GT(refs, good().meta().trees[0].leafImages.size());
  ResourceLimits limits;
  limits.mtaLeafBlockRefs = refs;
  EXPECT_EQ(errorOf(good().file.path, limits), "");
  // Tree 0's references alone exceed a limit of 10.
  limits.mtaLeafBlockRefs = 10;
  const std::string m = errorOf(good().file.path, limits);
  EXPECT_NE(m.find("trees[0].leaf_images: needs "), std::string::npos) << m;
  EXPECT_NE(m.find("original-texture block references (per leaf and image piece), over the limit of 10 by "),
            std::string::npos)
      << m;
}

// ---- opening ------------------------------------------------------------------------------------------------

size_t openDescriptors() {
  size_t n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator("/proc/self/fd")) ++n;
  return n;
}

TEST(PagingFile, ARefusedFileLeavesNoDescriptorOpen) {
  // The constructor opened the file, then threw: no destructor ran, and every refused file kept its
  // descriptor (a fuzz run ran out of them). Refused on the header, and refused by the validator.
  TempFile shortFile("short.mta"), bad("bad.mta");
  testing::writeBytes(shortFile.path, std::vector<uint8_t>(100, 0));
  testing::rewriteMetadata(good().file.path, bad.path, [](MtaMeta& m) { m.params.tau = 0.0; });
  const size_t before = openDescriptors();
  for (int i = 0; i < 50; ++i) {
    EXPECT_NE(errorOf(shortFile.path).find("truncated"), std::string::npos);
    EXPECT_NE(errorOf(bad.path).find("parameters.tau"), std::string::npos);
  }
  EXPECT_EQ(openDescriptors(), before);
}

TEST(PagingFile, ADirectoryIsRefusedAsSuch) {
  const std::string dir = std::filesystem::temp_directory_path().string();
  EXPECT_EQ(errorOf(dir), dir + ": is a directory, not an atlas tree file");
}

// ---- the consumers' own checks ---------------------------------------------------------------------------

TEST(RuntimeGeometry, OverlappingLeavesAreAnErrorNotAHeapOverflow) {
  // What the -5 children did to buildRuntimeGeometry before the validator refused them: the root became a
  // leaf over every triangle while the real leaves still listed theirs.
  MtaMeta m = good().meta();
  m.trees[0].nodes[0].children = {-5, -5, -5, -5};
  try {
    buildRuntimeGeometry(m);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("overlaps another leaf's triangles"), std::string::npos) << e.what();
  }
}

TEST(BlockIndex, ChildIndicesThatDoNotIncreaseAreAnErrorNotAnEndlessWalk) {
  MtaMeta m = good().meta();
  m.trees[1].nodes[2].children[0] = 1;
  try {
    buildBlockIndex(m, LayerMask(1));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("tree 1 node 2: child index 1 out of range"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tessera::mta
