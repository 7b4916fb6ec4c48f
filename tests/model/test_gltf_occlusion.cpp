// glTF 2.0 occlusionTexture: read as a second texture layer with its own texcoord set, strength and
// sampler (issue 14 §5; the atlas tree's layer 1, thesis §5.1.3).
#include <gtest/gtest.h>

#include "model/model.h"
#include "tests/model/occlusion_gltf.h"

namespace tessera::model {
namespace {

using testing::ScratchDir;

TEST(GltfOcclusion, AnOcclusionTextureIsReadWithItsOwnTexcoordSetStrengthAndSampler) {
  ScratchDir dir;
  const Model m = loadModel(testing::writeOcclusionGltf(dir, 0.5));
  ASSERT_EQ(m.materials.size(), 2u);
  const Material &lit = m.materials[0], &plain = m.materials[1];
  EXPECT_EQ(lit.baseColorTexture, 0);
  EXPECT_EQ(lit.occlusionTexture, 1);
  EXPECT_EQ(lit.occlusionStrength, 0.5f);
  EXPECT_EQ(lit.occlusionWrapS, Wrap::ClampToEdge);
  EXPECT_EQ(lit.occlusionWrapT, Wrap::ClampToEdge);
  EXPECT_EQ(lit.wrapS, Wrap::Repeat);  // the base texture has no sampler
  EXPECT_EQ(plain.occlusionTexture, -1);
  ASSERT_EQ(m.meshes.size(), 2u);
  ASSERT_EQ(m.meshes[0].occlusionTexcoords.size(), 4u);
  EXPECT_EQ(m.meshes[0].occlusionTexcoords[2], glm::vec2(0.75f, 0.75f));
  EXPECT_EQ(m.meshes[0].texcoords[2], glm::vec2(3.0f, 3.0f));
  EXPECT_TRUE(m.meshes[1].occlusionTexcoords.empty());
}

TEST(GltfOcclusion, AMissingOcclusionTexcoordSetIsAnErrorNamingTheMaterialAndTheSet) {
  ScratchDir dir;
  const std::string path = testing::writeOcclusionGltf(dir, 1.0, [](nlohmann::json& j) {
    j["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_1");
  });
  const std::string e = testing::errorOf([&] { loadModel(path); });
  EXPECT_CONTAINS(e, "/meshes/0/primitives/0/attributes");
  EXPECT_CONTAINS(e, "material 0's occlusion texture reads texCoord 1 (TEXCOORD_1)");
}

TEST(GltfOcclusion, AStrengthOutsideZeroToOneIsAnErrorNamingTheField) {
  ScratchDir dir;
  const std::string e = testing::errorOf([&] { loadModel(testing::writeOcclusionGltf(dir, 1.5)); });
  EXPECT_CONTAINS(e, "/materials/0/occlusionTexture/strength");
  EXPECT_CONTAINS(e, "expected a number in [0, 1]");
}

TEST(GltfOcclusion, AnOcclusionTextureIndexOutOfRangeIsAnErrorNamingTheField) {
  ScratchDir dir;
  const std::string path = testing::writeOcclusionGltf(dir, 1.0, [](nlohmann::json& j) {
    j["materials"][0]["occlusionTexture"]["index"] = 7;
  });
  const std::string e = testing::errorOf([&] { loadModel(path); });
  EXPECT_CONTAINS(e, "/materials/0/occlusionTexture/index");
}

}  // namespace
}  // namespace tessera::model
