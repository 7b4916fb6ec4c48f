// Every build type (Release, Debug, ASan) must reproduce golden/scene_hashes.json bit-exactly:
// this is the test that the oracle's bytes do not depend on optimization level or sanitizers.
// Regenerate the file with `build/tessera hashes -o golden/scene_hashes.json` after an intended change.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/raster/render_helpers.h"
#include "tools/scenes/scenes.h"

using namespace tessera;

namespace {
nlohmann::json loadManifest() {
  const std::string path = std::string(TESSERA_SOURCE_DIR) + "/golden/scene_hashes.json";
  std::ifstream f(path);
  if (!f) return nullptr;
  return nlohmann::json::parse(f, nullptr, false);
}
}  // namespace

class SceneHashes : public ::testing::TestWithParam<std::string> {};

TEST_P(SceneHashes, SceneReproducesItsRecordedImageHashes) {
  static const nlohmann::json manifest = loadManifest();
  ASSERT_TRUE(manifest.is_object()) << "golden/scene_hashes.json is missing or not JSON";
  ASSERT_TRUE(manifest.contains(GetParam())) << "no entry for " << GetParam()
                                             << "; run `build/tessera hashes -o golden/scene_hashes.json`";
  const scenes::SceneInfo* info = scenes::find(GetParam());
  const auto r = tessera::testing::renderList(scenes::build(info->name, info->width, info->height), 0);
  std::vector<std::string> expected = manifest[GetParam()].get<std::vector<std::string>>();
  EXPECT_EQ(r.hashes, expected) << "the oracle's bytes for " << GetParam() << " changed";
}

INSTANTIATE_TEST_SUITE_P(AllScenes, SceneHashes, ::testing::ValuesIn([] {
                           std::vector<std::string> names;
                           for (const auto& s : scenes::all()) names.emplace_back(s.name);
                           return names;
                         }()),
                         [](const auto& param) { return param.param; });
