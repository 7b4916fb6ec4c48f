// Texture-array batching of the real railway.glb (data/): the input batches, the output at the
// default limits, and the effect of a_max and d_max on it.
#include <gtest/gtest.h>

#include <set>

#include <tbb/global_control.h>

#include "batching/batcher.h"
#include "batching/input_batches.h"
#include "batching/tab_file.h"
#include "batching/tab_stats.h"
#include "model/model.h"

namespace tessera::batching {
namespace {

const TabScene& railwayInput() {
  static const TabScene s = prepareInput(model::loadModel(TESSERA_SOURCE_DIR "/data/railway.glb"));
  return s;
}

TEST(TabRailway, ThirtyThreeMeshesShareTwentyEightTexturesOfNineResolutions) {
  const TabScene& s = railwayInput();
  EXPECT_EQ(s.meshes.size(), 33u);
  EXPECT_EQ(s.textures.size(), 28u);
  std::set<std::pair<uint32_t, uint32_t>> sizes;
  for (const TabTexture& t : s.textures) sizes.insert({t.width, t.height});
  EXPECT_EQ(sizes.size(), 9u);
  EXPECT_TRUE(sizes.count({168, 336}));
  EXPECT_TRUE(sizes.count({256, 187}));
  uint32_t vertices = 0;
  for (const TabMesh& m : s.meshes) {
    EXPECT_EQ(m.kind, MeshKind::Batched);
    EXPECT_EQ(m.textures.size(), 1u);
    vertices += m.vertexCount;
  }
  EXPECT_EQ(vertices, 26797u * 3);  // non-indexed: 3 vertices per triangle
  // Sorted by (format, resolution, sampler, texture): the resolutions never go back.
  for (size_t i = 1; i < s.meshes.size(); ++i) {
    const TabTexture& a = s.textures[s.meshes[i - 1].textures[0]];
    const TabTexture& b = s.textures[s.meshes[i].textures[0]];
    EXPECT_LE(std::make_pair(a.width, a.height), std::make_pair(b.width, b.height));
  }
}

TEST(TabRailway, NineResolutionsNeedTwoOutputBatchesAtEightArrays) {
  TabScene s = railwayInput();
  runAlgorithm1(s, TabParams{});
  EXPECT_EQ(s.batches.size(), 2u);
  EXPECT_EQ(s.arrays.size(), 9u);
  const nlohmann::json t = tableOneJson(s);
  EXPECT_EQ(t["input_batches"], 33u);
  EXPECT_EQ(t["geometry_batches"], 2u);
  EXPECT_EQ(t["textures"], 28u);
  EXPECT_EQ(t["o_tam_bytes"], 33u * 36u);
  EXPECT_EQ(t["texture_bytes_duplicated"], 0u);  // each resolution's textures land in one batch
}

TEST(TabRailway, OneLayerPerArrayMakesOneArrayPerTexture) {
  TabScene s = railwayInput();
  runAlgorithm1(s, TabParams{1u << 20, 1, 8});
  EXPECT_EQ(s.arrays.size(), 28u);
  EXPECT_EQ(s.batches.size(), 4u);  // ceil(28 / 8)
}

}  // namespace
}  // namespace tessera::batching

namespace tessera::batching {
namespace {

TEST(TabBatcher, SameInputGivesTheSameBytes) {
  // The whole build — decoding in parallel, mip chains, sort, Algorithm 1, encoding — at 1 thread and at
  // the default parallelism.
  auto build = [](size_t threads) {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, threads);
    TabScene s = prepareInput(model::loadModel(TESSERA_SOURCE_DIR "/data/railway.glb"));
    runAlgorithm1(s, TabParams{});
    return encodeTabFile(s);
  };
  const std::vector<uint8_t> one = build(1), many = build(8);
  EXPECT_EQ(one.size(), many.size());
  EXPECT_TRUE(one == many);
}

}  // namespace
}  // namespace tessera::batching
