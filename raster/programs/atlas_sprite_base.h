// What the two render-to-texture-atlas compositing programs share (atlas_sprite, atlas_sprite_ao):
// the vertex stage (attribute 0 as gl_Position, attribute 2 = (dx, dy, layer) as flat integers from
// the provoking vertex), gl_FragDepth output, and the atlas texel each quad pixel reads.
// Does not implement: any fragment shading (each program's shadeQuads) or the GLSL twins, which spell
// the same stage in each file.
#pragma once

#include <cstdint>

#include "raster/programs/common.h"

namespace tessera::programs {

// A float holding an integer shift / layer: truncation toward zero inside (-2^24, 2^24), else INT32_MIN
// (an offset no texture reaches, so the fetch is empty and the fragment discarded).
inline uint32_t toShift(float f) {
  const int32_t v = (f > -16777216.0f && f < 16777216.0f) ? int32_t(f) : INT32_MIN;
  return uint32_t(v);
}

class AtlasSpriteBase : public Program {
 public:
  int varyingCount() const override { return 0; }
  uint32_t attributesRead() const override { return 0b101u; }  // position, the region's shifts
  bool writesDepth() const override { return true; }
  void shadeVertices(std::span<const VertexIn> in, std::span<VertexOut> out, const ShadeContext&) const override {
    for (size_t i = 0; i < in.size(); ++i) {
      out[i].pos = in[i].attr[0];
      for (int k = 0; k < 3; ++k) out[i].flat[k] = toShift(in[i].attr[2][k]);
    }
  }

 protected:
  // The atlas texel (x + dx, y + dy) of layer `layer` that pixel p of the quad reads (int64: a shift of
  // INT32_MIN lands outside every texture without overflow).
  static void atlasTexels(const QuadBatch& b, const Quad& quad, int64_t x[4], int64_t y[4], int64_t l[4]) {
    const int64_t dx = int32_t(b.flat[0]), dy = int32_t(b.flat[1]), layer = int32_t(b.flat[2]);
    for (int p = 0; p < 4; ++p) x[p] = quad.x + (p & 1) + dx, y[p] = quad.y + (p >> 1) + dy, l[p] = layer;
  }
};

}  // namespace tessera::programs
