// Program "atlas_sprite": render-to-texture-atlas compositing (Trapp & Döllner 2010, §3.2, Figure 3):
// one sprite per object shows its atlas region at its screen position, texel for pixel.
// Attributes: 0 = position in clip space (used as gl_Position unchanged; the caller builds two
// triangles per object, w = 1); 2 = (dx, dy, layer, -): floats holding integers, taken from the
// provoking (last) vertex as flat varyings (truncated toward zero like GLSL's int(); |v| >= 2^24 or
// NaN selects no texel). Uniforms: slot 7 = RGBA tint. Unit 0: the atlas colour (RGBA8 2D array),
// unit 1: the atlas depth (RG32F 2D array, atlas_capture's output 1: (window depth, covered)).
// Per fragment at integer window position (x, y): texel (x + dx, y + dy) of layer `layer`, level 0,
// fetched exactly (texelFetch) from both units (outside the texture: (0, 0, 0, 0), i.e. empty). The
// fragment is discarded unless depth.y >= 0.5 (covered; NaN discards); otherwise colour = texel * tint
// (float, component-wise, unfused) and gl_FragDepth = depth.x, clamped to [0, 1] (spec-choices F11).
// With the depth test on, sprites reproduce the depth-tested rendering; with it off and blending, the
// tint's alpha makes them translucent.
#include <cstdint>

#include "raster/programs/common.h"

namespace tessera::programs {
namespace {
// A float holding an integer shift / layer: truncation toward zero inside (-2^24, 2^24), else INT32_MIN
// (an offset no texture reaches, so the fetch is empty and the fragment discarded).
inline uint32_t toShift(float f) {
  const int32_t v = (f > -16777216.0f && f < 16777216.0f) ? int32_t(f) : INT32_MIN;
  return uint32_t(v);
}

class AtlasSprite final : public Program {
 public:
  std::string_view name() const override { return "atlas_sprite"; }
  int varyingCount() const override { return 0; }
  bool writesDepth() const override { return true; }
  void shadeVertices(std::span<const VertexIn> in, std::span<VertexOut> out, const ShadeContext&) const override {
    for (size_t i = 0; i < in.size(); ++i) {
      out[i].pos = in[i].attr[0];
      for (int k = 0; k < 3; ++k) out[i].flat[k] = toShift(in[i].attr[2][k]);
    }
  }
  void shadeQuads(const QuadBatch& b, const ShadeContext& ctx) const override {
    const float* tint = ctx.uniforms[7].data();
    const int64_t dx = int32_t(b.flat[0]), dy = int32_t(b.flat[1]), layer = int32_t(b.flat[2]);
    for (size_t q = 0; q < b.count; ++q) {
      const Quad& quad = b.quads[q];
      int64_t x[4], y[4], l[4];
      for (int p = 0; p < 4; ++p) x[p] = quad.x + (p & 1) + dx, y[p] = quad.y + (p >> 1) + dy, l[p] = layer;
      float color[4][4], depth[4][4];
      fetchQuad2DArray(ctx.units[0], x, y, l, color);
      fetchQuad2DArray(ctx.units[1], x, y, l, depth);
      QuadOut& o = b.out[q];
      for (int p = 0; p < 4; ++p) {
        if (!(depth[p][1] >= 0.5f)) o.discard |= uint8_t(1u << p);  // empty atlas texel
        float c[4];
        for (int k = 0; k < 4; ++k) c[k] = color[p][k] * tint[k];
        storeColor(o, 0, p, c);
        o.depth[p] = depth[p][0];
      }
    }
  }
};
}  // namespace
const Program& atlasSprite() { static const AtlasSprite p; return p; }
}  // namespace tessera::programs
