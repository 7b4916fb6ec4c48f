// golden/golden_diff.h and golden/golden_run.h: one image against its golden file, and check / update
// of a whole golden directory (the built-in scenes; the railway frames are the CLI case
// atlas_tree_goldens_reproduce_bit_exactly).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "base/sha256.h"
#include "golden/golden_diff.h"
#include "golden/golden_run.h"
#include "golden/manifest.h"
#include "golden/railway_frames.h"
#include "golden/tab_railway_frames.h"
#include "tools/scenes/scene_goldens.h"
#include "raster/image_io.h"

namespace tessera {
namespace fs = std::filesystem;

namespace {

const std::string kShippedDir = std::string(TESSERA_SOURCE_DIR) + "/golden";

struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& tag)
      : path(fs::temp_directory_path() / ("tessera-golden-test-" + tag + "-" + std::to_string(::getpid()))) {
    fs::remove_all(path);
    fs::create_directories(path / "images");
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string str() const { return path.string(); }
};

// A 3x2 RGBA8 image whose texel i (in storage order) is (10 i, 20, 30, 255).
TextureData smallImage() {
  TextureDesc d;
  d.width = 3;
  d.height = 2;
  TextureData t(d);
  for (size_t i = 0; i < 6; ++i) {
    t.levels[0][4 * i + 0] = uint8_t(10 * i);
    t.levels[0][4 * i + 1] = 20;
    t.levels[0][4 * i + 2] = 30;
    t.levels[0][4 * i + 3] = 255;
  }
  return t;
}

golden::ManifestEntry entryFor(const TextureData& t, const std::string& file) {
  golden::ManifestEntry e;
  e.file = file;
  e.imageSha256 = sha256Hex(imagePixels(t, 0, 0));
  e.format = "RGBA8";
  e.width = t.desc.width;
  e.height = t.desc.height;
  e.scene = "small";
  return e;
}

}  // namespace

TEST(GoldenDiff, TheSameBytesAndHashMatch) {
  TempDir dir("same");
  const TextureData t = smallImage();
  writeImage(t, 0, 0, dir.str() + "/images/small.png");
  const golden::ManifestEntry e = entryFor(t, "images/small.png");
  const golden::GoldenDiff d = golden::diffAgainstGolden(dir.str(), &e, imagePixels(t, 0, 0), Format::RGBA8);
  EXPECT_TRUE(d.matches()) << d.reason;
  EXPECT_EQ(d.sha256, e.imageSha256);
}

TEST(GoldenDiff, ChangedPixelsAreCountedWithTheLargestChannelDelta) {
  TempDir dir("changed");
  const TextureData t = smallImage();
  writeImage(t, 0, 0, dir.str() + "/images/small.png");
  const golden::ManifestEntry e = entryFor(t, "images/small.png");
  std::vector<uint8_t> pixels = imagePixels(t, 0, 0);
  pixels[0] += 3;   // red of one pixel
  pixels[9] -= 7;   // green of another
  pixels[10] += 2;  // and its blue
  const golden::GoldenDiff d = golden::diffAgainstGolden(dir.str(), &e, pixels, Format::RGBA8);
  EXPECT_EQ(d.differingPixels, 2u);
  EXPECT_EQ(d.maxAbsDelta, 7.0);
  EXPECT_EQ(d.reason, "2 pixels differ from images/small.png (max |delta| 7)");
}

TEST(GoldenDiff, EachOtherKindOfMismatchHasItsReason) {
  TempDir dir("kinds");
  const TextureData t = smallImage();
  const std::vector<uint8_t> pixels = imagePixels(t, 0, 0);
  EXPECT_EQ(golden::diffAgainstGolden(dir.str(), nullptr, pixels, Format::RGBA8).reason, "no golden entry");

  golden::ManifestEntry e = entryFor(t, "images/absent.png");
  const golden::GoldenDiff missing = golden::diffAgainstGolden(dir.str(), &e, pixels, Format::RGBA8);
  EXPECT_NE(missing.reason.find(dir.str() + "/images/absent.png"), std::string::npos) << missing.reason;

  writeImage(t, 0, 0, dir.str() + "/images/small.png");
  e = entryFor(t, "images/small.png");
  const std::vector<uint8_t> wider(pixels.size() + 8, 0);
  const golden::GoldenDiff shape = golden::diffAgainstGolden(dir.str(), &e, wider, Format::RGBA8);
  EXPECT_TRUE(shape.shapeDiffers);
  EXPECT_EQ(shape.reason, "golden image has another size or format");

  e.imageSha256 = std::string(64, '0');
  EXPECT_EQ(golden::diffAgainstGolden(dir.str(), &e, pixels, Format::RGBA8).reason,
            "manifest hash differs from the image");
}

