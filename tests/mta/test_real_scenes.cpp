// The builder on real inputs: railway.glb (28 textures, heavy repetition) and a small generated berlin.
#include <gtest/gtest.h>

#include <filesystem>

#include "model/city_gen.h"
#include "mta/build.h"
#include "mta/info.h"
#include "mta/paging_file.h"
#include "mta_test_scene.h"

namespace tessera::mta {
namespace {

void checkFile(const std::string& path, uint64_t trianglesIn) {
  const PagingFile f(path);
  const nlohmann::json j = describe(f, true);  // every block checksum
  EXPECT_EQ(j["triangles_in"].get<uint64_t>(), trianglesIn);
  uint64_t tris = 0;
  for (const Tree& t : f.meta().trees) tris += t.geometry.triangleCount();
  EXPECT_EQ(tris, f.meta().stats.trianglesOut);
  for (uint32_t i = 0; i < f.meta().images.size(); ++i)
    if (f.meta().images[i].pieceCount) {
      EXPECT_EQ(f.readImage(i).size(),
                size_t(f.meta().images[i].width) * f.meta().images[i].height * f.meta().images[i].channels);
    }
}

TEST(RealScenes, RailwayGlbBuildsAValidTree) {
  const std::string path = std::string(TESSERA_SOURCE_DIR) + "/data/railway.glb";
  // data/railway.glb is part of the repository (data/README.md): a missing copy is a failure, not a skip.
  ASSERT_TRUE(std::filesystem::exists(path)) << path << " is missing";
  auto m = std::make_shared<const model::Model>(model::loadModel(path));
  const Scene s = sceneFromModel(m);
  BuildParams p;
  p.dMin = 20.0;
  testing::TempFile out("railway.mta");
  buildMta(s, p, out.path);
  checkFile(out.path, m->triangleCount());
}

TEST(RealScenes, GeneratedBerlinBuildsAValidTree) {
  testing::TempFile dir("berlin");
  model::CityOptions o;
  o.buildings = 6;
  o.textureSize = 64;
  o.outDir = dir.path;
  o.progress = false;
  const model::CitySummary cs = model::generateCity(o);
  auto m = std::make_shared<const model::Model>(model::loadModel(cs.gltf));
  const Scene s = sceneFromModel(m);
  BuildParams p;
  p.atlasSize = 128;
  testing::TempFile out("berlin.mta");
  buildMta(s, p, out.path);
  checkFile(out.path, m->triangleCount());
  std::filesystem::remove_all(dir.path);
}

}  // namespace
}  // namespace tessera::mta
