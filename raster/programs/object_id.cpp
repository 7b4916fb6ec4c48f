// Program "object_id": writes the object id (attachment 0) and gl_PrimitiveID (attachment 1) to
// R32UI targets; used by the visibility cross-checks.
// Attributes: 0 = position, 2 = object id (U32). Uniforms: slots 0-3 = MVP.
#include "raster/programs/common.h"

namespace tessera::programs {
namespace {
class ObjectId final : public Program {
 public:
  std::string_view name() const override { return "object_id"; }
  int varyingCount() const override { return 0; }
  int colorOutputs() const override { return 2; }
  void shadeVertices(std::span<const VertexIn> in, std::span<VertexOut> out, const ShadeContext& ctx) const override {
    for (size_t i = 0; i < in.size(); ++i) {
      out[i].pos = mulMat4(ctx.uniforms, 0, in[i].attr[0]);
      out[i].flat[0] = toId(in[i].attr[2][0]);
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
