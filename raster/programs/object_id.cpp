// Program "object_id": writes the object id (attachment 0) and gl_PrimitiveID (attachment 1) to
// R32UI targets; used by the visibility cross-checks.
// Attributes: 0 = position, 2 = object id (U32). Uniforms: slots 0-3 = MVP; slots 8-15 = user clip
// planes P_i in object space, gl_ClipDistance[i] = ((P.x*x + P.y*y) + P.z*z) + P.w*w, exactly as
// "vertex_color" (only planes enabled in RasterState::clipMask take effect; unset slots are 0). The
// planes let the visibility rewrite (verify/visibility_rewrite.h) keep a vertex_color draw's clipping.
#include "raster/programs/common.h"

namespace tessera::programs {
namespace {
class ObjectId final : public Program {
 public:
  std::string_view name() const override { return "object_id"; }
  int varyingCount() const override { return 0; }
  uint32_t attributesRead() const override { return 0b101u; }  // position, object id
  bool mayDiscard(const ShadeContext&) const override { return false; }
  int colorOutputs() const override { return 2; }
  void shadeVertices(std::span<const VertexIn> in, std::span<VertexOut> out, const ShadeContext& ctx) const override {
    for (size_t i = 0; i < in.size(); ++i) {
      out[i].pos = mulMat4(ctx.uniforms, 0, in[i].attr[0]);
      out[i].flat[0] = toId(in[i].attr[2][0]);
      const Vec4& p = in[i].attr[0];
      for (int c = 0; c < kMaxClipDistances; ++c) {
        const Vec4& pl = ctx.uniforms[8 + c];
        out[i].clip[c] = ((pl[0] * p[0] + pl[1] * p[1]) + pl[2] * p[2]) + pl[3] * p[3];
      }
    }
  }
  void shadeQuads(const QuadBatch& b, const ShadeContext&) const override {
    for (size_t q = 0; q < b.count; ++q)
      for (int p = 0; p < 4; ++p) {
        b.out[q].color[0][p].u[0] = b.flat[0];
        b.out[q].color[1][p].u[0] = b.primitiveId;
        for (int k = 1; k < 4; ++k) b.out[q].color[0][p].u[k] = b.out[q].color[1][p].u[k] = 0;
      }
  }
};
}  // namespace
const Program& objectId() { static const ObjectId p; return p; }
}  // namespace tessera::programs
