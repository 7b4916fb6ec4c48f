#include "tools/cli/mta_path_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "raster/image_io.h"
#include "tools/cli/frame_job.h"
#include "tools/cli/options.h"

namespace tessera::cli {

namespace {

// --capacity in MiB: positive; the upper end keeps capacity * 2^20 far inside 64 bits.
constexpr RealRange kCapacityMiB{0.0, 1e9, true, false};

}  // namespace

void addPathRunOptions(CLI::App* cmd, PathRunArgs& a, bool withMemory) {
  std::string names;
  for (const std::string& n : mta::builtinPathNames()) names += (names.empty() ? "" : ", ") + n;
  cmd->add_option("--path", a.path, "Camera path: a built-in name (" + names + ") laid out over the scene, or a path file (docs/mta-camera-path.md)")
      ->capture_default_str();
  cmd->add_option("--frames", a.frames, "Number of frames (0 = the path's own; built-in paths are resampled)");
  addSizeOption(cmd, a.size, "Frame size WxH (minDistance is rescaled from the build's screen width)")
      ->capture_default_str();
  if (withMemory) {
    addRealOption(cmd, "--capacity", a.capacityMiB,
                  "Memory manager capacity k in MiB of paging-file blocks (never exceeded)", kCapacityMiB)
        ->capture_default_str();
    cmd->add_option("--budget", a.budget,
                    "Loading per frame: bytes (e.g. 8MiB, 500KiB), blocks (4blocks) - deterministic - or a wall-clock slot "
                    "with a background loader (5ms; not reproducible); 'unlimited' loads the whole ideal set every frame")
        ->capture_default_str();
    cmd->add_option("--queue", a.queue, "Request queue length")->capture_default_str();
  }
  addRealOption(cmd, "--tau", a.tau, "Pixel-per-texel ratio at run time (default: the build's)", kPositive);
  cmd->add_option("--distance-bound", a.distanceBound,
                  "How the distance test d >= minDistance accounts for off-axis magnification (docs/mta-render.md): node = d "
                  "times cos^2 of the largest view angle over the node's box clipped to the frustum; corner = d times cos^2 "
                  "of the frustum's corner angle for every node; both keep the tau guarantee at every pixel, node with fewer "
                  "nodes; thesis = plain d (the guarantee holds on the view axis only)")
      ->check(CLI::IsMember({"node", "corner", "thesis"}))
      ->capture_default_str();
  cmd->add_flag("--thesis-distance", a.thesisDistance, "The same as --distance-bound thesis");
  cmd->add_flag("--no-group-binds", a.noGroupBinds,
                "Record the draws leaf by leaf as the traversal emits them, binding a leaf's original textures again for "
                "every leaf; by default draws are grouped by texture, so each texture is bound once a frame (same triangles "
                "and depth test; only pixels where two fragments tie in depth can differ, docs/mta-render.md)");
  cmd->add_option("--max-binds", a.maxBinds,
                  "Cap texture binds per frame at N by drawing the refined nodes that miss the distance test by the least "
                  "with their resident atlases instead (0 = no cap, the thesis). Gives up the tau guarantee on those nodes: "
                  "frames.json counts them (nodes_coarsened_for_binds) and how far they fall short (bind_cap_worst_ratio); "
                  "docs/mta-render.md")
      ->check(CLI::Range(0u, 1000000u))
      ->capture_default_str();
  addMemoryBudgetOption(cmd, a.limits);
  addThreadsOption(cmd, a.threads, "Oracle threads; images never depend on it");
  cmd->add_option("--save-every", a.saveEvery, "Write every N-th frame as PNG (0 = none); the last frame is always written")
      ->capture_default_str();
  cmd->add_option("-o,--output", a.out, "Output directory")->required();
  cmd->add_flag("--quiet", a.quiet, "No progress on stderr");
}

mta::CameraPath loadPath(const PathRunArgs& a, const mta::MtaMeta& meta) {
  const auto names = mta::builtinPathNames();
  mta::CameraPath p;
  if (std::find(names.begin(), names.end(), a.path) != names.end()) {
    p = mta::builtinPathOverTree(a.path, meta, a.frames);
  } else {
    if (!std::filesystem::exists(a.path))
      throw Error("--path '" + a.path + "': neither a built-in path (" + [&] {
        std::string s;
        for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
        return s;
      }() + ") nor an existing file");
    p = mta::readPathFile(a.path);
    if (a.frames && a.frames < p.frames.size()) p.frames.resize(a.frames);
  }
  return p;
}

mta::RendererOptions rendererOptions(const PathRunArgs& a, mta::RenderMode mode) {
  mta::RendererOptions o;
  o.mode = mode;
  const auto [w, h] = parseSize(a.size, "--size");
  o.width = uint32_t(w);
  o.height = uint32_t(h);
  // 0 = the build's tau; any value given is checked by --tau's range (kPositive) while parsing.
  if (!(a.tau == 0.0 || kPositive.contains(a.tau))) throw Error("--tau must be a finite number > 0");
  o.tau = a.tau;
  o.bound = a.thesisDistance ? mta::DistanceBound::Thesis : mta::parseDistanceBound(a.distanceBound, "--distance-bound");
  o.groupBinds = !a.noGroupBinds;
  if (a.maxBinds != 0 && a.noGroupBinds)
    throw Error("--max-binds counts the binds of draws grouped by texture: it cannot be combined with --no-group-binds");
  o.maxBinds = a.maxBinds;
  o.threads = a.threads;
  o.limits.frameBytes = a.limits.frameBytes;
  if (!kCapacityMiB.contains(a.capacityMiB))
    throw Error("--capacity must be a number of MiB " + kCapacityMiB.describe());
  o.residency.capacityBytes = uint64_t(a.capacityMiB * 1048576.0);
  if (a.budget == "unlimited") {
    o.residency.budget.kind = mta::LoadBudget::Kind::Blocks;
    o.residency.budget.perFrame = UINT64_MAX;
    o.residency.maxQueue = UINT32_MAX;
  } else {
    o.residency.budget = mta::LoadBudget::parse(a.budget, "--budget");
    o.residency.maxQueue = a.queue;
  }
  return o;
}

nlohmann::json optionsJson(const PathRunArgs& a, const mta::RendererOptions& o, const mta::CameraPath& path) {
  return {{"input", a.input},
          {"path", a.path},
          {"path_name", path.name},
          {"frames", path.frames.size()},
          {"width", o.width},
          {"height", o.height},
          {"capacity_bytes", o.residency.capacityBytes},
          {"budget", a.budget == "unlimited" ? std::string("unlimited") : o.residency.budget.describe()},
          {"queue", o.residency.maxQueue},
          {"tau", o.tau},
          {"distance_bound", mta::distanceBoundName(o.bound)},
          {"draw_order", o.groupBinds ? "grouped by texture" : "leaf by leaf (--no-group-binds)"},
          {"max_binds", o.maxBinds}};
}

void writeFramePng(const std::string& path, uint32_t w, uint32_t h, const std::vector<uint8_t>& bottomUp) {
  std::vector<uint8_t> top(bottomUp.size());
  const size_t row = size_t(w) * 4;
  for (uint32_t y = 0; y < h; ++y) std::copy_n(bottomUp.data() + size_t(h - 1 - y) * row, row, top.data() + size_t(y) * row);
  writePngRGBA8(path, int(w), int(h), top.data());
}

void writeChartPng(const std::string& path, const verify::RgbaCanvas& c) { writePngRGBA8(path, c.width(), c.height(), c.data()); }

Progress::Progress(std::string label, size_t total, bool quiet) : label_(std::move(label)), total_(total), quiet_(quiet) {}

void Progress::tick(size_t done, const std::string& detail) {
  if (quiet_) return;
  const double now = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  if (now - last_ < 2.0 && done != total_) return;
  last_ = now;
  std::fprintf(stderr, "%s: frame %zu/%zu %s\n", label_.c_str(), done, total_, detail.c_str());
}

std::pair<double, double> maxMean(const std::vector<double>& v) {
  double mx = 0.0, sum = 0.0;
  for (double x : v) mx = std::max(mx, x), sum += x;
  return {mx, v.empty() ? 0.0 : sum / double(v.size())};
}

std::vector<double> column(const nlohmann::json& rows, const char* key) {
  std::vector<double> v;
  for (const auto& r : rows) v.push_back(r.contains(key) && !r[key].is_null() ? r[key].get<double>() : NAN);
  return v;
}

bool saveFrame(const PathRunArgs& a, size_t i, size_t n) { return a.saveEvery && (i % a.saveEvery == 0 || i + 1 == n); }

std::string frameName(const char* prefix, size_t i) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%04zu.png", prefix, i);
  return buf;
}

}  // namespace tessera::cli
