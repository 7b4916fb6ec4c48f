// Every build type (Release, Debug, ASan) must reproduce the golden images bit-exactly: this is the
// test that the oracle's bytes depend neither on the optimization level nor on sanitizers.
// After an intended change: `build/tessera golden update` and commit the images with the reason.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "base/sha256.h"
#include "tests/raster/render_helpers.h"
#include "tools/scenes/scenes.h"

using namespace tessera;

namespace {

const std::string kGoldenDir = std::string(TESSERA_SOURCE_DIR) + "/golden";

nlohmann::json manifestTests() {
  std::ifstream f(kGoldenDir + "/manifest.json");
  if (!f) return nlohmann::json::object();
  const nlohmann::json j = nlohmann::json::parse(f, nullptr, false);
  return j.is_object() && j.contains("tests") ? j["tests"] : nlohmann::json::object();
}

// Entries of the built-in scenes. The atlas tree's frames ("scene": "mta_railway") need railway.glb and
// the whole mta runtime; the CLI case atlas_tree_goldens_reproduce_bit_exactly checks them.
bool isSceneEntry(const nlohmann::json& e) { return e.value("scene", "") != "mta_railway"; }

std::vector<std::string> testNames() {
  std::vector<std::string> names;
  const nlohmann::json tests = manifestTests();
  for (auto it = tests.begin(); it != tests.end(); ++it)
    if (isSceneEntry(it.value())) names.push_back(it.key());
  return names;
}

}  // namespace

TEST(Golden, EveryScenePresentsOnlyImagesThatHaveAGoldenEntry) {
  const nlohmann::json tests = manifestTests();
  size_t images = 0;
  for (const auto& s : scenes::all()) {
    const auto r = tessera::testing::renderList(scenes::build(s.name, s.width, s.height), 0);
    images += r.hashes.size();
    EXPECT_TRUE(tests.contains(std::string(s.name))) << s.name << " has no golden image";
  }
  size_t sceneEntries = 0;
  for (auto it = tests.begin(); it != tests.end(); ++it) sceneEntries += isSceneEntry(it.value()) ? 1 : 0;
  EXPECT_EQ(images, sceneEntries) << "manifest and presented images differ in number: run `tessera golden update`";
}

class GoldenImage : public ::testing::TestWithParam<std::string> {};

TEST_P(GoldenImage, OracleReproducesTheGoldenImageBitExactly) {
  static const nlohmann::json tests = manifestTests();
  const nlohmann::json& e = tests[GetParam()];
  const std::string scene = e["scene"];
  const scenes::SceneInfo* info = scenes::find(scene);
  ASSERT_NE(info, nullptr) << "golden entry names an unknown scene";
  ASSERT_EQ(int(e["width"]), info->width);
  CpuBackend b;
  b.execute(scenes::build(info->name, info->width, info->height), scene);
  bool found = false;
  for (const PresentedImage& p : b.presented()) {
    if (p.attachment != e["attachment"].get<uint32_t>() || p.layer != e["layer"].get<uint32_t>()) continue;
    found = true;
    const TextureData& t = *b.texture(p.texture);
    const auto pixels = imagePixels(t, p.level, p.layer);
    EXPECT_EQ(sha256Hex(pixels), e["image_sha256"].get<std::string>()) << "the oracle's bytes changed";
    const DecodedImage golden = readImage(kGoldenDir + "/" + e["file"].get<std::string>());
    EXPECT_EQ(golden.pixels == pixels, true) << "the golden file's pixels differ from the oracle's";
  }
  EXPECT_TRUE(found) << "the scene no longer presents attachment/layer of this entry";
}

INSTANTIATE_TEST_SUITE_P(Manifest, GoldenImage, ::testing::ValuesIn(testNames()), [](const auto& param) {
  std::string n = param.param;
  for (char& c : n)
    if (c == '.') c = '_';
  return n;
});
