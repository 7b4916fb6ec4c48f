// Program "atlas_capture_tab": the render-to-texture-atlas capture pass of atlas_capture for batched
// geometry: texture-array batching's TAM lookup (texarray_batch, Trapp & Döllner 2015) instead of one
// bound texture, so one draw captures many objects with many textures (Trapp & Döllner 2010, §4).
// Attributes: 0 = position, 1 = (s, t, indexTAM) (texarray_batch's), 2 = object id (U32).
// Uniforms: slots 0-3 = MVP, slot 4.x = TAM layout (texarray_batch's: 1 = materials), slot 7 = RGBA
// tint (only .rgb is used). Units: 0 = the TAM (buffer texture, texarray_batch's layouts),
// 1..8 = the texture arrays TA0..TA7, 9 = the record buffer (RGBA32F buffer texture, atlas_displace's
// records: texels 2 id = (a, b, c, d), 2 id + 1 = (tx, ty, layer, -)). The record buffer moves to
// unit 9 so that a TAB draw's bindings (units 0-8) stay exactly as texarray_batch has them.
// Vertex and geometry stages: atlas_displace's (atlas_geometry.h) with the records on unit 9; the
// varyings pass through unchanged. Fragment: texarray_batch's lookup, material factor, alpha test
// (discard) and forced alpha (tab_lookup.h), then atlas_capture's outputs: 0 = (colour.rgb * tint.rgb,
// 1.0) (RGBA8), 1 = (gl_FragCoord.z, 1.0) (RG32F, cleared to (1, 0)).
#include "raster/programs/atlas_geometry.h"
#include "raster/programs/tab_lookup.h"

namespace tessera::programs {
namespace {
constexpr int kRecordUnit = 9;

class AtlasCaptureTab final : public Program {
 public:
  std::string_view name() const override { return "atlas_capture_tab"; }
  int varyingCount() const override { return 3; }
  uint32_t attributesRead() const override { return 0b111u; }  // position, texture coordinates and layer, object id
  int colorOutputs() const override { return 2; }
  bool hasGeometryStage() const override { return true; }
  bool readsFragDepth() const override { return true; }
  void shadeVertices(std::span<const VertexIn> in, std::span<VertexOut> out, const ShadeContext& ctx) const override {
    for (size_t i = 0; i < in.size(); ++i) {
      out[i].pos = mulMat4(ctx.uniforms, 0, in[i].attr[0]);
      for (int k = 0; k < 3; ++k) out[i].var[k] = in[i].attr[1][k];
      out[i].flat[0] = toId(in[i].attr[2][0]);
    }
  }
  bool shadeTriangle(VertexOut (&v)[3], uint32_t, uint32_t& layer, const ShadeContext& ctx) const override {
    return atlasDisplaceTriangle(v, layer, ctx.units[kRecordUnit]);
  }
  void shadeQuads(const QuadBatch& b, const ShadeContext& ctx) const override {
    const bool materials = ctx.uniforms[4][0] == 1.0f;
    const float* tint = ctx.uniforms[7].data();
    for (size_t q = 0; q < b.count; ++q) {
      float c[4][4];
      tabShadeQuad(b.quads[q], 0, materials, ctx, b.out[q], c);
      for (int p = 0; p < 4; ++p) {
        float o[4];
        for (int k = 0; k < 3; ++k) o[k] = c[p][k] * tint[k];
        o[3] = 1.0f;
        storeColor(b.out[q], 0, p, o);
        storeCaptureDepth(b.out[q], b.quads[q], p);
      }
    }
  }
};
}  // namespace
const Program& atlasCaptureTab() { static const AtlasCaptureTab p; return p; }
}  // namespace tessera::programs
