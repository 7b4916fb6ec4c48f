// mip_tunnel: a square tunnel seen from inside, textured with a 256x256 texture whose every mip
// level is a checkerboard with its own tint (so the level that was sampled is visible as a colour
// band). Left half: LINEAR_MIPMAP_LINEAR; right half (scissor): NEAREST_MIPMAP_NEAREST with a
// +0.5 LOD bias on the sampler.
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

void buildMipTunnel(CommandList& cl, int w, int h) {
  beginFrame(cl, w, h, true, {0, 0, 0, 1});
  static const std::array<uint8_t, 3> tints[9] = {{255, 255, 255}, {255, 64, 64}, {64, 255, 64}, {64, 64, 255},
                                                  {255, 255, 64}, {255, 64, 255}, {64, 255, 255}, {255, 160, 64},
                                                  {160, 160, 160}};
  TextureDesc d;
  d.width = d.height = 256;
  d.levels = fullMipCount(256, 256);
  const ResourceId tex = cl.createTexture(d);
  for (uint32_t l = 0; l < d.levels; ++l) {
    const uint32_t s = 256u >> l, cell = std::max(1u, 16u >> l);
    const auto& t = tints[l];
    RgbaImage img =
        checker(s, s, cell, {t[0], t[1], t[2], 255}, {uint8_t(t[0] / 3), uint8_t(t[1] / 3), uint8_t(t[2] / 3), 255});
    cl.uploadTexture(tex, l, 0, img.rgba);
  }
  Mesh m;
  const int segments = 24;
  const float len = 1.5f;
  for (int i = 0; i < segments; ++i) {
    const float z0 = -0.25f - len * float(i), z1 = z0 - len;
    const float s0 = float(i), s1 = float(i + 1);
    // floor, ceiling, left, right walls; texcoords: s along the tunnel, t across.
    m.quad({-1, -1, z0}, {1, -1, z0}, {1, -1, z1}, {-1, -1, z1}, {0, s0, 0, 0}, {1, s0, 0, 0}, {1, s1, 0, 0}, {0, s1, 0, 0});
    m.quad({1, 1, z0}, {-1, 1, z0}, {-1, 1, z1}, {1, 1, z1}, {0, s0, 0, 0}, {1, s0, 0, 0}, {1, s1, 0, 0}, {0, s1, 0, 0});
    m.quad({-1, 1, z0}, {-1, -1, z0}, {-1, -1, z1}, {-1, 1, z1}, {0, s0, 0, 0}, {1, s0, 0, 0}, {1, s1, 0, 0}, {0, s1, 0, 0});
    m.quad({1, -1, z0}, {1, 1, z0}, {1, 1, z1}, {1, -1, z1}, {0, s0, 0, 0}, {1, s0, 0, 0}, {1, s1, 0, 0}, {0, s1, 0, 0});
  }
  const uint32_t n = bindMesh(cl, m);
  cl.useProgram(cl.createProgram("textured"));
  setMatrix(cl, 0, mul(perspective(70.0, double(w) / h, 0.1, 100.0), lookAt({0.3f, 0.2f, 0}, {0, 0, -10}, {0, 1, 0})));
  setTexturedDefaults(cl);
  DepthState ds;
  ds.test = true;
  cl.setDepthState(ds);
  cl.bindTexture(0, tex);

  SamplerState tri;
  tri.minFilter = Filter::LinearMipmapLinear;
  cl.bindSampler(0, cl.createSampler(tri));
  cl.setScissor({true, {0, 0, w / 2, h}});
  cl.drawIndexed(0, n);

  SamplerState near;
  near.minFilter = Filter::NearestMipmapNearest;
  near.magFilter = Filter::Nearest;
  near.lodBias = 0.5f;
  cl.bindSampler(0, cl.createSampler(near));
  cl.setScissor({true, {w / 2, 0, w - w / 2, h}});
  cl.drawIndexed(0, n);
  cl.setScissor({});
}

}  // namespace tessera::scenes
