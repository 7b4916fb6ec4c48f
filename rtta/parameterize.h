// Lines 1-9 of Algorithm 1 of Trapp & Döllner 2010 (§2.2): per object, conservative view-frustum
// culling of B_world, projection, clipping to [-1, 1]², scaling to the viewport with outward rounding
// to whole pixels, and addBorder(b). Packing (lines 10) is packing.h, the transforms (11-14) transform.h.
//
// Choices the paper leaves open (docs/rtta.md lists them with their reasons):
// - Culling is conservative against the float evaluation the pipeline does: an object is culled only
//   when all 8 corners of B_world lie outside one clip plane (GL 4.6 §13.7: -w <= x, y, z <= w) by more
//   than the rounding error bound of the program's float transform (kTransformGamma below). A box that
//   is culled can therefore never put a fragment on screen.
// - A box that crosses the near plane (z + w = 0; the paper does not cover w <= 0) is clipped there:
//   the projected bound is the bound of the projections of the corners in front of the plane and of
//   the points where the box's 12 edges cross it. This is exact for the clipped box (a convex
//   polyhedron; projection maps its vertices to the vertices' hull's bound). Only when a kept point
//   still has w <= 0 (a projection that is not a GL perspective or orthographic one) does the record
//   fall back to the whole viewport (Record::wholeViewport).
// - Outward rounding covers the pipeline's own error: the bound is widened by the float error bound
//   of the vertex transform (in pixels) plus half a sub-pixel (the rasterizer snaps vertices to
//   1/2^kSubpixelBits px, raster/limits.h) before rounding to whole pixels, so every pixel centre the
//   object can cover lies inside B_viewport (RttaParameterization tests).
// - The border (b pixels on every side) is added after clipping to the viewport, so it may lie outside
//   the screen; those texels are never covered, and keep the atlas's reserved clear alpha.
// - The bordered region is then widened to even pixel coordinates (at most one more pixel per side), so
//   that with even atlas positions (packing.h) the shift s = B_atlas - B_viewport is even in x and y.
//   Implicit derivatives come from 2x2 quads aligned to even window coordinates (GL 4.6 §15.2.1: "the
//   derivatives ... are computed over 2x2 quads" in llvmpipe and the oracle alike); an odd shift would
//   pair every pixel with a different neighbour and change the LOD, and so the texels, of the capture.
// Does not implement: packing, transforms, the record buffer.
#pragma once

#include <glm/common.hpp>
#include <glm/mat4x4.hpp>
#include <span>
#include <vector>

#include "raster/types.h"
#include "rtta/record.h"

namespace tessera::rtta {

struct ParamOptions {
  int32_t border = 1;  // b >= 0
  bool cull = true;    // false: no frustum culling (the paper's Table 1 runs); off-screen boxes still get no region
};

// Relative error bound of the programs' mulMat4 (4 products summed left to right in float, GLSL
// `precise`): |fl(Σ m v) - Σ m v| <= γ_4 Σ |m| |v|, γ_4 = 4u / (1 - 4u), u = 2^-24 (Higham, Accuracy and
// Stability of Numerical Algorithms, §3.1). Rounded up.
inline constexpr double kTransformGamma = 4.0 * 0x1p-24 / (1.0 - 4.0 * 0x1p-24) * (1.0 + 0x1p-20);

// World AABB of `positions` (exact: float coordinates in double).
template <class Vec3s>
Box3 boundsOf(const Vec3s& positions) {
  Box3 b;
  bool first = true;
  for (const auto& p : positions) {
    const glm::dvec3 q(p.x, p.y, p.z);
    if (first) b.lo = b.hi = q, first = false;
    b.lo = glm::min(b.lo, q);
    b.hi = glm::max(b.hi, q);
  }
  return b;
}

// inner expanded by `border` on every side, then to even coordinates (floor / ceil to a multiple of 2).
PixelRect borderedRegion(const PixelRect& inner, int32_t border);

// Records for objects 0..n-1 with their B_world boxes, seen through the float matrix `vpm` (the one
// the frame's programs use) in viewport `vp`. Fills id, world, culled, nearClipped, wholeViewport,
// inner and viewport; layer stays -1 and atlas / T empty until packing. Throws Error on a bad option.
std::vector<Record> parameterize(std::span<const Box3> objects, const glm::mat4& vpm, const Rect& vp,
                                 const ParamOptions& options);

}  // namespace tessera::rtta