TEST(ImageFiles, AnExrOfTheSameImageHasTheSameBytesWhenWrittenAgainLater) {
  TempDir dir("exr-bytes");
  TextureDesc d;
  d.width = 4;
  d.height = 3;
  d.format = Format::R32UI;
  TextureData t(d);
  for (size_t i = 0; i < t.levels[0].size(); ++i) t.levels[0][i] = uint8_t(7 * i);
  const std::string a = dir.str() + "/images/a.exr", b = dir.str() + "/images/b.exr";
  writeImage(t, 0, 0, a);
  ::sleep(1);  // the writer's clock has second resolution
  writeImage(t, 0, 0, b);
  const auto bytes = [](const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_EQ(bytes(a), bytes(b));
  EXPECT_EQ(bytes(a).find("DateTime"), std::string::npos);
}

TEST(GoldenRun, UpdateRecreatesTheShippedEntriesAndCheckThenReportsEachKindOfDifference) {
  TempDir dir("run");
  golden::GoldenOptions o;
  o.dir = dir.str();
  o.railway = "";  // the built-in scenes only
  o.sceneImages = scenes::allSceneImages();

  // Into an empty directory: every image is new, and its entry is the shipped one.
  const golden::GoldenReport created = golden::updateGoldens(o);
  const golden::Manifest shipped = golden::readManifest(kShippedDir + "/manifest.json");
  size_t sceneEntries = 0;
  for (const auto& [name, e] : shipped.tests) sceneEntries += golden::isRailwayScene(e.scene) ? 0 : 1;
  EXPECT_EQ(created.tests, sceneEntries);
  EXPECT_EQ(created.passed, 0u);
  EXPECT_EQ(created.failed.size(), sceneEntries);
  ASSERT_EQ(created.changed.size(), sceneEntries);
  for (const golden::GoldenChange& c : created.changed) EXPECT_EQ(c.oldSha256, "") << c.test;
  const golden::Manifest written = golden::readManifest(dir.str() + "/manifest.json");
  ASSERT_EQ(written.tests.size(), sceneEntries);
  for (const auto& [name, e] : written.tests) EXPECT_EQ(e, shipped.tests.at(name)) << name;

  golden::GoldenReport r = golden::checkGoldens(o);
  EXPECT_TRUE(r.passedAll());
  EXPECT_EQ(r.passed, sceneEntries);

  // An older golden of blend: one pixel's red 5 lower, and its hash in the manifest; plus a stale entry.
  DecodedImage blend = readImage(dir.str() + "/images/blend.png");
  const std::string currentHash = sha256Hex(blend.pixels);
  blend.pixels[0] = uint8_t(blend.pixels[0] >= 5 ? blend.pixels[0] - 5 : blend.pixels[0] + 5);
  writePngRGBA8(dir.str() + "/images/blend.png", blend.width, blend.height, blend.pixels.data());
  golden::Manifest older = written;
  older.tests.at("blend").imageSha256 = sha256Hex(blend.pixels);
  older.tests["gone"] = older.tests.at("blend");
  golden::writeManifest(dir.str() + "/manifest.json", older);

  r = golden::checkGoldens(o);
  EXPECT_FALSE(r.passedAll());
  EXPECT_EQ(r.passed, sceneEntries - 1);
  ASSERT_EQ(r.failed.size(), 1u);
  EXPECT_EQ(r.failed[0].test, "blend");
  EXPECT_EQ(r.failed[0].reason, "1 pixels differ from images/blend.png (max |delta| 5)");
  EXPECT_EQ(r.stale, std::vector<std::string>{"gone"});
  const nlohmann::json j = r.toJson();
  EXPECT_EQ(j["failed"][0]["test"], "blend");
  EXPECT_EQ(j["stale_entries"][0], "gone");
  EXPECT_FALSE(j.contains("changed"));

  // Only the failing image is rewritten; the stale entry goes.
  const auto before = fs::last_write_time(dir.path / "images/depth.png");
  o.onlyFailing = true;
  r = golden::updateGoldens(o);
  ASSERT_EQ(r.changed.size(), 1u);
  EXPECT_EQ(r.changed[0].test, "blend");
  EXPECT_EQ(r.changed[0].oldSha256, sha256Hex(blend.pixels));
  EXPECT_EQ(r.changed[0].newSha256, currentHash);
  EXPECT_EQ(r.changed[0].pixelsChanged, 1);
  EXPECT_EQ(r.changed[0].maxAbsDelta, 5.0);
  EXPECT_EQ(fs::last_write_time(dir.path / "images/depth.png"), before);
  EXPECT_TRUE(r.toJson().contains("needed_update"));

  r = golden::checkGoldens(o);
  EXPECT_TRUE(r.passedAll());
  EXPECT_EQ(golden::readManifest(dir.str() + "/manifest.json").tests, written.tests);
}

}  // namespace tessera
