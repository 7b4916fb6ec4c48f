// Program "atlas_sprite_ao": render-to-texture-atlas compositing with screen-space ambient occlusion
// and edge enhancement (Trapp & Döllner 2010, §3.2, Figure 3D) for the important objects. It is
// atlas_sprite (same attributes, units, discard and gl_FragDepth) plus a post-process on the object's
// own atlas region: the region is occlusion-free, so the filters see the object alone, and the border
// (at least kAoRadius texels) keeps them from reading a neighbour's region.
// Uniforms: slot 7 = RGBA tint; slot 8 = (occlusion bias, edge depth step, -, -) in window depth;
// slot 9 = RGBA edge colour; slots 10, 11 = the occlusion factors f[0..4] (f[k] in component k % 4 of
// slot 10 + k / 4), indexed by the number k of occluding kernel pairs.
// Per covered fragment (centre texel T at (x + dx, y + dy), depth texel (z, covered)):
// - k = #{ pairs o in kAoPairs : T + o and T - o are covered and (z_o + z_-o) - (z + z) < -bias }: the
//   centre lies behind the mean of two opposite neighbours, i.e. in a concave crease (an obscurance from
//   the depth buffer's second difference, as in unsharp masking of the depth buffer; 0 on planes);
// - edge = some 4-neighbour T + e is uncovered (a silhouette) or |z_e - z| > step (a crease);
// - colour = edge ? edge colour : (texel * tint) * (f[k], f[k], f[k], 1).
// Every operation is a texelFetch, a comparison, or one IEEE float subtraction / product (unfused,
// `precise` in the twin: GLSL 4.60 §4.7.1 makes +, -, * correctly rounded), so on the same texels GL
// computes the same floats. The result is NOT monotone in the depth texels (monotoneInSamples() is
// false): provenance gives a fragment whose kernel reads a texel that carries an interval the whole
// output range (docs/crosscheck.md, INPUT_INTERVAL), and the post-process is judged on GL's own atlas
// instead (docs/rtta.md, "ghosted-ao").
#include <cstdint>

#include "raster/programs/atlas_ao.h"
#include "raster/programs/atlas_sprite_base.h"

namespace tessera::programs {
namespace {
class AtlasSpriteAo final : public AtlasSpriteBase {
 public:
  std::string_view name() const override { return "atlas_sprite_ao"; }
  bool monotoneInSamples() const override { return false; }
  void shadeQuads(const QuadBatch& b, const ShadeContext& ctx) const override {
    const Vec4* u = ctx.uniforms;
    const float bias = u[8][0], step = u[8][1];
    for (size_t q = 0; q < b.count; ++q) {
      const Quad& quad = b.quads[q];
      int64_t x[4], y[4], l[4];
      atlasTexels(b, quad, x, y, l);
      float color[4][4], depth[4][4];
      fetchQuad2DArray(ctx.units[0], x, y, l, color);
      fetchQuad2DArray(ctx.units[1], x, y, l, depth);
      // Neighbour depths, one fetch per offset for the whole quad (the kernel, then the 4-neighbours).
      int occluders[4] = {0, 0, 0, 0};
      bool edge[4] = {false, false, false, false};
      for (const AoOffset& o : kAoPairs) {
        int64_t ax[4], ay[4], bx[4], by[4];
        for (int p = 0; p < 4; ++p) ax[p] = x[p] + o.dx, ay[p] = y[p] + o.dy, bx[p] = x[p] - o.dx, by[p] = y[p] - o.dy;
        float na[4][4], nb[4][4];
        fetchQuad2DArray(ctx.units[1], ax, ay, l, na);
        fetchQuad2DArray(ctx.units[1], bx, by, l, nb);
        for (int p = 0; p < 4; ++p) {
          const float second = (na[p][0] + nb[p][0]) - (depth[p][0] + depth[p][0]);
          occluders[p] += (na[p][1] >= 0.5f && nb[p][1] >= 0.5f && second < -bias) ? 1 : 0;
        }
      }
      for (const AoOffset& o : kEdgeNeighbours) {
        int64_t nx[4], ny[4];
        for (int p = 0; p < 4; ++p) nx[p] = x[p] + o.dx, ny[p] = y[p] + o.dy;
        float n[4][4];
        fetchQuad2DArray(ctx.units[1], nx, ny, l, n);
        for (int p = 0; p < 4; ++p) {
          const float diff = n[p][0] - depth[p][0];
          edge[p] = edge[p] || !(n[p][1] >= 0.5f) || (diff < 0.0f ? -diff : diff) > step;
        }
      }
      QuadOut& out = b.out[q];
      for (int p = 0; p < 4; ++p) {
        if (!(depth[p][1] >= 0.5f)) out.discard |= uint8_t(1u << p);  // empty atlas texel
        float c[4];
        if (edge[p]) {
          for (int k = 0; k < 4; ++k) c[k] = u[9][k];
        } else {
          const float f = u[10 + occluders[p] / 4][occluders[p] % 4];
          for (int k = 0; k < 4; ++k) c[k] = color[p][k] * u[7][k];
          for (int k = 0; k < 3; ++k) c[k] = c[k] * f;
        }
        storeColor(out, 0, p, c);
        out.depth[p] = depth[p][0];
      }
    }
  }
};
}  // namespace
const Program& atlasSpriteAo() { static const AtlasSpriteAo p; return p; }
}  // namespace tessera::programs
