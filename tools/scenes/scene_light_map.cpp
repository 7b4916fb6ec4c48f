// light_map: a second texture layer multiplied in (program textured_layers; Buchholz's thesis §5.1.3,
// layers >= 1 of the atlas tree). A floor and a back wall in perspective: the base is a checkerboard
// repeated 8 times (REPEAT, trilinear), the layer a smooth coloured light map stretched once over each
// surface (CLAMP_TO_EDGE, trilinear), so the two lookups take different levels at every pixel. Left
// half (scissor): RGB light map at strength 1; right half: glTF occlusion (R only) at strength 0.6.
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

void buildLightMap(CommandList& cl, int w, int h) {
  beginFrame(cl, w, h, true, {0.05f, 0.05f, 0.1f, 1});
  const ResourceId base = uploadTexture(cl, checker(64, 64, 8, {230, 220, 200, 255}, {90, 110, 160, 255}), true);
  RgbaImage light{32, 32, std::vector<uint8_t>(32 * 32 * 4)};
  for (uint32_t y = 0; y < 32; ++y)
    for (uint32_t x = 0; x < 32; ++x) {
      // A warm spot near one corner fading to a cool dark rim: every channel its own ramp.
      const int dx = int(x) - 10, dy = int(y) - 12, d2 = dx * dx + dy * dy;
      const int r = std::max(40, 255 - d2 / 3), g = std::max(30, 230 - d2 / 2), b = std::max(60, 120 + int(x) * 3 - d2 / 4);
      light.set(x, y, {uint8_t(r), uint8_t(g), uint8_t(std::min(b, 255)), 255});
    }
  const ResourceId layer = uploadTexture(cl, light, true);

  Mesh m;
  // (s0, t0) the base texcoord (8 repeats), (s1, t1) the light map's (once over the surface).
  m.quad({-2, -1, -1}, {2, -1, -1}, {2, -1, -9}, {-2, -1, -9}, {0, 0, 0, 0}, {8, 0, 1, 0}, {8, 8, 1, 1}, {0, 8, 0, 1});
  m.quad({-2, -1, -9}, {2, -1, -9}, {2, 2, -9}, {-2, 2, -9}, {0, 0, 0, 0}, {8, 0, 1, 0}, {8, 6, 1, 1}, {0, 6, 0, 1});
  const uint32_t n = bindMesh(cl, m);
  cl.useProgram(cl.createProgram("textured_layers"));
  setMatrix(cl, 0, mul(perspective(60.0, double(w) / h, 0.1, 100.0), lookAt({0.2f, 0.3f, 0}, {0, -0.2f, -8}, {0, 1, 0})));
  setTexturedDefaults(cl);
  // Layer 1's texture matrix: identity.
  const float m1[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  cl.setUniforms(9, m1);
  DepthState ds;
  ds.test = true;
  cl.setDepthState(ds);
  cl.bindTexture(0, base);
  cl.bindTexture(1, layer);
  SamplerState repeat;
  repeat.minFilter = Filter::LinearMipmapLinear;
  cl.bindSampler(0, cl.createSampler(repeat));
  SamplerState clamp = repeat;
  clamp.wrapS = clamp.wrapT = Wrap::ClampToEdge;
  cl.bindSampler(1, cl.createSampler(clamp));

  setVec4(cl, 12, {1.0f, 0.0f, 0.0f, 0.0f});
  cl.setScissor({true, {0, 0, w / 2, h}});
  cl.drawIndexed(0, n);
  setVec4(cl, 12, {0.6f, 1.0f, 0.0f, 0.0f});
  cl.setScissor({true, {w / 2, 0, w - w / 2, h}});
  cl.drawIndexed(0, n);
  cl.setScissor({});
}

}  // namespace tessera::scenes
