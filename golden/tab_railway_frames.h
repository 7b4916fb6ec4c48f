// The texture-array batching golden frames: railway.glb batched with the default limits
// (`tessera tab build`) and drawn batched over the orbit path (`tessera tab render`), which exercises
// Algorithm 1 on a real model (two output batches, nine arrays, NPOT layers), the TAM material layout
// of texarray_batch and REPEAT sampling from arrays.
//
// Implements: building the TabScene in memory and rendering the 24 frames of the orbit path at 256x192,
// keeping frames 0, 8, 16 and 23: exactly what the entries' "command" does with the CLI (the path is
// mta::builtinPath over the TabScene's bounds, as `tab render` lays it out; the .tab file round trip
// changes nothing, which TabFile.ARoundTripGivesTheSameScene checks).
// Does not implement: comparing the frames (golden_diff.h).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "golden/railway_frames.h"
#include "golden/rtta_railway_frames.h"

namespace tessera::golden {

inline constexpr const char* kTabRailwayScene = "tab_railway";

// Whether a manifest entry's scene is rendered from railway.glb (atlas tree, TAB or RTTA frames) rather than
// presented by a built-in scene.
inline bool isRailwayScene(std::string_view scene) {
  return scene == kRailwayScene || scene == kTabRailwayScene || scene == kRttaRailwayScene;
}

// Throws Error naming the file when railway.glb is missing.
std::vector<RailwayFrame> tabRailwayFrames(const std::string& railwayPath);

}  // namespace tessera::golden
