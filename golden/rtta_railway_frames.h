// The render-to-texture-atlas golden frames: railway.glb with one object per mesh, captured into the
// layered atlas by screen-space vertex displacement and composited with depth sprites (`tessera rtta
// render --mode rtta`), which exercises Algorithm 1 (culling, near-plane clipping, packing, exact
// transforms) on a real model, the two-attachment layered capture (atlas_capture) and fragment depth
// (atlas_sprite).
//
// Implements: rendering the 24 frames of the orbit path at 256x192 (atlas 512x256, border 1) and
// keeping frames 0, 8, 16 and 23, exactly what the entries' "command" does.
// Does not implement: comparing the frames (golden_diff.h).
#pragma once

#include <string>
#include <vector>

#include "golden/railway_frames.h"

namespace tessera::golden {

inline constexpr const char* kRttaRailwayScene = "rtta_railway";

// Throws Error naming the file when railway.glb is missing.
std::vector<RailwayFrame> rttaRailwayFrames(const std::string& railwayPath);

}  // namespace tessera::golden
