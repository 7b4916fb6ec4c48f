#include "golden/golden_run.h"

#include <filesystem>
#include <set>

#include "base/error.h"
#include "golden/golden_diff.h"
#include "golden/golden_images.h"
#include "golden/manifest.h"
#include "golden/railway_frames.h"
#include "golden/tab_railway_frames.h"
#include "raster/image_io.h"

namespace tessera::golden {

namespace {

GoldenReport run(const GoldenOptions& o, bool update) {
  Manifest manifest = loadManifest(o.dir);
  GoldenReport report;
  report.update = update;
  std::set<std::string> seen;
  if (update) {
    std::error_code ec;
    std::filesystem::create_directories(o.dir + "/images", ec);
    if (ec) throw Error(o.dir + "/images: cannot create: " + ec.message());
  }
  renderGoldenImages(o.sceneImages, o.railway, [&](const RenderedImage& img) {
    seen.insert(img.name);
    const TextureData& tex = *img.texture;
    const std::vector<uint8_t> pixels = imagePixels(tex, img.level, img.layer);
    const auto it = manifest.tests.find(img.name);
    const ManifestEntry* entry = it == manifest.tests.end() ? nullptr : &it->second;
    const GoldenDiff diff = diffAgainstGolden(o.dir, entry, pixels, tex.desc.format);
    ++report.tests;
    if (diff.matches()) {
      ++report.passed;
      if (!update || o.onlyFailing) return;
    } else {
      report.failed.push_back({img.name, diff.reason});
    }
    if (!update) return;
    const std::string oldHash = entry ? entry->imageSha256 : "";
    const std::string file = "images/" + img.name + imageExtension(tex.desc.format);
    writeImage(tex, img.level, img.layer, o.dir + "/" + file);
    ManifestEntry e;
    e.file = file;
    e.imageSha256 = diff.sha256;
    e.format = std::string(formatName(tex.desc.format));
    e.width = levelWidth(tex.desc, img.level);
    e.height = levelHeight(tex.desc, img.level);
    e.scene = img.scene;
    e.attachment = img.attachment;
    e.layer = img.layer;
    e.command = img.command;
    manifest.tests[img.name] = e;
    if (oldHash != diff.sha256)
      report.changed.push_back(
          {img.name, oldHash, diff.sha256, diff.shapeDiffers ? -1 : int64_t(diff.differingPixels), diff.maxAbsDelta});
  });
  // Entries for images that nothing presents any more are stale. Without railway.glb the atlas tree
  // frames were not rendered, so their entries say nothing.
  for (const auto& [name, e] : manifest.tests)
    if (!seen.count(name) && !(o.railway.empty() && isRailwayScene(e.scene))) report.stale.push_back(name);
  if (update) {
    for (const std::string& n : report.stale) manifest.tests.erase(n);
    writeManifest(o.dir + "/manifest.json", manifest);
  }
  return report;
}

}  // namespace

nlohmann::json GoldenReport::toJson() const {
  nlohmann::json fails = nlohmann::json::array(), changes = nlohmann::json::array();
  for (const GoldenFailure& f : failed) fails.push_back({{"test", f.test}, {"reason", f.reason}});
  for (const GoldenChange& c : changed)
    changes.push_back({{"test", c.test},
                       {"old_sha256", c.oldSha256},
                       {"new_sha256", c.newSha256},
                       {"pixels_changed", c.pixelsChanged},
                       {"max_abs_delta", c.maxAbsDelta}});
  nlohmann::json j;
  j["tests"] = tests;
  j["passed"] = passed;
  j[update ? "needed_update" : "failed"] = fails;
  if (update) j["changed"] = changes;
  j["stale_entries"] = stale;
  return j;
}

GoldenReport checkGoldens(const GoldenOptions& options) { return run(options, false); }
GoldenReport updateGoldens(const GoldenOptions& options) { return run(options, true); }

}  // namespace tessera::golden
