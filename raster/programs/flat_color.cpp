// Program "flat_color": one uniform colour.
// Attributes: 0 = position (xyz[w]). Uniforms: slots 0-3 = MVP (column-major), slot 4 = RGBA.
#include "raster/programs/common.h"

namespace tessera::programs {
namespace {
class FlatColor final : public Program {
 public:
  std::string_view name() const override { return "flat_color"; }
  int varyingCount() const override { return 0; }
  uint32_t attributesRead() const override { return 0b001u; }  // position
  bool mayDiscard(const ShadeContext&) const override { return false; }
  void shadeVertices(std::span<const VertexIn> in, std::span<VertexOut> out, const ShadeContext& ctx) const override {
    for (size_t i = 0; i < in.size(); ++i) out[i].pos = mulMat4(ctx.uniforms, 0, in[i].attr[0]);
  }
  void shadeQuads(const QuadBatch& b, const ShadeContext& ctx) const override {
    const float* c = ctx.uniforms[4].data();
    for (size_t q = 0; q < b.count; ++q)
      for (int p = 0; p < 4; ++p) storeColor(b.out[q], 0, p, c);
  }
};
}  // namespace
const Program& flatColor() { static const FlatColor p; return p; }
}  // namespace tessera::programs
