// `tessera tab render` (cmd_tab.cpp registers it; `tessera demo` runs it on railway.glb): a batched
// scene over a camera path, batched and / or baseline, with per-frame counters, images, recorded
// frames, a pixel comparison of the two variants, plot.png and index.html (docs/tab.md).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "base/resource_limits.h"

namespace tessera::cli {

struct TabRenderArgs {
  std::string input;  // .tab file
  std::string out;
  std::string path = "orbit";
  uint32_t frames = 0;  // 0 = the path's own count
  std::string size = "640x480";
  int threads = 0;
  uint32_t saveEvery = 10;
  bool baseline = false, both = false;
  bool quiet = false;
  ResourceLimits limits;  // the .tab reader's texture and vertex budgets (--model-budget-*)
};

// Writes under a.out: <variant>_NNNN.png and .tframe for saved frames (and diff_NNNN.png with --both),
// frames.json, plot.png, index.html. Returns the summary.
nlohmann::json runTabRender(const TabRenderArgs& a);

}  // namespace tessera::cli
