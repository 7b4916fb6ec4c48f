// `tessera tab`: texture-array batching (Trapp & Döllner 2015) of a model — build a .tab file, describe
// it with Table 1's columns, and render it over a camera path with and without batching
// (docs/tab.md, docs/tab-format.md).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "base/error.h"
#include "base/sha256.h"
#include "batching/batcher.h"
#include "batching/input_batches.h"
#include "batching/tab_file.h"
#include "batching/tab_record.h"
#include "batching/tab_stats.h"
#include "model/model.h"
#include "mta/camera.h"
#include "mta/camera_path.h"
#include "raster/counters.h"
#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "raster/serialize.h"
#include "tools/cli/commands.h"
#include "tools/cli/frame_job.h"
#include "tools/cli/mta_path_run.h"
#include "tools/cli/options.h"
#include "tools/cli/output_directory.h"
#include "tools/cli/tab_render.h"

namespace tessera::cli {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The peak resident set of this process (VmHWM), 0 where /proc is missing.
uint64_t peakResidentBytes() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("VmHWM:", 0) == 0) return uint64_t(std::stoull(line.substr(6))) * 1024;
  return 0;
}

struct TabBuildArgs {
  std::string model, out;
  batching::TabParams p;
  ResourceLimits limits;
  bool quiet = false;
};

void addBuild(CLI::App* tab) {
  auto a = std::make_shared<TabBuildArgs>();
  auto* build = tab->add_subcommand(
      "build",
      "Batch a model's textured meshes (Algorithm 1): textures of one resolution, format and wrap mode share a texture "
      "array, meshes merge into geometry batches of at most --b-max vertices; writes a .tab file and prints Table 1's "
      "columns as JSON");
  build->add_option("model", a->model, "Model file (glTF, OBJ, AC3D, Assimp formats)")->required();
  build->add_option("-o,--output", a->out, "Output .tab file (written atomically)")->required();
  build->add_option("--b-max", a->p.bMax, "Vertices per geometry batch (> 3; 3 per triangle, non-indexed)")->capture_default_str();
  build->add_option("--d-max", a->p.dMax, "Layers per texture array (1..2048)")->capture_default_str();
  build->add_option("--a-max", a->p.aMax, "Texture arrays per output batch (1..8: texarray_batch's switch width)")
      ->capture_default_str();
  addModelBudgetOptions(build, a->limits);
  build->add_flag("--quiet", a->quiet, "No progress on stderr");
  build->callback([a] {
    batching::validateParams(a->p, "tab build");  // before any work
    const auto t0 = Clock::now();
    const model::Model m = model::loadModel(a->model, a->limits);
    const double loadS = secondsSince(t0);
    batching::InputOptions io;
    double lastPrint = -1e9;
    const auto tDecode = Clock::now();
    if (!a->quiet)
      io.progress = [&](size_t done, size_t total) {  // about every 2 s, with the time left
        const double t = secondsSince(tDecode);
        if (t - lastPrint < 2.0 && done != total) return;
        lastPrint = t;
        std::fprintf(stderr, "tab build: textures %zu/%zu decoded with mip chains (%.1f s, about %.0f s left)\n", done, total,
                     t, done ? t * double(total - done) / double(done) : 0.0);
      };
    batching::TabScene s = batching::prepareInput(m, io);
    const auto t1 = Clock::now();
    batching::runAlgorithm1(s, a->p);
    const double batchS = secondsSince(t1);
    batching::writeTabFile(s, a->out);
    nlohmann::json j = batching::tableOneJson(s);
    j["file"] = {{"path", a->out}, {"bytes", uint64_t(fs::file_size(a->out))}};
    j["build"] = {{"seconds", secondsSince(t0)},
                  {"load_seconds", loadS},
                  {"algorithm1_seconds", batchS},
                  {"peak_resident_bytes", peakResidentBytes()}};
    std::printf("%s\n", j.dump(2).c_str());
  });
}

void addInfo(CLI::App* tab) {
  auto path = std::make_shared<std::string>();
  auto limits = std::make_shared<ResourceLimits>();
  auto* info = tab->add_subcommand("info", "Validate a .tab file and print Table 1's columns as JSON");
  info->add_option("file", *path, "A .tab file")->required();
  addModelBudgetOptions(info, *limits);
  info->callback([path, limits] {
    const batching::TabScene s = batching::readTabFile(*path, *limits);
    nlohmann::json j = batching::tableOneJson(s);
    j["file"] = {{"path", *path}, {"bytes", uint64_t(fs::file_size(*path))}};
    std::printf("%s\n", j.dump(2).c_str());
  });
}

void addTabRender(CLI::App* tab) {
  auto a = std::make_shared<TabRenderArgs>();
  auto* render = tab->add_subcommand(
      "render",
      "Render a .tab file over a camera path, batched (Algorithm 2: texarray_batch, one draw per geometry batch) "
      "and/or as the unbatched baseline (one draw per mesh with `textured`): PNG and .tframe frames, frames.json, "
      "plot.png and index.html; prints a summary");
  render->add_option("file", a->input, "A .tab file")->required();
  render->add_flag("--baseline", a->baseline, "Render only the baseline (w/o TAB)");
  render->add_flag("--both", a->both, "Render both variants and compare their images pixel by pixel");
  render->add_option("--path", a->path,
                     "Camera path: orbit, street, thesis (laid out over the scene's bounds) or a camera path file "
                     "(docs/mta-camera-path.md)")
      ->capture_default_str();
  render->add_option("--frames", a->frames, "Frames (0 = the path's own count)")->capture_default_str();
  addSizeOption(render, a->size, "Frame size WxH")->capture_default_str();
  addThreadsOption(render, a->threads, "Oracle worker threads; images never depend on it");
  render->add_option("--save-every", a->saveEvery, "Write PNG and .tframe of every K-th frame and the last (0 = none)")
      ->capture_default_str();
  render->add_option("-o,--output", a->out, "Output directory")->required();
  addModelBudgetOptions(render, a->limits);
  render->add_flag("--quiet", a->quiet, "No progress on stderr");
  render->callback([a] { std::printf("%s\n", runTabRender(*a).dump(2).c_str()); });
}

}  // namespace

void addTabCommands(CLI::App& app) {
  auto* tab = app.add_subcommand("tab", "Texture-array batching, TAB (Trapp & Döllner 2015): build, describe and render batched scenes");
  tab->require_subcommand(1);
  addBuild(tab);
  addInfo(tab);
  addTabRender(tab);
}

}  // namespace tessera::cli
