// The atlas tree's golden frames: railway.glb (the real scene in data/, see data/README.md) built with d_min 5 and
// rendered over the thesis path in a deterministic-budget mode. `tessera golden check|update` includes
// them beside the built-in scenes; the entry's "command" reproduces each frame with the CLI.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "raster/texture.h"

namespace tessera::cli {

struct MtaGoldenFrame {
  std::string name;  // "mta_railway.fNNN"
  std::shared_ptr<TextureData> image;
  std::string command;
};

// Throws Error naming the file when railway.glb is missing.
std::vector<MtaGoldenFrame> mtaGoldenFrames(const std::string& railwayPath);

}  // namespace tessera::cli
