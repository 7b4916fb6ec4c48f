// What `tessera mta render`, `tessera mta runs` and `tessera texel` share: opening a tree, choosing a
// camera path, the renderer options, saving frames and plots.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/resource_limits.h"
#include "mta/camera_path.h"
#include "mta/paging_file.h"
#include "mta/tree_renderer.h"
#include "verify/line_chart.h"

namespace tessera::cli {

struct PathRunArgs {
  std::string input;          // .mta (or, for texel, a model file built first)
  std::string out;
  std::string path = "thesis";
  uint32_t frames = 0;        // 0 = the path's own count
  std::string size = "1024x768";
  double capacityMiB = 100.0; // the thesis's 100 MB
  std::string budget = "8MiB";
  uint32_t queue = 32;
  double tau = 0.0;
  bool thesisDistance = false;
  std::string distanceBound = "node";
  bool noGroupBinds = false;  // planFrame's leaf-by-leaf draw order (RendererOptions::groupBinds off)
  uint32_t maxBinds = 0;      // RendererOptions::maxBinds (0 = no cap)
  int threads = 0;
  uint32_t saveEvery = 25;    // 0 = no frame images
  bool recordFrames = false;  // mta render: a .tframe next to every saved frame image (--record)
  bool quiet = false;
  double buildDMin = 0.0;     // texel with a model: d_min of the build (0 = D / 72)
  ResourceLimits limits;      // --memory-budget (frameBytes); texel with a model: the model budgets (--model-budget-*)
};

// Registers the options above on a subcommand.
void addPathRunOptions(CLI::App* cmd, PathRunArgs& a, bool withMemory);

mta::CameraPath loadPath(const PathRunArgs& a, const mta::MtaMeta& meta);
mta::RendererOptions rendererOptions(const PathRunArgs& a, mta::RenderMode mode);
nlohmann::json optionsJson(const PathRunArgs& a, const mta::RendererOptions& o, const mta::CameraPath& path);

// RGBA8 rows bottom first -> PNG (top first), atomically.
void writeFramePng(const std::string& path, uint32_t w, uint32_t h, const std::vector<uint8_t>& bottomUp);
void writeChartPng(const std::string& path, const verify::RgbaCanvas& c);

// Prints "label frame i/n (..)" about every 2 s on stderr unless quiet.
class Progress {
 public:
  Progress(std::string label, size_t total, bool quiet);
  void tick(size_t done, const std::string& detail);

 private:
  std::string label_;
  size_t total_;
  bool quiet_;
  double last_ = -1e9;
};

// The three commands (cmd_mta_render.cpp, cmd_mta_runs.cpp, cmd_texel.cpp); each writes its files under
// a.out and returns its summary.
nlohmann::json runMtaRender(const PathRunArgs& a);
nlohmann::json runMtaRuns(const PathRunArgs& a, int tolerance);
nlohmann::json runTexel(const PathRunArgs& a);

// max, mean of a series.
std::pair<double, double> maxMean(const std::vector<double>& v);
// The series of rows[i][key]; NaN where a row lacks it or holds null (a gap in the charts).
std::vector<double> column(const nlohmann::json& rows, const char* key);
// Whether frame i of n is written as PNG: every a.saveEvery-th and the last (none when saveEvery is 0).
bool saveFrame(const PathRunArgs& a, size_t i, size_t n);
// "<prefix>_NNNN.png".
std::string frameName(const char* prefix, size_t i);

// The colours of the charts' series.
inline constexpr verify::Rgba kBlue{40, 90, 200, 255}, kRed{210, 50, 40, 255}, kGreen{30, 150, 60, 255},
    kGrey{110, 110, 110, 255}, kOrange{230, 140, 20, 255}, kPurple{140, 60, 170, 255};

}  // namespace tessera::cli
