// Program "textured": texture(unit 0, M * (s, t, 1)) * tint.
// Attributes: 0 = position, 1 = texcoord (s, t). Uniforms: slots 0-3 = MVP; slots 4, 5, 6 = the
// columns of the 3x3 texture matrix M in .xyz (applied per vertex: M is affine, so applying it per
// vertex and interpolating equals applying it per fragment); slot 7 = RGBA tint; slot 8.x = shader
// LOD bias (texture(s, c, bias)); slot 8.y = alpha cutoff: the fragment is discarded iff cutoff > 0
// and (texel * tint).a < cutoff (glTF 2.0 §3.9.4 MASK; 0, the default, never discards); slot 8.z =
// opaque flag: != 0 forces the output alpha to 1 after the test (glTF OPAQUE and MASK). The order
// (multiply, test, force) is texarray_batch's materials layout, so a material gives one colour in the
// baseline and the batched frame (docs/spec-choices.md F9, F10). With REPEAT addressing M
// realises the 2^k atlas scaling of the texture atlas tree (Buchholz 2005 §4.5.4).
#include <algorithm>

#include "raster/programs/common.h"

namespace tessera::programs {
namespace {
class Textured final : public Program {
 public:
  std::string_view name() const override { return "textured"; }
  int varyingCount() const override { return 2; }
  uint32_t attributesRead() const override { return 0b011u; }  // position, texture coordinates
  bool mayDiscard(const ShadeContext& ctx) const override { return ctx.uniforms[8][1] > 0.0f; }  // cutoff
  void shadeVertices(std::span<const VertexIn> in, std::span<VertexOut> out, const ShadeContext& ctx) const override {
    const Vec4* u = ctx.uniforms;
    for (size_t i = 0; i < in.size(); ++i) {
      out[i].pos = mulMat4(u, 0, in[i].attr[0]);
      const float s = in[i].attr[1][0], t = in[i].attr[1][1];
      out[i].var[0] = (u[4][0] * s + u[5][0] * t) + u[6][0];
      out[i].var[1] = (u[4][1] * s + u[5][1] * t) + u[6][1];
    }
  }
  void shadeQuads(const QuadBatch& b, const ShadeContext& ctx) const override {
    const float* tint = ctx.uniforms[7].data();
    const float bias = ctx.uniforms[8][0], cutoff = ctx.uniforms[8][1];
    const bool opaque = ctx.uniforms[8][2] != 0.0f;
    // The lookups of up to kChunk quads in one call: quads that share a lambda fill the sampler's wide
    // vectors (the rasterizer's batches are 64 quads).
    constexpr size_t kChunk = 64;
    float s[kChunk][4], t[kChunk][4], texel[kChunk][4][4];
    for (size_t q = 0; q < b.count; ++q) {
      const size_t k = q % kChunk;
      if (k == 0) {
        const size_t n = std::min(kChunk, b.count - q);
        for (size_t i = 0; i < n; ++i)
          for (int p = 0; p < 4; ++p) s[i][p] = b.quads[q + i].var[p][0], t[i][p] = b.quads[q + i].var[p][1];
        sampleQuads2D(ctx.units[0], n, s, t, bias, texel);
      }
      for (int p = 0; p < 4; ++p) {
        float c[4];
        for (int ch = 0; ch < 4; ++ch) c[ch] = texel[k][p][ch] * tint[ch];
        if (cutoff > 0.0f && c[3] < cutoff) b.out[q].discard |= uint8_t(1u << p);
        if (opaque) c[3] = 1.0f;
        storeColor(b.out[q], 0, p, c);
      }
    }
  }
};
}  // namespace
const Program& textured() { static const Textured p; return p; }
}  // namespace tessera::programs
