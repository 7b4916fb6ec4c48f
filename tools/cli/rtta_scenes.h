// The scenes `tessera rtta` renders: a model file or a built-in scene, turned into an RttaScene with
// one object per mesh or per scene-graph node instance.
#pragma once

#include <string>
#include <vector>

#include "base/resource_limits.h"
#include "rtta/rtta_scene.h"

namespace tessera::cli {

struct LoadedRttaScene {
  rtta::RttaScene scene;
};

std::vector<std::string> builtinRttaSceneNames();

// Throws Error naming the file (or scene) and the reason.
// withTab: also run TAB's Algorithm 1 (default limits) for `--texturing tab`.
LoadedRttaScene loadRttaScene(const std::string& input, const std::string& objects, const ResourceLimits& limits, bool quiet,
                              bool withTab = false);

}  // namespace tessera::cli
