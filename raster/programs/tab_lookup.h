// The fragment lookup of texture-array batching (TAB, Trapp & Döllner 2015, Listing 1) with glTF
// materials, shared by "texarray_batch" and "atlas_capture_tab" so that both shade a fragment with the
// same operations in the same order. The TAM layouts, the discard rule and the derivative choice are
// documented in texarray_batch.cpp. Does not implement: vertex or geometry stages.
#pragma once

#include <cstring>

#include "raster/programs/common.h"

namespace tessera::programs {

constexpr int kTabMaxArrays = 8;

// One quad: varyings [first, first + 3) = (s, t, indexTAM); unit 0 = the TAM, units 1..8 = TA0..TA7;
// `materials` = slot 4.x == 1. Writes each pixel's colour to c and sets discard bits in o.
inline void tabShadeQuad(const Quad& quad, int first, bool materials, const ShadeContext& ctx, QuadOut& o,
                         float (&c)[4][4]) {
  constexpr int kMaxArrays = kTabMaxArrays;
  float s[4], t[4];
  for (int p = 0; p < 4; ++p) s[p] = quad.var[p][first], t[p] = quad.var[p][first + 1];
  // Coarse derivatives (GL 4.6 §8.14.1 with the quad rule of docs/spec-choices.md).
  const float dsdx = s[1] - s[0], dtdx = t[1] - t[0], dsdy = s[2] - s[0], dtdy = t[2] - t[0];
  // The entry of each pixel; a quad normally lies in one triangle, so one entry for all four.
  float tae[4][4];
  float factor[4][4];
  for (int p = 0; p < 4; ++p) {
    const int64_t e = toIndex(quad.var[p][first + 2]);
    // toIndex gives -1 or |e| < 2^62 (its limit 4.6e18), so 2e + 1 cannot overflow.
    if (materials) {
      fetchBuffer(ctx.units[0], e < 0 ? -1 : 2 * e, tae[p]);
      fetchBuffer(ctx.units[0], e < 0 ? -1 : 2 * e + 1, factor[p]);
    } else {
      fetchBuffer(ctx.units[0], e, tae[p]);
    }
  }
  const bool uniform = std::memcmp(tae[0], tae[1], sizeof tae[0]) == 0 &&
                       std::memcmp(tae[0], tae[2], sizeof tae[0]) == 0 &&
                       std::memcmp(tae[0], tae[3], sizeof tae[0]) == 0;
  for (int p = 0; p < 4; ++p) c[p][0] = 0, c[p][1] = 0, c[p][2] = 0, c[p][3] = 1;
  if (uniform) {
    const float arrayId = tae[0][0];
    if (arrayId >= 0.0f && arrayId < float(kMaxArrays)) {
      const float r[4] = {tae[0][1], tae[1][1], tae[2][1], tae[3][1]};
      sampleGrad2DArray(ctx.units[1 + int(arrayId)], s, t, r, dsdx, dtdx, dsdy, dtdy, c);
    }
  } else {
    // Pixels naming different arrays: one lookup per pixel, the same explicit derivatives.
    for (int p = 0; p < 4; ++p) {
      const float arrayId = tae[p][0];
      if (!(arrayId >= 0.0f && arrayId < float(kMaxArrays))) continue;
      const float sp[4] = {s[p], s[p], s[p], s[p]}, tp[4] = {t[p], t[p], t[p], t[p]};
      const float rp[4] = {tae[p][1], tae[p][1], tae[p][1], tae[p][1]};
      float one[4][4];
      sampleGrad2DArray(ctx.units[1 + int(arrayId)], sp, tp, rp, dsdx, dtdx, dsdy, dtdy, one);
      for (int k = 0; k < 4; ++k) c[p][k] = one[0][k];
    }
  }
  if (materials) {
    for (int p = 0; p < 4; ++p) {
      // glTF material: factor, alpha test on the factored alpha, then OPAQUE / MASK force alpha 1.
      for (int k = 0; k < 4; ++k) c[p][k] = c[p][k] * factor[p][k];
      if (tae[p][2] > 0.0f && c[p][3] < tae[p][2]) o.discard |= uint8_t(1u << p);
      if (tae[p][3] != 0.0f) c[p][3] = 1.0f;
    }
  }
}

}  // namespace tessera::programs
