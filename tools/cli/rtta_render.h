// `tessera rtta render` and `tessera rtta params` (cmd_rtta.cpp registers them; `tessera demo` runs the
// render on the built-in five-object scene): render-to-texture-atlas against STD and RTT over a camera
// path, with per-frame counters, composite and atlas-layer images, recorded frames, pixel comparisons,
// table.json (Table 1 of Trapp & Döllner 2010), plot.png and index.html (docs/rtta.md).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/resource_limits.h"

namespace tessera::cli {

// --border not given (no one passes this value): 1, or the occlusion kernel's radius for ghosted-ao.
inline constexpr int32_t kDefaultBorder = INT32_MIN;

struct RttaRenderArgs {
  std::string input;  // a model file, or a built-in scene name (rttaSceneNames())
  std::string out;
  std::string mode = "all";  // std | rtt | rtta | all
  std::string composite = "depth";
  std::string path = "orbit";
  uint32_t frames = 0;       // 0 = the path's own count
  std::string size = "1024x1024";
  std::string atlas;         // WxH; empty = the smallest power of two >= viewport + 2 border per side
  int32_t border = kDefaultBorder;  // kDefaultBorder: 1, or the occlusion kernel's radius for ghosted-ao
  bool noCull = false;
  std::string objects = "mesh";   // mesh | node
  std::string texturing = "bind"; // bind | tab
  std::string layers = "exact";   // exact | lazy:K
  std::vector<uint32_t> important;
  int threads = 0;
  uint32_t saveEvery = 10;
  bool quiet = false;
  ResourceLimits limits;
};

// Built-in scenes `rtta render` accepts instead of a model file.
std::vector<std::string> rttaSceneNames();

// Writes under a.out: <mode>_NNNN.png, atlas_NNNN_L.png and .tframe files for saved frames,
// frames.json, table.json, plot.png, index.html. Returns the summary.
nlohmann::json runRttaRender(const RttaRenderArgs& a);

// The records of one frame as JSON (`rtta params`): camera = the first frame of a.path.
nlohmann::json rttaParams(const RttaRenderArgs& a);

}  // namespace tessera::cli
