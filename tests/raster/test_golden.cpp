// Every build type (Release, Debug, ASan) must reproduce the golden images bit-exactly: this is the
// test that the oracle's bytes depend neither on the optimization level nor on sanitizers.
// After an intended change: `build/tessera golden update` and commit the images with the reason.
// The manifest and the comparison are the golden module's (golden/); the scenes' images come from
// tools/scenes/scene_goldens.h.
#include <gtest/gtest.h>

#include <set>

#include "golden/golden_diff.h"
#include "golden/golden_images.h"
#include "golden/manifest.h"
#include "golden/railway_frames.h"
#include "golden/tab_railway_frames.h"
#include "raster/image_io.h"
#include "tools/scenes/scene_goldens.h"
#include "tools/scenes/scenes.h"

namespace tessera {

namespace {

const std::string kGoldenDir = std::string(TESSERA_SOURCE_DIR) + "/golden";

// Empty when the manifest cannot be read: Golden.TheShippedManifestIsValid then says why (an exception here
// would abort the test registration instead).
golden::Manifest manifestOrEmpty() {
  try {
    return golden::readManifest(kGoldenDir + "/manifest.json");
  } catch (const Error&) {
    return {};
  }
}

const golden::Manifest& manifest() {
  static const golden::Manifest m = manifestOrEmpty();
  return m;
}

// Entries of the built-in scenes. The atlas tree's frames ("scene": "mta_railway") need railway.glb and
// the whole mta runtime; the CLI case atlas_tree_goldens_reproduce_bit_exactly checks them.
bool isSceneEntry(const golden::ManifestEntry& e) { return !golden::isRailwayScene(e.scene); }

std::vector<std::string> testNames() {
  std::vector<std::string> names;
  for (const auto& [name, e] : manifest().tests)
    if (isSceneEntry(e)) names.push_back(name);
  return names;
}

}  // namespace

TEST(Golden, TheShippedManifestIsValid) { EXPECT_NO_THROW(golden::readManifest(kGoldenDir + "/manifest.json")); }

TEST(Golden, EveryScenePresentsOnlyImagesThatHaveAGoldenEntry) {
  std::set<std::string> presented;
  for (const auto& s : scenes::all()) {
    scenes::renderSceneImages(s, [&](const golden::RenderedImage& img) {
      presented.insert(img.name);
      EXPECT_TRUE(manifest().tests.count(img.name)) << img.name << " has no golden image";
    });
  }
  size_t sceneEntries = 0;
  for (const auto& [name, e] : manifest().tests) sceneEntries += isSceneEntry(e) ? 1 : 0;
  EXPECT_EQ(presented.size(), sceneEntries)
      << "manifest and presented images differ in number: run `tessera golden update`";
}

class GoldenImage : public ::testing::TestWithParam<std::string> {};

TEST_P(GoldenImage, OracleReproducesTheGoldenImageBitExactly) {
  const golden::ManifestEntry& e = manifest().tests.at(GetParam());
  const scenes::SceneInfo* info = scenes::find(e.scene);
  ASSERT_NE(info, nullptr) << "golden entry names an unknown scene";
  bool found = false;
  scenes::renderSceneImages(*info, [&](const golden::RenderedImage& img) {
    if (img.name != GetParam()) return;
    found = true;
    // The presented image's size, which is the scene's unless it presents an off-screen target (an
    // RTTA atlas is larger than the viewport).
    EXPECT_EQ(e.width, levelWidth(img.texture->desc, img.level));
    EXPECT_EQ(e.height, levelHeight(img.texture->desc, img.level));
    EXPECT_EQ(img.attachment, e.attachment);
    EXPECT_EQ(img.layer, e.layer);
    const auto pixels = imagePixels(*img.texture, img.level, img.layer);
    const golden::GoldenDiff d = golden::diffAgainstGolden(kGoldenDir, &e, pixels, img.texture->desc.format);
    EXPECT_TRUE(d.matches()) << "the oracle's bytes changed: " << d.reason;
  });
  EXPECT_TRUE(found) << "the scene no longer presents attachment/layer of this entry";
}

INSTANTIATE_TEST_SUITE_P(Manifest, GoldenImage, ::testing::ValuesIn(testNames()), [](const auto& param) {
  std::string n = param.param;
  for (char& c : n)
    if (c == '.') c = '_';
  return n;
});

}  // namespace tessera
