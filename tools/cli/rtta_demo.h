// The render-to-texture-atlas part of `tessera demo`: the built-in five-object scene (like the paper's
// Fig. 1) and railway.glb rendered STD, RTT and RTTA over the orbit path, with Table 1's measures, the
// pixel agreement of the composites with STD, the atlas layers with their regions outlined, and the
// ghosted composite. Writes under OUT/rtta and returns the report JSON and an HTML section.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace tessera::cli {

struct RttaDemoResult {
  nlohmann::json report;
  std::string html;
};

// Throws Error naming the file when railway.glb is missing.
RttaDemoResult runRttaDemo(const std::string& outDir, const std::string& railwayPath, int threads);

}  // namespace tessera::cli
