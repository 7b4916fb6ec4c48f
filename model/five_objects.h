// A built-in five-object model after Fig. 1 of Trapp & Döllner 2010 (a brake assembly), the small
// scene of RTTA's Table 1 and of its `rtta_five` goldens (issue 12).
//
// Implements: fiveObjectModel(), a model::Model built in code with five objects, each one mesh, one
// material, one texture and one scene-graph object (so `--objects mesh` and `--objects node` both give
// five objects, in this order):
//   0 "disc"    a brake disc: an annulus (radius 1, hole 0.35, thickness 0.12) centred on the origin in
//               the z = 0 plane, its axis +z; kDiscSegments segments;
//   1 "pad"     a brake pad: a box in front of the disc's upper part, wider than the caliper's plate;
//   2 "caliper" a caliper of three boxes: a front plate in front of the pad, a back plate behind the
//               disc and a bridge over the disc's rim;
//   3 "screw_a", 4 "screw_b"  two hexagonal screws standing on the caliper's front plate.
// At the default camera below (square viewport) every object is in view; the caliper hides the middle
// of the pad and part of the disc, the screws hide part of the caliper, and the disc's lower part
// leaves the bottom of the screen.
// No two faces that can be seen are coplanar (gaps of 0.01 between disc, pad and front plate; the screws
// sink 0.01 into the plate; the bridge stays inside the plates' outline), so no covered pixel depends
// on a depth tie.
// Geometry: faces wind counter-clockwise seen from outside, with flat (boxes, caps, ring faces) or
// radial (disc walls) normals; ring angles use detSin / detCos, so positions are the same bits
// everywhere. Texcoords lie in [0, 1] (v = 0 is the first row, as every loader gives them).
// Textures: power-of-two RGBA8 (alpha 255) in memory (TextureRef::Source::Memory, rawRGBA), each texel a
// function of its coordinates by integer arithmetic only; loadTexture() returns them, probeTexture()
// gives format "raw". Materials are opaque, single-sided, clamp-to-edge, base colour factor 1.
// Does not implement: a file format (nothing is written or read), animation, a camera object.
#pragma once

#include <glm/vec3.hpp>

#include "model/model.h"

namespace tessera::model {

constexpr uint32_t kDiscSegments = 48;

// The suggested default camera: a look-at pinhole camera with a vertical field of view of 45 degrees
// (tan(22.5°) = √2 − 1) for a square viewport (aspect 1, so the horizontal field is also 45 degrees:
// mta::Camera's tanHalfFovX = kFiveObjectTanHalfFovY), GL clip conventions.
inline const glm::dvec3 kFiveObjectEye{1.1, 1.5, 2.6};
inline const glm::dvec3 kFiveObjectTarget{0.1, 0.55, 0.0};
inline const glm::dvec3 kFiveObjectUp{0.0, 1.0, 0.0};
constexpr double kFiveObjectFovyDegrees = 45.0;
constexpr double kFiveObjectTanHalfFovY = 0.41421356237309503;  // √2 − 1, the double nearest tan(22.5°)
constexpr double kFiveObjectNear = 0.1, kFiveObjectFar = 20.0;

// The model; source "builtin:five_objects", loader "builtin". Deterministic: two calls give equal
// geometry and the same texel bytes.
Model fiveObjectModel();

}  // namespace tessera::model
