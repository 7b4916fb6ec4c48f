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

// The planes a vertex lies outside of, one bit each: 0 near (z >= -w), 1 far (z <= w), 2-5 the guard
// band's x >= -g w, x <= g w, y >= -g w, y <= g w, 6 + i user clip distance i (enabled ones only).
// "Outside" is !(d >= 0), so a NaN distance is outside.
constexpr int kClipFixedPlanes = 6;
constexpr uint32_t kClipFixedPlaneBits = (1u << kClipFixedPlanes) - 1;
constexpr uint32_t kClipPlaneBits = (1u << (kClipFixedPlanes + kMaxClipDistances)) - 1;
// Alone, instead of plane bits: a NaN or infinite position coordinate (only program arithmetic makes
// one; validation rejects non-finite input positions). GL leaves the primitive undefined; the oracle
// discards it.
constexpr uint32_t kClipNonFinite = 1u << 31;

// The outcode of one vertex for the user clip distances in clipMask: the six fixed planes in SSE2
// pairs where available, the scalar steps under the "reference" SIMD target (the same bits).
uint32_t classifyVertex(const VertexOut& v, uint8_t clipMask);

// A triangle from its vertices' outcodes: Outside if one is kClipNonFinite or all three lie outside
// one plane, Inside if none lies outside any, Clipped otherwise.
inline ClipResult classifyCodes(uint32_t c0, uint32_t c1, uint32_t c2) {
  if (((c0 | c1 | c2) & kClipNonFinite) || (c0 & c1 & c2 & kClipPlaneBits)) return ClipResult::Outside;
  return ((c0 | c1 | c2) & kClipPlaneBits) ? ClipResult::Clipped : ClipResult::Inside;
}

// Classifies the triangle. Inside: no plane cuts it (use the original vertices unchanged).
// Outside: all three vertices lie strictly outside one plane. Otherwise Clipped.
// A vertex with a NaN or infinite position coordinate makes the triangle Outside. classifyCodes of
// the three classifyVertex codes (tests/raster/test_classify.cpp compares the SSE2 and the scalar
// steps). Setup classifies from the codes the vertex stage recorded (window_simd.h) instead.
ClipResult classifyTriangle(const VertexOut* const (&v)[3], uint8_t clipMask);
inline ClipResult classifyTriangle(const VertexOut (&v)[3], uint8_t clipMask) {
  const VertexOut* const p[3] = {&v[0], &v[1], &v[2]};
  return classifyTriangle(p, clipMask);
}

// Clips the triangle; returns the number of polygon vertices written to `out` (0 if nothing is
// left, otherwise >= 3).
int clipTriangle(const VertexOut (&v)[3], uint8_t clipMask, int varyings, ClipVertex (&out)[kMaxClipPolygon]);

}  // namespace tessera::detail
