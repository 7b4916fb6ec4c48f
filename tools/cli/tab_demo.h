// The texture-array batching part of `tessera demo`: railway.glb batched (Algorithm 1, default limits)
// and rendered over the orbit path both batched and unbatched, with the draw-call and bind reductions,
// the pixel agreement of the two variants and the frames. Writes under OUT/tab and returns the report
// JSON and an HTML section for index.html.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace tessera::cli {

struct TabDemoResult {
  nlohmann::json report;
  std::string html;
};

// Throws Error naming the file when railway.glb is missing.
TabDemoResult runTabDemo(const std::string& outDir, const std::string& railwayPath, int threads);

}  // namespace tessera::cli
