// The built-in scenes: small, deterministic frames that each exercise one rule of the oracle
// (fill rule, LOD, wraps and filters, arrays, layered targets, clip distances, blending, depth)
// plus a textured city block. Each builds a CommandList; geometry and textures are generated
// with integer/IEEE arithmetic only (no libm), so the list is the same on every machine.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "raster/command_list.h"

namespace tessera::scenes {

struct SceneInfo {
  std::string_view name;
  std::string_view rule;  // one line: what the scene checks
  int width, height;      // default size
};

const std::vector<SceneInfo>& all();
const SceneInfo* find(std::string_view name);
// Builds the scene at the given size. Throws Error for an unknown name or a size outside
// [1, 16384].
CommandList build(std::string_view name, int width, int height);

}  // namespace tessera::scenes
