// glTF inputs from the fuzz campaign of issue 9, one test per bug: each is a clear tessera::Error naming
// the file, the JSON pointer and the reason, found before anything is allocated for it, never a crash,
// a hang or a silently wrong model. The small reproducers live in tests/model/hostile/gltf/; what is
// big or needs a variation is written here.
#include <gtest/gtest.h>

#include <string>

#include "model/model.h"
#include "model_test_util.h"

namespace tessera::model {
namespace {

using testing::errorOf;
using testing::ScratchDir;

const std::string kHostile = TESSERA_SOURCE_DIR "/tests/model/hostile/gltf/";

// A glTF whose one mesh is a triangle (3 float positions in a data: URI), with `nodes` and the scene's
// root list as given (JSON text).
std::string triangleGltf(const std::string& nodes, const std::string& sceneNodes, const std::string& extra = "") {
  const std::string bin = [] {
    std::string b;
    testing::appendBytes(b, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
    return b;
  }();
  return R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)" +
         testing::base64(bin) +
         R"("}],"bufferViews":[{"buffer":0,"byteLength":36}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],)"
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":)" +
         nodes + R"(,"scenes":[{"nodes":)" + sceneNodes + "}]" + extra + "}";
}

// A chain of `n` nodes, each translating by (1, 0, 0) and listing the next as its child; the last one
// has the triangle.
std::string chainGltf(size_t n) {
  std::string nodes = "[";
  for (size_t i = 0; i + 1 < n; ++i) nodes += R"({"translation":[1,0,0],"children":[)" + std::to_string(i + 1) + "]},";
  nodes += R"({"translation":[1,0,0],"mesh":0}])";
  return triangleGltf(nodes, "[0]");
}

// `levels` levels of two nodes; each node of a level lists both nodes of the next one; the last level has
// the triangle. Both nodes of the first level are roots: 2 * (2^levels - 1) node instances.
std::string dagGltf(int levels) {
  std::string nodes = "[";
  for (int l = 0; l < levels; ++l)
    for (int k = 0; k < 2; ++k) {
      nodes += l + 1 < levels ? R"({"children":[)" + std::to_string(2 * l + 2) + "," + std::to_string(2 * l + 3) + "]}"
                              : std::string(R"({"mesh":0})");
      nodes += l + 1 < levels || k == 0 ? "," : "]";
    }
  return triangleGltf(nodes, "[0,1]");
}

TEST(Gltf, ANodeChain100000DeepIsRefusedWithoutRecursion) {
  // The recursive walk overflowed the stack (SIGSEGV). The first node past the limit is named.
  ScratchDir dir;
  testing::writeFile(dir / "chain.gltf", chainGltf(100000));
  const std::string e = errorOf([&] { loadModel(dir / "chain.gltf"); });
  EXPECT_CONTAINS(e, dir / "chain.gltf");
  EXPECT_CONTAINS(e, "/nodes/256: the node hierarchy nests deeper than the limit of 256 levels");
}

TEST(Gltf, AChainAsDeepAsTheLimitLoadsWithEveryTranslationComposed) {
  ScratchDir dir;
  testing::writeFile(dir / "chain.gltf", chainGltf(256));
  const Model m = loadModel(dir / "chain.gltf");
  ASSERT_EQ(m.meshes.size(), 1u);
  // 256 translations by 1 in x: vertex (1, 0, 0) lands at x = 257.
  EXPECT_EQ(m.meshes[0].positions[1].x, 257.0f);
  EXPECT_EQ(m.meshes[0].positions[1].y, 0.0f);
  ResourceLimits shallower;
  shallower.graphDepth = 255;
  EXPECT_CONTAINS(errorOf([&] { loadModel(dir / "chain.gltf", shallower); }),
                  "/nodes/255: the node hierarchy nests deeper than the limit of 255 levels");
}

