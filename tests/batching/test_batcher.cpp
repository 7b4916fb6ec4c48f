// Algorithm 1 (batching/batcher.h): its limits hold on many inputs, every mesh keeps its triangles and
// finds its texture through the TAM, and each slip of the printed pseudo-code stays fixed.
#include <gtest/gtest.h>

#include <random>

#include "base/error.h"
#include "batching/batcher.h"
#include "tests/batching/tab_test_scene.h"

namespace tessera::batching {
namespace {

using testing::MeshSpec;
using testing::tabInput;
using testing::TexSpec;

// A deterministic mix: 40 textures over 6 keys, 300 meshes of 1..60 triangles, 1 or 2 units.
TabScene randomInput(uint32_t seed, bool twoUnits) {
  std::mt19937 rng(seed);
  const TexSpec keys[6] = {{64, 64}, {128, 128}, {64, 128}, {64, 64, WrapMode::ClampToEdge}, {256, 187}, {32, 32}};
  std::vector<TexSpec> tex;
  for (int i = 0; i < 40; ++i) tex.push_back(keys[rng() % 6]);
  std::vector<MeshSpec> meshes;
  for (int i = 0; i < 300; ++i) {
    MeshSpec m{1 + uint32_t(rng() % 60), {uint32_t(rng() % 40)}};
    if (twoUnits) m.textures.push_back(uint32_t(rng() % 40));
    meshes.push_back(m);
  }
  return tabInput(tex, meshes);
}

const TabParams kParamSweep[] = {{4, 1, 1}, {30, 3, 2}, {200, 5, 3}, {1000, 16, 8}, {1u << 20, 256, 8}, {90, 2, 1}};

TEST(TabBatcher, NoArrayEverHoldsMoreThanDMaxLayers) {
  for (uint32_t seed = 1; seed <= 4; ++seed)
    for (const TabParams& p : kParamSweep) {
      TabScene s = randomInput(seed, seed % 2 == 0 && p.aMax >= 2);  // two units need two arrays
      runAlgorithm1(s, p);
      for (const TextureArray& a : s.arrays) {
        EXPECT_GE(a.layers.size(), 1u);
        EXPECT_LE(a.layers.size(), p.dMax);
      }
    }
}

TEST(TabBatcher, NoOutputBatchUsesMoreThanAMaxArrays) {
  for (uint32_t seed = 1; seed <= 4; ++seed)
    for (const TabParams& p : kParamSweep) {
      TabScene s = randomInput(seed, seed % 2 == 0 && p.aMax >= 2);  // two units need two arrays
      runAlgorithm1(s, p);
      for (const OutputBatch& b : s.batches) {
        EXPECT_LE(b.arrays.size(), p.aMax);
        // One resolution and format (and sampler) per array: every layer has the array's key.
        for (uint32_t a : b.arrays)
          for (uint32_t t : s.arrays[a].layers) {
            EXPECT_EQ(s.textures[t].width, s.arrays[a].key.width);
            EXPECT_EQ(s.textures[t].height, s.arrays[a].key.height);
            EXPECT_EQ(s.textures[t].wrapS, s.arrays[a].key.wrapS);
          }
      }
    }
}

TEST(TabBatcher, NoGeometryBatchExceedsBMaxUnlessOneMeshAloneDoes) {
  for (uint32_t seed = 1; seed <= 4; ++seed)
    for (const TabParams& p : kParamSweep) {
      TabScene s = randomInput(seed, false);
      runAlgorithm1(s, p);
      for (const OutputBatch& b : s.batches)
        for (const GeometryBatch& g : b.geometry) {
          if (g.meshCount == 1) continue;  // one mesh alone may exceed b_max: meshes are never split
          EXPECT_LE(g.vertexCount, p.bMax);
        }
    }
  // And a batch is only closed when the next mesh would not fit: b_max = 9 with 3-vertex meshes gives
  // geometry batches of exactly 9 vertices.
  TabScene s = tabInput({{64, 64}}, std::vector<MeshSpec>(7, MeshSpec{1, {0}}));
  runAlgorithm1(s, {9, 16, 8});
  ASSERT_EQ(s.batches.size(), 1u);
  ASSERT_EQ(s.batches[0].geometry.size(), 3u);
  EXPECT_EQ(s.batches[0].geometry[0].vertexCount, 9u);
  EXPECT_EQ(s.batches[0].geometry[1].vertexCount, 9u);
  EXPECT_EQ(s.batches[0].geometry[2].vertexCount, 3u);
}

TEST(TabBatcher, EveryTriangleAppearsOnceWithItsOriginalTexcoords) {
  for (const TabParams& p : kParamSweep) {
    const TabScene before = randomInput(7, p.aMax >= 2);
    TabScene s = before;
    runAlgorithm1(s, p);
    ASSERT_EQ(s.vertices.size(), before.vertices.size());
    for (size_t v = 0; v < s.vertices.size(); ++v) {
      EXPECT_EQ(s.vertices[v].x, before.vertices[v].x);
      EXPECT_EQ(s.vertices[v].y, before.vertices[v].y);
      EXPECT_EQ(s.vertices[v].z, before.vertices[v].z);
      EXPECT_EQ(s.vertices[v].s, before.vertices[v].s);
      EXPECT_EQ(s.vertices[v].t, before.vertices[v].t);
    }
    // The geometry batches, in order, tile the meshes and their vertices exactly once.
    uint32_t nextMesh = 0, nextVertex = 0;
    for (const OutputBatch& b : s.batches)
      for (const GeometryBatch& g : b.geometry) {
        EXPECT_EQ(g.firstMesh, nextMesh);
        EXPECT_EQ(g.firstVertex, nextVertex);
        uint32_t vertices = 0;
        for (uint32_t m = g.firstMesh; m < g.firstMesh + g.meshCount; ++m) vertices += s.meshes[m].vertexCount;
        EXPECT_EQ(g.vertexCount, vertices);
        nextMesh += g.meshCount;
        nextVertex += g.vertexCount;
      }
    EXPECT_EQ(nextMesh, s.meshes.size());
    EXPECT_EQ(nextVertex, s.vertices.size());
  }
}

TEST(TabBatcher, EveryTamEntryNamesALayerHoldingItsMeshTexture) {
  for (const TabParams& p : kParamSweep) {
    TabScene s = randomInput(11, p.aMax >= 2);
    runAlgorithm1(s, p);
    for (uint32_t mi = 0; mi < s.meshes.size(); ++mi) {
      const TabMesh& m = s.meshes[mi];
      ASSERT_LT(m.outputBatch, s.batches.size());
      const OutputBatch& b = s.batches[m.outputBatch];
      // The mesh lies in one of its output batch's geometry batches.
      bool inside = false;
      for (const GeometryBatch& g : b.geometry) inside |= mi >= g.firstMesh && mi < g.firstMesh + g.meshCount;
      EXPECT_TRUE(inside) << "mesh " << mi;
      for (size_t u = 0; u < m.textures.size(); ++u) {  // units(M_i) consecutive entries
        ASSERT_LT(m.tamIndex + u, b.tam.size());
        const TamEntry& e = b.tam[m.tamIndex + u];
        ASSERT_LT(e.array, b.arrays.size());
        const TextureArray& a = s.arrays[b.arrays[e.array]];
        ASSERT_LT(e.layer, a.layers.size());
        EXPECT_EQ(a.layers[e.layer], m.textures[u]) << "mesh " << mi << " unit " << u;
      }
      for (uint32_t v = 0; v < m.vertexCount; ++v) EXPECT_EQ(s.vertices[m.firstVertex + v].index, float(m.tamIndex));
    }
  }
}

TEST(TabBatcher, TwoUnitsOfAMeshTakeConsecutiveEntriesInTheSameOutputBatch) {
  // a_max = 2: mesh 1 needs a new array for each unit, so it cannot join mesh 0's batch (one array used).
  TabScene s = tabInput({{64, 64}, {32, 32}, {16, 16}}, {{1, {0}}, {1, {1, 2}}});
  runAlgorithm1(s, {1000, 16, 2});
  ASSERT_EQ(s.batches.size(), 2u);
  EXPECT_EQ(s.meshes[1].outputBatch, 1u);
  EXPECT_EQ(s.meshes[1].tamIndex, 0u);
  ASSERT_EQ(s.batches[1].tam.size(), 2u);
  EXPECT_EQ(s.batches[1].tam[0].array, 0u);
  EXPECT_EQ(s.batches[1].tam[1].array, 1u);
}

TEST(TabBatcher, ASharedTextureTakesOneLayerAndEveryMeshItsOwnEntry) {
  TabScene s = tabInput({{64, 64}, {64, 64}}, {{1, {0}}, {2, {1}}, {1, {0}}, {1, {0}}});
  runAlgorithm1(s, {1000, 16, 8});
  ASSERT_EQ(s.arrays.size(), 1u);
  EXPECT_EQ(s.arrays[0].layers, (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(s.batches[0].tam.size(), 4u);  // O_TAM counts meshes, not textures
  EXPECT_EQ(s.batches[0].tam[2].layer, 0u);
  EXPECT_EQ(s.batches[0].tam[3].layer, 0u);
}

TEST(TabBatcher, AnArrayIsFullAtExactlyDMaxLayers) {
  // Line 6's `>` of the printed algorithm would put 3 layers in an array with d_max = 2.
  TabScene s = tabInput({{64, 64}, {64, 64}, {64, 64}}, {{1, {0}}, {1, {1}}, {1, {2}}});
  runAlgorithm1(s, {1000, 2, 8});
  ASSERT_EQ(s.arrays.size(), 2u);
  EXPECT_EQ(s.arrays[0].layers.size(), 2u);
  EXPECT_EQ(s.arrays[1].layers.size(), 1u);
  EXPECT_EQ(s.batches.size(), 1u);
}

TEST(TabBatcher, TooManyArraysStartANewOutputBatchWithItsOwnArraysAndTam) {
  // a_max = 1 and three resolutions: three output batches, each one array and a TAM from entry 0.
  TabScene s = tabInput({{16, 16}, {32, 32}, {64, 64}}, {{1, {0}}, {1, {0}}, {1, {1}}, {1, {2}}});
  runAlgorithm1(s, {1000, 16, 1});
  ASSERT_EQ(s.batches.size(), 3u);
  EXPECT_EQ(s.batches[0].tam.size(), 2u);
  EXPECT_EQ(s.meshes[2].tamIndex, 0u);
  EXPECT_EQ(s.meshes[3].tamIndex, 0u);
  for (const OutputBatch& b : s.batches) EXPECT_EQ(b.arrays.size(), 1u);
}

TEST(TabBatcher, TheLastBatchIsEmittedAndOneMeshPerInputGivesOneGeometryBatch) {
  // Line 3 of the printed algorithm opened a new batch per mesh; the last one was never emitted.
  TabScene s = tabInput({{64, 64}}, std::vector<MeshSpec>(5, MeshSpec{2, {0}}));
  runAlgorithm1(s, {1u << 20, 16, 8});
  ASSERT_EQ(s.batches.size(), 1u);
  ASSERT_EQ(s.batches[0].geometry.size(), 1u);
  EXPECT_EQ(s.batches[0].geometry[0].meshCount, 5u);
  EXPECT_EQ(s.batches[0].geometry[0].vertexCount, 30u);
}

TEST(TabBatcher, ParametersOutOfRangeAreClearErrorsNamingTheOption) {
  TabScene s = tabInput({{64, 64}}, {{1, {0}}});
  auto message = [&](TabParams p) {
    try {
      runAlgorithm1(s, p);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({3, 16, 8}).find("--b-max"), std::string::npos);
  EXPECT_NE(message({4, 0, 8}).find("--d-max"), std::string::npos);
  EXPECT_NE(message({4, 2049, 8}).find("--d-max"), std::string::npos);
  EXPECT_NE(message({4, 16, 0}).find("--a-max"), std::string::npos);
  EXPECT_NE(message({4, 16, 9}).find("--a-max"), std::string::npos);
  // One mesh needing two arrays with a_max = 1 cannot be batched at all.
  TabScene two = tabInput({{64, 64}, {32, 32}}, {{1, {0, 1}}});
  EXPECT_THROW(runAlgorithm1(two, {4, 16, 1}), Error);
}

}  // namespace
}  // namespace tessera::batching
