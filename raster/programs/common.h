// Helpers shared by the built-in programs. Every arithmetic order here is part of the oracle:
// the GLSL twins spell the same operations (GLSL may still reorder or fuse them; the comparator
// treats sub-ULP position differences as EDGE_TIE, docs/spec-choices.md).
#pragma once

#include "raster/program.h"

namespace tessera::programs {

// Column-major mat4 in uniform slots [base, base + 4) (slot base + c is column c), times v,
// evaluated as ((c0*x + c1*y) + c2*z) + c3*w in float per component.
inline Vec4 mulMat4(const Vec4* u, int base, const Vec4& v) {
  Vec4 r;
  for (int i = 0; i < 4; ++i) {
    float acc = u[base][i] * v[0];
    acc = acc + u[base + 1][i] * v[1];
    acc = acc + u[base + 2][i] * v[2];
    acc = acc + u[base + 3][i] * v[3];
    r[i] = acc;
  }
  return r;
}

// float -> uint32 for ids carried in float attributes / buffer texels: truncation toward zero, as the
// GLSL twins' uint(); values outside [0, 2^32) and NaN map to 0xffffffff instead of UB.
inline uint32_t toId(float f) {
  return (f >= 0.0f && f < 4294967296.0f) ? uint32_t(f) : 0xffffffffu;
}

// floor(x + 1/2) as an index for buffer fetches; NaN, infinities and |x| >= 2^62 give -1, which every
// fetch treats as out of range (never UB).
inline int64_t toIndex(float x) {
  const double v = double(x) + 0.5;
  if (!(v > -4.6e18 && v < 4.6e18)) return -1;
  int64_t i = int64_t(v);
  if (double(i) > v) --i;  // floor
  return i;
}

// Writes the same RGBA to every pixel of a quad's attachment.
inline void storeColor(QuadOut& o, int attachment, int pixel, const float c[4]) {
  for (int k = 0; k < 4; ++k) o.color[attachment][pixel].f[k] = c[k];
}

}  // namespace tessera::programs
