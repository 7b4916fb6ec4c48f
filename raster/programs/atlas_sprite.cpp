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

#include "raster/programs/atlas_sprite_base.h"

namespace tessera::programs {
namespace {
class AtlasSprite final : public AtlasSpriteBase {
 public:
  std::string_view name() const override { return "atlas_sprite"; }
  void shadeQuads(const QuadBatch& b, const ShadeContext& ctx) const override {
    const float* tint = ctx.uniforms[7].data();
    for (size_t q = 0; q < b.count; ++q) {
      const Quad& quad = b.quads[q];
      int64_t x[4], y[4], l[4];
      atlasTexels(b, quad, x, y, l);
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
