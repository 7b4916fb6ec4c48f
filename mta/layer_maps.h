// Whether layers >= 1 can share layer 0's atlas areas (thesis §5.1.3), checked before anything is written.
//
// The build fills the layer-i atlas of a leaf per layer-0 area (one area per layer-0 texture): through the
// affine map m of one reference triangle, the first of the area's triangles (range order) with a layer-i
// texture and a non-degenerate atlas triangle (mta/build.cpp renderLeaf). The thesis fills per triangle
// and so needs layer 0 to be injective: two triangles sharing atlas texels with different layer-i content
// would overwrite each other. Filling per area needs more than that and makes injectivity beside the
// point: every triangle of the area gets m's texels whether or not its texels overlap another's, so it is
// drawn right exactly when it maps layer i as the reference does. That is what this checks, for every
// triangle of every area: a layer-i texture exactly when the reference has one, of the same image and
// wrap modes, and its layer-i texcoords at each vertex equal to m at the vertex's atlas position, within 1/256
// texel of the layer-i image (fillArea's bilinear weights are 8-bit: maps that differ by less put the same
// taps and weights up to one weight step), modulo the wrap period (1 for REPEAT, 2 for MIRRORED_REPEAT,
// none for CLAMP_TO_EDGE: the sampled texels are the same). The thesis's own case, a computed layer 0 with
// a texture per triangle, has one triangle per area and always passes; so does a model whose layers use
// one texcoord set and, per base texture, one layer-i texture (`tessera city --light-map`).
// Does not implement: filling (build.cpp), a per-triangle fill that would accept more models.
#pragma once

#include <cstdint>

#include "mta/scene.h"
#include "mta/tree.h"

namespace tessera::mta {

// Throws Error naming the scene, the layer, the two input triangles (Scene::describeTriangle: mesh and
// triangle for a model) and how they differ, for the first triangle of `tree` (leaves in order, areas in
// texture order, triangles in range order) that maps a layer differently from its area's reference.
// Precondition: `tree` was built from `scene` (buildTree), its leaves still hold their entries.
void checkLayerMaps(const Scene& scene, const Tree& tree);

}  // namespace tessera::mta
