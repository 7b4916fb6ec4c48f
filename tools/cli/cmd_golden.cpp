// `tessera golden check | update`: the golden images under golden/ (Filament-style workflow).
//
// golden/manifest.json maps each test name to one image file, one to one:
//   "<scene>" = attachment 0 (layer 0), "<scene>.a<N>" = attachment N, "<scene>.l<N>" = layer N.
// Each entry records the file, its pixel hash (image_sha256: SHA-256 of the decoded pixels), format,
// size and provenance (the scene, size and command that produce it). `check` re-renders every scene
// and demands bit-exact pixels; `update` rewrites the images and the manifest and prints what changed.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>

#include <fmt/format.h>

#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "base/sha256.h"
#include "tools/cli/commands.h"
#include "tools/cli/frame_job.h"
#include "tools/cli/mta_golden.h"
#include "tools/cli/repo_paths.h"
#include "tools/scenes/scenes.h"

namespace tessera::cli {

namespace {

struct GoldenArgs {
  std::string dir = "golden";
  std::string railway = "data/railway.glb";
  bool onlyFailing = false;
};

struct Rendered {
  std::string name;
  const TextureData* tex;
  PresentedImage img;
};

std::string testName(const std::string& scene, const PresentedImage& p, uint32_t layers) {
  std::string n = scene;
  if (p.attachment) n += ".a" + std::to_string(p.attachment);
  if (layers > 1 && p.layer) n += ".l" + std::to_string(p.layer);
  return n;
}

nlohmann::json loadManifest(const std::string& dir) {
  const std::string path = dir + "/manifest.json";
  std::ifstream f(path);
  if (!f) return nlohmann::json{{"version", 1}, {"tests", nlohmann::json::object()}};
  nlohmann::json j = nlohmann::json::parse(f, nullptr, false);
  if (j.is_discarded() || !j.contains("tests") || !j["tests"].is_object())
    throw Error(path + ": not a golden manifest (expected an object with \"tests\")");
  return j;
}

// Compares decoded pixels; returns (differing pixels, max |delta| over channels).
std::pair<uint64_t, double> diffPixels(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, Format f) {
  if (a.size() != b.size()) return {~0ull, 0.0};
  const size_t bpt = texelBytes(f), ch = size_t(channelCount(f));
  uint64_t n = 0;
  double maxd = 0.0;
  for (size_t i = 0; i < a.size(); i += bpt) {
    if (std::memcmp(&a[i], &b[i], bpt) == 0) continue;
    ++n;
    for (size_t c = 0; c < ch; ++c) {
      double x, y;
      if (isUnorm(f)) {
        x = a[i + c], y = b[i + c];
      } else if (isFloat(f)) {
        float fx, fy;
        std::memcpy(&fx, &a[i + 4 * c], 4), std::memcpy(&fy, &b[i + 4 * c], 4);
        x = fx, y = fy;
      } else {
        uint32_t ux, uy;
        std::memcpy(&ux, &a[i + 4 * c], 4), std::memcpy(&uy, &b[i + 4 * c], 4);
        x = ux, y = uy;
      }
      maxd = std::max(maxd, std::fabs(x - y));
    }
  }
  return {n, maxd};
}

int runGolden(const GoldenArgs& a, bool update) {
  namespace fs = std::filesystem;
  nlohmann::json manifest = loadManifest(a.dir);
  nlohmann::json& tests = manifest["tests"];
  nlohmann::json result;
  nlohmann::json changed = nlohmann::json::array(), failed = nlohmann::json::array();
  size_t checked = 0, passed = 0;
  std::map<std::string, bool> seen;
  if (update) {
    std::error_code ec;
    fs::create_directories(a.dir + "/images", ec);
    if (ec) throw Error(a.dir + "/images: cannot create: " + ec.message());
  }
  // One presented image against its entry.
  auto checkImage = [&](const std::string& name, const TextureData& tex, uint32_t level, uint32_t layer, const std::string& scene,
                        uint32_t attachment, const std::string& command) {
    seen[name] = true;
    const auto pixels = imagePixels(tex, level, layer);
    const std::string hash = sha256Hex(pixels);
    const std::string file = "images/" + name + imageExtension(tex.desc.format);
    ++checked;
    std::string why;
    uint64_t ndiff = 0;
    double maxd = 0.0;
    if (!tests.contains(name)) {
      why = "no golden entry";
    } else {
      const nlohmann::json& e = tests[name];
      const std::string path = a.dir + "/" + e.value("file", "");
      std::vector<uint8_t> golden;
      try {
        golden = readImage(path).pixels;
      } catch (const Error& err) {
        why = err.what();
      }
      if (why.empty()) {
        std::tie(ndiff, maxd) = diffPixels(golden, pixels, tex.desc.format);
        if (ndiff == ~0ull) why = "golden image has another size or format";
        else if (ndiff) why = fmt::format("{} pixels differ from {} (max |delta| {})", ndiff, e["file"].get<std::string>(), maxd);
        else if (e.value("image_sha256", "") != hash) why = "manifest hash differs from the image";
      }
    }
    if (why.empty()) {
      ++passed;
      if (!update || a.onlyFailing) return;
    } else {
      failed.push_back({{"test", name}, {"reason", why}});
    }
    if (!update) return;
    const std::string oldHash = tests.contains(name) ? tests[name].value("image_sha256", "") : "";
    writeImage(tex, level, layer, a.dir + "/" + file);
    tests[name] = {{"file", file},
                   {"image_sha256", hash},
                   {"format", std::string(formatName(tex.desc.format))},
                   {"width", levelWidth(tex.desc, level)},
                   {"height", levelHeight(tex.desc, level)},
                   {"scene", scene},
                   {"attachment", attachment},
                   {"layer", layer},
                   {"command", command}};
    if (oldHash != hash)
      changed.push_back({{"test", name}, {"old_sha256", oldHash}, {"new_sha256", hash},
                         {"pixels_changed", ndiff == ~0ull ? -1 : int64_t(ndiff)}, {"max_abs_delta", maxd}});
  };
  for (const scenes::SceneInfo& s : scenes::all()) {
    const std::string scene(s.name);
    const CommandList list = scenes::build(s.name, s.width, s.height);
    CpuBackend backend;
    backend.execute(list, scene);
    for (const PresentedImage& p : backend.presented()) {
      const TextureData& tex = *backend.texture(p.texture);
      checkImage(testName(scene, p, tex.desc.layers), tex, p.level, p.layer, scene, p.attachment,
                 fmt::format("tessera render {} --size {}x{}", scene, s.width, s.height));
    }
  }
  // Atlas tree frames of railway.glb in deterministic-budget mode (docs/mta-render.md).
  for (const MtaGoldenFrame& f : mtaGoldenFrames(a.railway)) checkImage(f.name, *f.image, 0, 0, "mta_railway", 0, f.command);
  // Entries for images that no scene presents any more are stale.
  nlohmann::json stale = nlohmann::json::array();
  for (auto it = tests.begin(); it != tests.end(); ++it)
    if (!seen.count(it.key())) stale.push_back(it.key());
  if (update) {
    for (const auto& n : stale) tests.erase(n.get<std::string>());
    writeTextFile(a.dir + "/manifest.json", manifest.dump(2) + "\n");
  }
  result["tests"] = checked;
  result["passed"] = passed;
  result[update ? "needed_update" : "failed"] = failed;
  if (update) result["changed"] = changed;
  result["stale_entries"] = stale;
  std::printf("%s\n", result.dump(2).c_str());
  if (update) {
    for (const auto& c : changed)
      std::fprintf(stderr, "golden: %s changed (%s -> %s)\n", c["test"].get<std::string>().c_str(),
                   c["old_sha256"].get<std::string>().substr(0, 12).c_str(),
                   c["new_sha256"].get<std::string>().substr(0, 12).c_str());
    return 0;
  }
  return failed.empty() && stale.empty() ? 0 : 1;
}

}  // namespace

void addGoldenCommands(CLI::App& app) {
  auto* golden = app.add_subcommand("golden", "Check or regenerate the golden images (golden/manifest.json)");
  golden->require_subcommand(1);
  auto a = std::make_shared<GoldenArgs>();
  auto* check = golden->add_subcommand("check", "Re-render every scene; demand bit-exact pixels (exit 1 on any difference)");
  check->add_option("--dir", a->dir, "Golden directory")->capture_default_str();
  check->add_option("--railway", a->railway, "railway.glb, the real scene of the atlas tree goldens (data/README.md)")->capture_default_str();
  // The defaults are repository paths: found from the clone's root or beside the build folder.
  check->callback([a] {
    a->dir = repoPath(a->dir), a->railway = repoPath(a->railway);
    if (int rc = runGolden(*a, false)) throw CLI::RuntimeError(rc);
  });
  auto* update = golden->add_subcommand("update", "Regenerate golden images and the manifest; print what changed");
  update->add_option("--dir", a->dir, "Golden directory")->capture_default_str();
  update->add_option("--railway", a->railway, "railway.glb, the real scene of the atlas tree goldens (data/README.md)")->capture_default_str();
  update->add_flag("--only-failing", a->onlyFailing, "Rewrite only the images that no longer match");
  update->callback([a] {
    a->dir = repoPath(a->dir), a->railway = repoPath(a->railway);
    runGolden(*a, true);
  });
}

}  // namespace tessera::cli
