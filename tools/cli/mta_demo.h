// The atlas tree part of `tessera demo`: railway.glb (the real city scene in data/, see data/README.md) built into an
// atlas tree and run over the thesis path: memory-managed rendering with its plot, the three runs of
// §4.7.2, and the texel-per-pixel analysis. Writes under OUT/mta and returns the report JSON and an
// HTML section for index.html.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace tessera::cli {

struct MtaDemoResult {
  nlohmann::json report;
  std::string html;
};

// Throws Error naming the file when railway.glb is missing.
MtaDemoResult runMtaDemo(const std::string& outDir, const std::string& railwayPath, int threads);

}  // namespace tessera::cli
