// Construction of the tree structure (thesis §4.5.1-4.5.4, §4.8.1): recursive node splitting until
// each node's textures fit one A x A atlas, then contiguous triangle ranges, root-atlas texture
// coordinates and texture matrices.
//
// Implements: the topology and the leaf atlas layouts; needs image sizes only (no texels).
// Does not implement: atlas texels (atlas_image.h) or the file (paging_file.h).
#pragma once

#include <cstdint>
#include <span>

#include "mta/params.h"
#include "mta/scene.h"
#include "mta/tree.h"

namespace tessera::mta {

// Builds the tree for the triangles `tris` of `g` (all of one alpha class). Children are built in
// parallel (TBB); the result depends only on the inputs. minDistance of leaves = dMin; of inner nodes
// 2 · max over children of (child minDistance, and for a leaf child dMin · its cap factor).
// Precondition: no triangle in `tris` is critical at dMin (critical.h), else Error.
Tree buildTree(const Scene& s, const Geometry& g, std::span<const uint32_t> tris, uint8_t alpha, const BuildParams& p,
               double dMin);

// The leaf layout for `tris` if it fits one atlas: entries in texture order, coverage, and the cap factor:
// max over its textures of need / image size (>= 1), how much the cap at the image's own size (mta-build.md
// step 3) leaves the leaf short of τ at d_min. Exposed for tests.
bool layoutAtlas(const Scene& s, const Geometry& g, std::span<const uint32_t> tris, const std::vector<TexelSize>& sizes,
                 const BuildParams& p, std::vector<AtlasEntry>& entries, double& coverage,
                 double* capFactor = nullptr);

}  // namespace tessera::mta
