// lod_levels: screen-aligned quads of constant lambda over a 64x64 texture whose every mip level is
// one flat tint. s is affine in x and t is constant, so du/dy = dv/dx = dv/dy = 0 and every rho GL
// 4.6 §8.14.1 allows (the exact one, and any f with max(mu, mv) <= f <= mu + mv) is the same number
// |du/dx|, with coarse or fine derivatives alike: lambda is known to the precision of log2 alone.
// (With t affine in y too, mu + mv would allow lambda up to 1 higher.) Columns: lambda = 0.25, 0.75, 1.3, 1.7 (none
// within 1/8 of a switch point: 0, an integer, or k + 1/2). Bottom row LINEAR_MIPMAP_LINEAR (LINEAR mag), top row
// NEAREST_MIPMAP_NEAREST (NEAREST mag).
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

void buildLodLevels(CommandList& cl, int w, int h) {
  beginFrame(cl, w, h, false, {0, 0, 0, 1});
  static const std::array<uint8_t, 3> tints[7] = {{255, 255, 255}, {255, 40, 40},  {40, 255, 40}, {40, 40, 255},
                                                  {255, 255, 40},  {255, 40, 255}, {40, 255, 255}};
  TextureDesc d;
  d.width = d.height = 64;
  d.levels = fullMipCount(64, 64);
  const ResourceId tex = cl.createTexture(d);
  for (uint32_t l = 0; l < d.levels; ++l) {
    const uint32_t s = 64u >> l;
    const std::array<uint8_t, 4> c = {tints[l][0], tints[l][1], tints[l][2], 255};
    cl.uploadTexture(tex, l, 0, checker(s, s, s, c, c).rgba);
  }
  // Quads of 24 x 24 px in cells of 32 x 32 px (ortho in pixels): rho = 64 range / 24 texels per
  // pixel for s = 0 .. range, so range = 2^lambda * 24 / 64 (2^0.25 etc. as decimal constants); t = 1/2.
  const float lambdas2[4] = {1.189207115f, 1.681792831f, 2.462288827f, 3.249009585f};  // 2^0.25, 2^0.75, 2^1.3, 2^1.7
  Mesh m;
  for (int row = 0; row < 2; ++row)
    for (int col = 0; col < 4; ++col) {
      const float x0 = float(col * 32 + 4), y0 = float(row * 32 + 4), r = lambdas2[col] * 24.0f / 64.0f;
      m.quad({x0, y0, 0}, {x0 + 24, y0, 0}, {x0 + 24, y0 + 24, 0}, {x0, y0 + 24, 0}, {0, 0.5f, 0, 0}, {r, 0.5f, 0, 0},
             {r, 0.5f, 0, 0}, {0, 0.5f, 0, 0});
    }
  bindMesh(cl, m);
  cl.useProgram(cl.createProgram("textured"));
  setMatrix(cl, 0, ortho(0, w, 0, h, -1, 1));
  setTexturedDefaults(cl);
  cl.bindTexture(0, tex);
  SamplerState tri;
  tri.minFilter = Filter::LinearMipmapLinear;
  cl.bindSampler(0, cl.createSampler(tri));
  cl.drawIndexed(0, 24);
  SamplerState near;
  near.minFilter = Filter::NearestMipmapNearest;
  near.magFilter = Filter::Nearest;
  cl.bindSampler(0, cl.createSampler(near));
  cl.drawIndexed(24, 24);
}

}  // namespace tessera::scenes
