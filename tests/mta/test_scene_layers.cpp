// A model's glTF occlusionTexture becomes layer 1 of the atlas tree's scene (thesis §5.1.3), read from
// its own texcoord set; triangles without one have no layer-1 texture.
#include <gtest/gtest.h>

#include <memory>

#include "model/model.h"
#include "mta/scene.h"
#include "tests/model/occlusion_gltf.h"

namespace tessera::mta {
namespace {

TEST(SceneLayers, AnOcclusionTextureIsLayerOneWithItsOwnTexcoordsAndWrapModes) {
  model::testing::ScratchDir dir;
  auto m = std::make_shared<const model::Model>(model::loadModel(model::testing::writeOcclusionGltf(dir, 0.5)));
  const Scene s = sceneFromModel(m);
  ASSERT_EQ(s.geometry.layers.size(), 2u);
  const SceneLayer &l0 = s.geometry.layers[0], &l1 = s.geometry.layers[1];
  ASSERT_EQ(l1.texture.size(), 4u);  // two quads
  // The lit quad: base texture 0, occlusion texture 1 (image 1, clamped); the plain quad: none in layer 1.
  EXPECT_EQ(l0.texture[0], 0);
  EXPECT_EQ(l1.texture[0], 1);
  EXPECT_EQ(l1.texture[1], 1);
  EXPECT_EQ(l1.texture[2], -1);
  EXPECT_EQ(l1.texture[3], -1);
  EXPECT_EQ(s.textures[1].image, 1u);
  EXPECT_EQ(s.textures[1].wrapS, model::Wrap::ClampToEdge);
  EXPECT_EQ(l1.uv[2], glm::vec2(0.75f, 0.75f));  // triangle 0 = vertices 0, 1, 2
  EXPECT_EQ(l0.uv[2], glm::vec2(3.0f, 3.0f));
}

TEST(SceneLayers, AModelWithoutOcclusionTexturesHasOneLayer) {
  model::testing::ScratchDir dir;
  const std::string path = model::testing::writeOcclusionGltf(dir, 1.0, [](nlohmann::json& j) {
    j["materials"][0].erase("occlusionTexture");
  });
  const Scene s = sceneFromModel(std::make_shared<const model::Model>(model::loadModel(path)));
  EXPECT_EQ(s.geometry.layers.size(), 1u);
}

}  // namespace
}  // namespace tessera::mta
