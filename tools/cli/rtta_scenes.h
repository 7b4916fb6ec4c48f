// The scenes `tessera rtta` renders: a model file or a built-in scene, turned into an RttaScene with
// one object per mesh or per scene-graph node instance.
#pragma once

#include <string>
#include <vector>

#include "base/resource_limits.h"
#include "mta/camera_path.h"
#include "rtta/rtta_scene.h"

namespace tessera::cli {

struct LoadedRttaScene {
  rtta::RttaScene scene;
};

std::vector<std::string> builtinRttaSceneNames();

// The "orbit" path of the built-in scene "five": its default camera (model/five_objects.h) swung
// about the vertical axis through the target, from -45 to +45 degrees, so every frame shows the
// assembly as the paper's Fig. 1 does (the generic orbit over the scene's bounds starts inside it).
// frames = 0: 24. The horizontal field of view is the model's vertical one times width / height.
mta::CameraPath fiveOrbit(uint32_t frames, int width, int height);

// Throws Error naming the file (or scene) and the reason.
// withTab: also run TAB's Algorithm 1 (default limits) for `--texturing tab`.
LoadedRttaScene loadRttaScene(const std::string& input, const std::string& objects, const ResourceLimits& limits, bool quiet,
                              bool withTab = false);

}  // namespace tessera::cli
