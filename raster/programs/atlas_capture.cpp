// Program "atlas_capture": render-to-texture-atlas capture pass (Trapp & Döllner 2010, §2.3, §3.1)
// with the window depth kept for compositing.
// Attributes: 0 = position, 1 = texcoord (s, t), 2 = object id (U32). Uniforms: slots 0-3 = MVP,
// slot 7 = RGBA tint. Unit 0: the record buffer (RGBA32F buffer texture), two texels per object:
// record[2 id] = (a, b, c, d), record[2 id + 1] = (tx, ty, layer, -). Unit 1: the object's texture
// (sampled like atlas_displace). All of this is atlas_displace's layout.
// Vertex and geometry stages: atlas_displace's, unchanged (atlas_geometry.h).
// Outputs (a layered target: colour 0 RGBA8 array, colour 1 RG32F array, depth D32F array, the same
// size and layer count):
// - 0: texel * tint (float, component-wise, unfused), then alpha = 1.0: the atlas is cleared with
//   alpha 0, the reserved empty / border value, so every object texel is told apart from it;
// - 1: (gl_FragCoord.z, 1.0): the window depth the depth test compared, and "covered". Clear it with
//   (1, 0): far plane, empty (atlas_sprite discards where .y < 0.5).
#include "raster/programs/atlas_geometry.h"

namespace tessera::programs {
namespace {
class AtlasCapture final : public Program {
 public:
  std::string_view name() const override { return "atlas_capture"; }
  int varyingCount() const override { return 2; }
  uint32_t attributesRead() const override { return 0b111u; }  // position, texture coordinates, object id
  int colorOutputs() const override { return 2; }
  bool hasGeometryStage() const override { return true; }
  bool readsFragDepth() const override { return true; }
  void shadeVertices(std::span<const VertexIn> in, std::span<VertexOut> out, const ShadeContext& ctx) const override {
    for (size_t i = 0; i < in.size(); ++i) {
      out[i].pos = mulMat4(ctx.uniforms, 0, in[i].attr[0]);
      out[i].var[0] = in[i].attr[1][0];
      out[i].var[1] = in[i].attr[1][1];
      out[i].flat[0] = toId(in[i].attr[2][0]);
    }
  }
  bool shadeTriangle(VertexOut (&v)[3], uint32_t, uint32_t& layer, const ShadeContext& ctx) const override {
    return atlasDisplaceTriangle(v, layer, ctx.units[0]);
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
        for (int k = 0; k < 3; ++k) c[k] = texel[p][k] * tint[k];
        c[3] = 1.0f;
        storeColor(b.out[q], 0, p, c);
        storeCaptureDepth(b.out[q], quad, p);
      }
    }
  }
};
}  // namespace
const Program& atlasCapture() { static const AtlasCapture p; return p; }
}  // namespace tessera::programs
