// Program "atlas_displace": render-to-texture-atlas by screen-space vertex displacement
// (Trapp & Döllner 2010, §2.3 and Figure 4).
// Attributes: 0 = position, 1 = texcoord (s, t), 2 = object id (U32). Uniforms: slots 0-3 = MVP,
// slot 7 = RGBA tint. Unit 0: the record buffer (RGBA32F buffer texture), two texels per object:
// record[2 id] = (a, b, c, d), the 2x2 linear part of T in NDC; record[2 id + 1] = (tx, ty, layer, -).
// Unit 1: the object's texture (sampled like "textured", no texture matrix).
//
// Geometry stage per triangle: clip distances 0-3 = the four side planes of the *undisplaced* clip
// position (w + x, w - x, w + y, w - y), so clipping keeps exactly the on-screen part; the position
// becomes x' = a x + b y + tx w, y' = c x + d y + ty w (z, w unchanged). This equals the paper's
// (T (v / w)) w without the per-vertex division; the GLSL twin spells the same expression.
// gl_Layer = the record's layer, read from the provoking (last) vertex's object id.
#include <cmath>

#include "raster/programs/common.h"

namespace tessera::programs {
namespace {
class AtlasDisplace final : public Program {
 public:
  std::string_view name() const override { return "atlas_displace"; }
  int varyingCount() const override { return 2; }
  uint32_t attributesRead() const override { return 0b111u; }  // position, texture coordinates, object id
  bool hasGeometryStage() const override { return true; }
  void shadeVertices(std::span<const VertexIn> in, std::span<VertexOut> out, const ShadeContext& ctx) const override {
    for (size_t i = 0; i < in.size(); ++i) {
      out[i].pos = mulMat4(ctx.uniforms, 0, in[i].attr[0]);
      out[i].var[0] = in[i].attr[1][0];
      out[i].var[1] = in[i].attr[1][1];
      out[i].flat[0] = toId(in[i].attr[2][0]);
    }
  }
  bool shadeTriangle(VertexOut (&v)[3], uint32_t, uint32_t& layer, const ShadeContext& ctx) const override {
    const uint32_t id = v[2].flat[0];
    float m[4], tr[4];
    fetchBuffer(ctx.units[0], int64_t(id) * 2, m);
    fetchBuffer(ctx.units[0], int64_t(id) * 2 + 1, tr);
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
  void shadeQuads(const QuadBatch& b, const ShadeContext& ctx) const override {
    const float* tint = ctx.uniforms[7].data();
    for (size_t q = 0; q < b.count; ++q) {
      const Quad& quad = b.quads[q];
      float s[4], t[4], texel[4][4];
      for (int p = 0; p < 4; ++p) s[p] = quad.var[p][0], t[p] = quad.var[p][1];
      sampleQuad2D(ctx.units[1], s, t, 0.0f, texel);
      for (int p = 0; p < 4; ++p) {
        float c[4];
        for (int k = 0; k < 4; ++k) c[k] = texel[p][k] * tint[k];
        storeColor(b.out[q], 0, p, c);
      }
    }
  }
};
}  // namespace
const Program& atlasDisplace() { static const AtlasDisplace p; return p; }
}  // namespace tessera::programs
