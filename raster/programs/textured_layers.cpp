// Program "textured_layers": a base texture modulated by a second texture layer (Buchholz's thesis
// §5.1.3: layers ≥ 1 of the atlas tree, e.g. a light map or glTF's occlusionTexture), as "textured"
// with one more lookup and one more factor.
// Attributes: 0 = position, 1 = (s0, t0, s1, t1): the layer-0 and the layer-1 texcoord in one vec4.
// Uniforms: slots 0-3 = MVP; slots 4, 5, 6 = the columns of layer 0's 3x3 texture matrix M0 in .xyz;
// slot 7 = RGBA tint; slot 8 = (shader LOD bias of both lookups, alpha cutoff, opaque flag, -) as in
// "textured"; slots 9, 10, 11 = the columns of layer 1's texture matrix M1; slot 12 = (strength s,
// channel mode, -, -): mode 0 takes the layer's R, G, B as the factors of R, G, B (a light map), mode 1
// takes its R for all three (glTF 2.0 occlusionTexture, whose G and B may hold other data).
// Per fragment, with t0 = texture(unit 0, M0 (s0, t0, 1)) and t1 = texture(unit 1, M1 (s1, t1, 1)):
//   f_k = (t1_k - 1) * s + 1 for k = R, G, B (glTF's mix(c, c * occlusion, strength), which for s in
//   [0, 1] and t1 in [0, 1] lies in [1 - s, 1]);
//   colour = ((t0_R * f_R) * tint_R, (t0_G * f_G) * tint_G, (t0_B * f_B) * tint_B, t0_A * tint_A);
// then the alpha test and the opaque flag of "textured" (slot 8). Layer 1's alpha is not used.
// Every step is one IEEE float operation, unfused (`precise` in the twin); the output is
// non-decreasing in every sampled channel while s, t0, t1 and the tint are >= 0 (monotoneInSamples),
// so the cross-check's interval runs bound it (docs/crosscheck.md).
#include "raster/programs/common.h"

namespace tessera::programs {
namespace {
class TexturedLayers final : public Program {
 public:
  std::string_view name() const override { return "textured_layers"; }
  int varyingCount() const override { return 4; }
  uint32_t attributesRead() const override { return 0b011u; }  // position, the two layers' texture coordinates
  bool mayDiscard(const ShadeContext& ctx) const override { return ctx.uniforms[8][1] > 0.0f; }  // cutoff
  void shadeVertices(std::span<const VertexIn> in, std::span<VertexOut> out, const ShadeContext& ctx) const override {
    const Vec4* u = ctx.uniforms;
    for (size_t i = 0; i < in.size(); ++i) {
      out[i].pos = mulMat4(u, 0, in[i].attr[0]);
      const float s0 = in[i].attr[1][0], t0 = in[i].attr[1][1];
      out[i].var[0] = (u[4][0] * s0 + u[5][0] * t0) + u[6][0];
      out[i].var[1] = (u[4][1] * s0 + u[5][1] * t0) + u[6][1];
      const float s1 = in[i].attr[1][2], t1 = in[i].attr[1][3];
      out[i].var[2] = (u[9][0] * s1 + u[10][0] * t1) + u[11][0];
      out[i].var[3] = (u[9][1] * s1 + u[10][1] * t1) + u[11][1];
    }
  }
  void shadeQuads(const QuadBatch& b, const ShadeContext& ctx) const override {
    const float* tint = ctx.uniforms[7].data();
    const float bias = ctx.uniforms[8][0], cutoff = ctx.uniforms[8][1];
    const bool opaque = ctx.uniforms[8][2] != 0.0f;
    const float strength = ctx.uniforms[12][0];
    const bool redOnly = ctx.uniforms[12][1] != 0.0f;
    for (size_t q = 0; q < b.count; ++q) {
      const Quad& quad = b.quads[q];
      float s0[4], t0[4], s1[4], t1[4], base[4][4], layer[4][4];
      for (int p = 0; p < 4; ++p) s0[p] = quad.var[p][0], t0[p] = quad.var[p][1], s1[p] = quad.var[p][2], t1[p] = quad.var[p][3];
      sampleQuad2D(ctx.units[0], s0, t0, bias, base);
      sampleQuad2D(ctx.units[1], s1, t1, bias, layer);
      for (int p = 0; p < 4; ++p) {
        float c[4];
        for (int k = 0; k < 3; ++k) {
          const float f = (layer[p][redOnly ? 0 : k] - 1.0f) * strength + 1.0f;
          c[k] = (base[p][k] * f) * tint[k];
        }
        c[3] = base[p][3] * tint[3];
        if (cutoff > 0.0f && c[3] < cutoff) b.out[q].discard |= uint8_t(1u << p);
        if (opaque) c[3] = 1.0f;
        storeColor(b.out[q], 0, p, c);
      }
    }
  }
};
}  // namespace
const Program& texturedLayers() { static const TexturedLayers p; return p; }
}  // namespace tessera::programs
