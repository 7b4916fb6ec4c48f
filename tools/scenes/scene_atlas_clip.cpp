// atlas_clip: clip distances of render-to-texture-atlas come from the undisplaced position
// (atlas_displace.cpp). One textured quad reaching from x = -1.6 to 0.4 in clip space is displaced
// by x' = 0.5 x + 0.5 w into the right half; clip distances 0-3 (enabled) cut it at the undisplaced
// x = -1, i.e. at x' = 0, so the left quarter of the target stays clear. Clipping the displaced
// position instead would keep the part down to x' = -0.3.
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

void buildAtlasClip(CommandList& cl, int w, int h) {
  beginFrame(cl, w, h, false, {0.2f, 0.2f, 0.25f, 1});
  const float rec[8] = {0.5f, 0, 0, 1, 0.5f, 0, 0, 0};  // (a, b, c, d), (tx, ty, layer, -)
  std::span<const uint8_t> recBytes(reinterpret_cast<const uint8_t*>(rec), sizeof rec);
  TextureDesc rd;
  rd.kind = TextureKind::Buffer;
  rd.format = Format::RGBA32F;
  rd.width = 2;
  rd.buffer = cl.createBuffer(BufferKind::Texel, recBytes);
  cl.bindTexture(0, cl.createTexture(rd));
  cl.bindTexture(1, uploadTexture(cl, checker(8, 8, 2, {220, 120, 40, 255}, {40, 90, 200, 255}), false));
  SamplerState s;
  s.minFilter = Filter::Nearest;
  s.magFilter = Filter::Nearest;
  cl.bindSampler(1, cl.createSampler(s));
  Mesh m;
  m.quad({-1.6f, -0.8f, 0}, {0.4f, -0.8f, 0}, {0.4f, 0.8f, 0}, {-1.6f, 0.8f, 0}, {0, 0, 0, 0}, {1, 0, 0, 0},
         {1, 1, 0, 0}, {0, 1, 0, 0}, 0);
  const uint32_t n = bindMesh(cl, m);
  cl.useProgram(cl.createProgram("atlas_displace"));
  setMatrix(cl, 0, ortho(-1, 1, -1, 1, -1, 1));
  setVec4(cl, 7, {1, 1, 1, 1});
  RasterState rs;
  rs.clipMask = 0x0f;
  cl.setRasterState(rs);
  cl.drawIndexed(0, n);
}

}  // namespace tessera::scenes
