// Program "vertex_color": perspective-correct interpolated per-vertex colour.
// Attributes: 0 = position, 1 = RGBA. Uniforms: slots 0-3 = MVP; slots 8-15 = user clip planes
// P_i in object space: gl_ClipDistance[i] = P_i.x * x + P_i.y * y + P_i.z * z + P_i.w (only the
// planes enabled in RasterState::clipMask take effect).
#include "raster/programs/common.h"

namespace tessera::programs {
namespace {
class VertexColor final : public Program {
 public:
  std::string_view name() const override { return "vertex_color"; }
  int varyingCount() const override { return 4; }
  uint32_t attributesRead() const override { return 0b011u; }  // position, colour
  bool mayDiscard(const ShadeContext&) const override { return false; }
  void shadeVertices(std::span<const VertexIn> in, std::span<VertexOut> out, const ShadeContext& ctx) const override {
    for (size_t i = 0; i < in.size(); ++i) {
      out[i].pos = mulMat4(ctx.uniforms, 0, in[i].attr[0]);
      for (int k = 0; k < 4; ++k) out[i].var[k] = in[i].attr[1][k];
      const Vec4& p = in[i].attr[0];
      for (int c = 0; c < kMaxClipDistances; ++c) {
        const Vec4& pl = ctx.uniforms[8 + c];
        out[i].clip[c] = ((pl[0] * p[0] + pl[1] * p[1]) + pl[2] * p[2]) + pl[3] * p[3];
      }
    }
  }
  void shadeQuads(const QuadBatch& b, const ShadeContext&) const override {
    for (size_t q = 0; q < b.count; ++q)
      for (int p = 0; p < 4; ++p) storeColor(b.out[q], 0, p, b.quads[q].var[p]);
  }
};
}  // namespace
const Program& vertexColor() { static const VertexColor p; return p; }
}  // namespace tessera::programs
