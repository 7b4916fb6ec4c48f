// The vertex and geometry stages shared by the render-to-texture-atlas capture programs
// ("atlas_capture", "atlas_capture_tab"): atlas_displace's stages (atlas_displace.cpp, Trapp & Döllner
// 2010, Figure 4) with the record buffer on a chosen unit, so that every capture program displaces,
// clips and layers a triangle exactly as atlas_displace does (same operations, same order).
// Does not implement: fragment stages (each program has its own).
#pragma once

#include "raster/programs/common.h"

namespace tessera::programs {

// Record of object `id` on `unit`: texels 2 id = (a, b, c, d) and 2 id + 1 = (tx, ty, layer, -).
// Geometry stage: clip distances 0-3 from the undisplaced position, x' = (a x + b y) + tx w,
// y' = (c x + d y) + ty w, layer from the provoking (last) vertex's id; false = no valid layer (drop).
inline bool atlasDisplaceTriangle(VertexOut (&v)[3], uint32_t& layer, const TexUnit& records) {
  const uint32_t id = v[2].flat[0];
  float m[4], tr[4];
  fetchBuffer(records, int64_t(id) * 2, m);
  fetchBuffer(records, int64_t(id) * 2 + 1, tr);
  if (!(tr[2] >= 0.0f && tr[2] < 65536.0f)) return false;  // no layer: drop (never UB)
  layer = uint32_t(tr[2]);
  for (VertexOut& o : v) {
    const float x = o.pos[0], y = o.pos[1], w = o.pos[3];
    o.clip[0] = w + x;
    o.clip[1] = w - x;
    o.clip[2] = w + y;
    o.clip[3] = w - y;
    o.pos[0] = (m[0] * x + m[1] * y) + tr[0] * w;
    o.pos[1] = (m[2] * x + m[3] * y) + tr[1] * w;
  }
  return true;
}

// Output 1 of the capture programs (RG32F): (gl_FragCoord.z, 1 = covered). The atlas depth target is
// cleared with (1, 0): depth at the far plane, not covered.
inline void storeCaptureDepth(QuadOut& o, const Quad& q, int pixel) {
  const float d[4] = {q.z[pixel], 1.0f, 0.0f, 1.0f};
  storeColor(o, 1, pixel, d);
}

}  // namespace tessera::programs
