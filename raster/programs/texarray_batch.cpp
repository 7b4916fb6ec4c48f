// Program "texarray_batch": texture-array batching (Trapp & Döllner 2015, Listing 1), with glTF
// materials (base-colour factor, alpha MASK / OPAQUE / BLEND) per TAM entry.
// Attributes: 0 = position, 1 = (s, t, indexTAM). Uniforms: slots 0-3 = MVP; slot 4.x = TAM layout.
// Unit 0: the texture-array mapping TAM, a buffer texture, in one of two layouts (slot 4.x):
// - 0 (any value but 1): RG32F, entry e = texel e = (arrayID, layerID); colour = the texel.
// - 1 (materials): RGBA32F, entry e = texels 2e and 2e + 1: texel 2e = (arrayID, layerID,
//   alphaCutoff, opaqueFlag), texel 2e + 1 = the base-colour factor (r, g, b, a).
//   colour = texel * factor (component-wise, float); the fragment is discarded iff alphaCutoff > 0
//   and colour.a < alphaCutoff (glTF 2.0 §3.9.4 MASK: alpha >= cutoff renders opaque; a cutoff <= 0,
//   as OPAQUE and BLEND store it, never discards, even a negative alpha);
//   then opaqueFlag != 0 forces colour.a = 1 (OPAQUE and MASK), 0 keeps it (BLEND). The same order as
//   "textured" (docs/spec-choices.md F9, F10), so both give one colour for one material.
//   Two texels per entry: a buffer of at most 2^27 texels holds at most 2^26 entries.
//   Factors must be >= 0: provenance mode bounds the output by running on the sampler's lower and
//   upper bounds, which needs a program monotone in each sampled channel.
// Units 1 .. 1 + kMaxArrays - 1: the texture arrays TA_0 .. TA_7 (sampler2DArray).
//
// Per fragment: indexTAM = int(floor(z + 0.5)) (the paper's int() truncates, but an interpolated
// constant k may arrive as k - epsilon); (arrayID, layerID) = texelFetch(TAM, indexTAM) (layout 1:
// 2 * indexTAM); colour = textureGrad(TA[arrayID], (s, t, layerID), dFdx(st), dFdy(st)). The
// derivatives are the quad's coarse differences taken before choosing the array, as the GLSL twin must
// do: GLSL forbids non-uniform sampler indexing and derivatives inside non-uniform control flow are
// undefined (GLSL 4.50 §8.9), so the twin computes dFdx/dFdy first and then switches over arrayID.
// An arrayID outside [0, kMaxArrays) or an unbound array unit gives (0, 0, 0, 1) (incomplete); in
// layout 1 that texel is multiplied and tested like any other.
#include "raster/programs/tab_lookup.h"

namespace tessera::programs {
namespace {
class TexarrayBatch final : public Program {
 public:
  std::string_view name() const override { return "texarray_batch"; }
  int varyingCount() const override { return 3; }
  uint32_t attributesRead() const override { return 0b011u; }  // position, texture coordinates and layer
  // Only the materials layout has an alpha cutoff (per TAM entry, so any draw in it may discard).
  bool mayDiscard(const ShadeContext& ctx) const override { return ctx.uniforms[4][0] == 1.0f; }
  void shadeVertices(std::span<const VertexIn> in, std::span<VertexOut> out, const ShadeContext& ctx) const override {
    for (size_t i = 0; i < in.size(); ++i) {
      out[i].pos = mulMat4(ctx.uniforms, 0, in[i].attr[0]);
      for (int k = 0; k < 3; ++k) out[i].var[k] = in[i].attr[1][k];
    }
  }
  void shadeQuads(const QuadBatch& b, const ShadeContext& ctx) const override {
    const bool materials = ctx.uniforms[4][0] == 1.0f;
    for (size_t q = 0; q < b.count; ++q) {
      float c[4][4];
      tabShadeQuad(b.quads[q], 0, materials, ctx, b.out[q], c);
      for (int p = 0; p < 4; ++p) storeColor(b.out[q], 0, p, c[p]);
    }
  }
};
}  // namespace
const Program& texarrayBatch() { static const TexarrayBatch p; return p; }
}  // namespace tessera::programs