TEST(Gltf, ANodeDagDescribing2To40InstancesFailsFast) {
  // It ran past 30 s and 3.5 GB. The message gives the whole graph's count, 2 * (2^40 - 1): a walk
  // that counted instances one by one could not know it without visiting all of them.
  const std::string path = kHostile + "node-dag-2to40-instances.gltf";
  EXPECT_CONTAINS(errorOf([&] { loadModel(path); }),
                  path + ": needs 2199023255550 node instances, over the limit of 1000000 by 2199022255550");
  // Past the instance budget, the triangle and vertex budgets stop it: one triangle per leaf instance.
  ResourceLimits l;
  l.modelInstances = UINT64_MAX - 1;
  EXPECT_CONTAINS(errorOf([&] { loadModel(path, l); }), "needs 1099511627776 triangles, over the limit of 50000000");
  l.modelTriangles = UINT64_MAX - 1;
  EXPECT_CONTAINS(errorOf([&] { loadModel(path, l); }), "needs 3298534883328 vertices, over the limit of 150000000");
}

TEST(Gltf, ANodeDagDescribingMoreThan2To64InstancesSaysSoInsteadOfWrapping) {
  ScratchDir dir;
  testing::writeFile(dir / "dag70.gltf", dagGltf(70));  // 2^71 - 2 instances
  EXPECT_CONTAINS(errorOf([&] { loadModel(dir / "dag70.gltf"); }),
                  "needs more than 2^64 node instances, over the limit of 1000000");
}

TEST(Gltf, ANodeReachedAlongTwoPathsIsInstancedOncePerPathInPreOrder) {
  // Node 3 (the triangle) is a child of node 1 (x + 10) and of node 2 (y + 20): two instances, in the
  // order of a depth-first walk that lists children in file order.
  ScratchDir dir;
  testing::writeFile(dir / "twice.gltf", triangleGltf(R"([{"children":[1,2]},{"translation":[10,0,0],"children":[3]},)"
                                                      R"({"translation":[0,20,0],"children":[3]},{"mesh":0}])",
                                                      "[0]"));
  const Model m = loadModel(dir / "twice.gltf");
  ASSERT_EQ(m.meshes.size(), 2u);
  EXPECT_EQ(m.meshes[0].positions[0], glm::vec3(10, 0, 0));
  EXPECT_EQ(m.meshes[1].positions[0], glm::vec3(0, 20, 0));
}

TEST(Gltf, AnAccessorCountOf2To32MinusOneIsRefusedBeforeAllocating) {
  // Reader::floats allocated count * 3 floats (51 GB) before it checked the bufferView's range.
  const std::string path = kHostile + "accessor-count-2to32-minus-1.gltf";
  EXPECT_CONTAINS(errorOf([&] { loadModel(path); }),
                  path + ": /accessors/0: 4294967295 elements from byteOffset 0 overrun bufferView 0 (36 bytes)");
}

TEST(Gltf, AnIndexAccessorCountOf2To31IsRefusedBeforeAllocating) {
  const std::string path = kHostile + "index-accessor-count-2to31.gltf";
  EXPECT_CONTAINS(errorOf([&] { loadModel(path); }),
                  path + ": /accessors/1: 2147483648 elements from byteOffset 0 overrun bufferView 1 (12 bytes)");
}

TEST(Gltf, AnAccessorCountOf2To62IsAClearErrorNotAnInternalError) {
  // count * 3 wrapped around and std::vector threw length_error, which the CLI reports as an internal
  // error (exit 3); errorOf fails the test on anything but tessera::Error.
  const std::string path = kHostile + "accessor-count-2to62.gltf";
  EXPECT_CONTAINS(errorOf([&] { loadModel(path); }), path + ": /accessors/0: 4611686018427387904 elements");
}

TEST(Gltf, AnAccessorWithoutABufferViewAndACountOf2To32IsRefusedByTheVertexBudget) {
  // Without a bufferView an accessor is all zeros, whatever its count: no buffer bounds it. Here 2^32
  // positions, and one triangle of three indices 0.
  ScratchDir dir;
  testing::writeFile(
      dir / "zeros.gltf",
      R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":12,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAA"}],)"
      R"("bufferViews":[{"buffer":0,"byteLength":12}],)"
      R"("accessors":[{"componentType":5126,"count":4294967296,"type":"VEC3"},)"
      R"({"bufferView":0,"componentType":5125,"count":3,"type":"SCALAR"}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
      R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})");
  EXPECT_CONTAINS(errorOf([&] { loadModel(dir / "zeros.gltf"); }),
                  dir / "zeros.gltf" + ": needs 4294967296 vertices, over the limit of 150000000");
}

}  // namespace
}  // namespace tessera::model
