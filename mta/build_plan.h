// The plan of an atlas tree build: everything the build decides before it writes a byte.
//
// Implements: parameter and scene validation, d_min (absolute, or D / divisor), critical-triangle
// handling, the RGB and the RGBA tree (topology, leaf layouts, ranges), each leaf's original images and
// each image's stored channel count. Needs image headers only, never texels, so a plan is cheap next to
// the build it describes: `mta build` plans first, estimates the file from the plan (output_size.h),
// refuses a run-away build before the output exists, and --fit plans repeatedly (output_budget.h).
// Does not implement: atlas texels, the paging file (build.h writes a plan), the size estimate.
#pragma once

#include <cstdint>
#include <functional>

#include "mta/paging_file.h"
#include "mta/params.h"
#include "mta/scene.h"

namespace tessera::mta {

struct BuildPlan {
  // trees, textures, images (size, channels, name), stats and params; blocks and pieces stay empty until
  // the build writes them.
  MtaMeta meta;
  uint64_t nodes = 0, leaves = 0;  // over both trees
};

// The bounding-box diagonal D of the scene's positions (0 for an empty scene).
double sceneDiagonal(const Scene& scene);
// d_min as the build resolves it: params.dMin when > 0, else D / params.dMinDivisor.
double resolveDMin(const Scene& scene, const BuildParams& params);

// Throws Error for invalid parameters, an invalid or empty scene, a zero-size scene without --d-min, and
// what critical-triangle handling or the tree construction refuse. `checkpoint(where)` (optional) runs
// after critical-triangle handling and after the trees are built (the build checks its memory there).
// Deterministic: the plan depends only on the scene and the parameters (not on threads).
BuildPlan planBuild(const Scene& scene, const BuildParams& params,
                    const std::function<void(const char* where)>& checkpoint = {});

}  // namespace tessera::mta
