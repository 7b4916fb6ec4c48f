// The atlas tree's golden frames: railway.glb (the real scene in data/, see data/README.md) built with
// d_min 5 and rendered over the thesis path in a deterministic-budget mode (docs/mta-render.md).
//
// Implements: building the tree into a temporary directory and rendering the 60 frames of the thesis
// path at 256x192 with a 48 MiB memory manager and a 4 MiB load budget per frame, keeping frames 0, 15,
// 30, 45 and 59. This is exactly what the entry's "command" does with the CLI
// (`tessera mta render tree.mta --path thesis --frames 60 --size 256x192 --capacity 48 --budget 4MiB`):
// the path is mta::builtinPathOverTree, as the CLI lays out a built-in path, and the renderer options
// are those that tools/cli/mta_path_run.cpp rendererOptions() makes of these flags (a change there must
// change them here; the CLI case railway_golden_command_reproduces_the_golden_frames catches a drift).
// Does not implement: comparing the frames (golden_diff.h).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "raster/texture.h"

namespace tessera::golden {

// The manifest's "scene" of these frames.
inline constexpr const char* kRailwayScene = "mta_railway";

struct RailwayFrame {
  std::string name;                    // "mta_railway.fNNN"
  std::shared_ptr<TextureData> image;  // RGBA8, one level, rows bottom first
  std::string command;
};

// Throws Error naming the file when railway.glb is missing.
std::vector<RailwayFrame> railwayFrames(const std::string& railwayPath);

}  // namespace tessera::golden
