// `tessera city --split-per-building`: one glTF per building plus a scene manifest. Loaded through the
// manifest, the city must be the one-file city: the same meshes in the same order with the same
// positions and texcoords bit for bit, the texture files its meshes use, and materials equal field by field.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "model/city_gen.h"
#include "model/model.h"
#include "model_test_util.h"

namespace tessera::model {
namespace {

using testing::ScratchDir;

CitySummary generateFiveBuildings(CityPreset preset, const std::string& dir, bool split) {
  CityOptions o;
  o.preset = preset;
  o.buildings = 5;
  o.textureSize = 16;
  o.outDir = dir;
  o.progress = false;
  o.splitPerBuilding = split;
  return generateCity(o);
}

// A texture's file relative to the city's directory (textures/tNNNNN.png): the two cities are in two directories.
std::string inCity(const TextureRef& t) {
  const std::filesystem::path p(t.path);
  return (p.parent_path().filename() / p.filename()).string();
}

bool sameMaterial(const Material& a, const Material& b, const Model& ma, const Model& mb) {
  const auto texturePath = [](const Model& m, int32_t t) {
    return t < 0 ? std::string() : inCity(m.textures[size_t(t)]);
  };
  return a.name == b.name && texturePath(ma, a.baseColorTexture) == texturePath(mb, b.baseColorTexture) &&
         a.baseColorFactor == b.baseColorFactor && a.alphaMode == b.alphaMode && a.alphaCutoff == b.alphaCutoff &&
         a.doubleSided == b.doubleSided && a.wrapS == b.wrapS && a.wrapT == b.wrapT;
}

void expectTheSameCity(CityPreset preset) {
  ScratchDir dir;
  const CitySummary one = generateFiveBuildings(preset, dir / "one", false),
                    split = generateFiveBuildings(preset, dir / "split", true);
  EXPECT_EQ(split.gltf, dir / "split" + "/" + cityPresetName(preset) + ".json");
  EXPECT_EQ(split.triangles, one.triangles);
  EXPECT_EQ(split.textures, one.textures);
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "split/parts/building_4.gltf"));
  const Model a = loadModel(one.gltf), b = loadModel(split.gltf);
  EXPECT_EQ(b.loader, "scene:manifest");
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    SCOPED_TRACE("mesh " + std::to_string(i) + " '" + a.meshes[i].name + "'");
    EXPECT_EQ(a.meshes[i].positions, b.meshes[i].positions);  // bit for bit: the same doubles, the same arithmetic
    EXPECT_EQ(a.meshes[i].texcoords, b.meshes[i].texcoords);
    EXPECT_EQ(a.meshes[i].indices, b.meshes[i].indices);
    EXPECT_TRUE(sameMaterial(a.materials[a.meshes[i].material], b.materials[b.meshes[i].material], a, b));
    EXPECT_EQ(a.objects[a.meshes[i].object].name, b.objects[b.meshes[i].object].name);
  }
  // The split city holds the textures its meshes use, in order of first use; the one-file city lists
  // every image the generator wrote (chemnitz writes a few no primitive uses), in the generator's order.
  std::vector<std::string> usedByA, inB;
  for (const Mesh& mesh : a.meshes)
    if (const int32_t t = a.materials[mesh.material].baseColorTexture; t >= 0) {
      const std::string f = inCity(a.textures[size_t(t)]);
      if (std::find(usedByA.begin(), usedByA.end(), f) == usedByA.end()) usedByA.push_back(f);
    }
  for (const TextureRef& t : b.textures) inB.push_back(inCity(t));
  EXPECT_EQ(usedByA, inB);
  if (preset == CityPreset::Berlin) {
    EXPECT_EQ(a.textures.size(), b.textures.size());  // every facade is used
  }
  EXPECT_EQ(a.bounds.min, b.bounds.min);
  EXPECT_EQ(a.bounds.max, b.bounds.max);
}

TEST(CitySplit, ABerlinSplitPerBuildingLoadsThroughItsManifestAsTheOneFileCity) {
  expectTheSameCity(CityPreset::Berlin);
}

TEST(CitySplit, AChemnitzSplitPerBuildingWithRotatedBuildingsInBlocksLoadsAsTheOneFileCity) {
  expectTheSameCity(CityPreset::Chemnitz);
}

}  // namespace
}  // namespace tessera::model
