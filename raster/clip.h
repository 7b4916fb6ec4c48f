// Primitive clipping in double precision (GL 4.6 §13.5 and §13.7).
//
// Implements: Sutherland–Hodgman clipping of one triangle against near (z >= -w), far (z <= w),
// the x/y guard band (|x|, |y| <= kGuardBand * w, limits.h) and the enabled user clip distances
// (gl_ClipDistance[i] >= 0). New vertices interpolate position, clip distances and smooth varyings
// linearly in clip space with t = d0 / (d0 - d1); the output polygon is triangulated as a fan from
// its first vertex. Flat varyings are not touched (they stay those of the provoking vertex).
// Does not implement: culling, perspective division, snapping (setup.cpp).
#pragma once

#include <cstdint>

#include "raster/limits.h"
#include "raster/program.h"

namespace tessera::detail {

struct ClipVertex {
  double pos[4];
  double clip[kMaxClipDistances];
  double var[kMaxVaryings];
};

// Up to 3 + number of planes vertices; 6 fixed planes + 8 user planes.
constexpr int kMaxClipPolygon = 3 + 6 + kMaxClipDistances;

enum class ClipResult { Inside, Outside, Clipped };

// Classifies the triangle. Inside: no plane cuts it (use the original vertices unchanged).
// Outside: all three vertices lie strictly outside one plane. Otherwise Clipped.
// The vertices are read in place (setup passes pointers into the vertex stage's output). A vertex
// with a NaN or infinite position coordinate makes the triangle Outside. The six fixed planes are
// tested in SSE2 pairs where available, the scalar steps under the "reference" SIMD target (the same
// results: tests/raster/test_classify.cpp).
ClipResult classifyTriangle(const VertexOut* const (&v)[3], uint8_t clipMask);
inline ClipResult classifyTriangle(const VertexOut (&v)[3], uint8_t clipMask) {
  const VertexOut* const p[3] = {&v[0], &v[1], &v[2]};
  return classifyTriangle(p, clipMask);
}

// Clips the triangle; returns the number of polygon vertices written to `out` (0 if nothing is
// left, otherwise >= 3).
int clipTriangle(const VertexOut (&v)[3], uint8_t clipMask, int varyings, ClipVertex (&out)[kMaxClipPolygon]);

}  // namespace tessera::detail
