// Lines 11-14 of Algorithm 1 of Trapp & Döllner 2010 (§2.2): computeTransform(B_viewport, B_atlas,
// TA, VP), the 2D map T of screen NDC onto atlas NDC, "a translation and viewport scaling".
//
// With screen viewport VP = (vx, vy, W, H), atlas viewport (0, 0, Tw, Th) and the whole-pixel shift
// s = B_atlas.origin - B_viewport.origin, a point at window x on screen must land at atlas window
// x + s_x. Solving x_atlas_ndc = 2 (x_win + s_x) / Tw - 1 with x_win = (x_ndc + 1) W / 2 + vx gives
//     a = W / Tw,  tx = (W + 2 (vx + s_x)) / Tw - 1     (and d, ty likewise; b = c = 0).
// Where float rounding remains (docs/rtta.md):
// - a and tx are stored as floats: exact when Tw, Th are powers of two (then both are dyadic with few
//   significant bits); otherwise rounded to nearest, and Transform::exact is false;
// - the program then evaluates (a x + b y) + tx w in float (each product and sum rounded), and the
//   pipeline divides by w and scales by Tw / 2 in double, so the atlas window position equals the
//   screen one plus s only up to those roundings; after snapping to 1/256 px the two agree unless the
//   exact value lies within that rounding of a snapping boundary (measured by RttaCapture tests).
// Does not implement: the sprites' geometry (composite recording), packing.
#pragma once

#include <span>

#include "raster/types.h"
#include "rtta/packing.h"
#include "rtta/record.h"

namespace tessera::rtta {

struct TransformInfo {
  Affine2 T;
  bool exact = false;  // a, d, tx, ty are the exact values (no float rounding of the coefficients)
};

TransformInfo computeTransform(const Record& r, const AtlasSize& ta, const Rect& vp);

// Sets Record::T for every record with a layer; returns how many had inexact coefficients.
size_t computeTransforms(std::span<Record> records, const AtlasSize& ta, const Rect& vp);

// T⁻¹ applied to an atlas-NDC point, in double: ((x' - tx) / a, (y' - ty) / d).
void inverseApply(const Affine2& T, double xAtlas, double yAtlas, double& xScreen, double& yScreen);

// Screen NDC of a window x / y (the inverse of GL 4.6 §13.8.1's viewport transform), in double.
inline double windowToNdc(double win, int32_t origin, int32_t size) { return 2.0 * (win - origin) / size - 1.0; }

}  // namespace tessera::rtta
