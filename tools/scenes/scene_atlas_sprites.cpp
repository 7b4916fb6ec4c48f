// atlas_sprites: render-to-texture-atlas compositing with depth sprites (Trapp & Döllner 2010, §3.2,
// Figure 3A). A hand-made 32x32, 2-layer atlas (RGBA8 colour + RG32F (depth, covered), uploaded as
// textures) is composited by program atlas_sprite into the frame with the depth test on (LESS):
// - C: all of layer 1 (depth 0.7, a 2-texel empty border) at screen [4, 36)^2;
// - A: layer 0, x in [0, 16), depth 0.25 + x / 64, with an empty disc (radius 4 around (8, 16)) that
//   shows what lies behind, at screen [20, 36) x [16, 48);
// - B: layer 0, x in [16, 32), depth 0.3 + (x - 16) / 16, at screen [28, 44) x [10, 42), drawn after A:
//   in front of A at screen x 28..29 and behind it from x 30 on (the fragment depth decides, not the
//   draw order); behind C where C is covered and B's depth exceeds 0.7. B's last four columns hold
//   depths 1.05 .. 1.2375: clamped to 1 (spec-choices F11), they fail LESS against the clear depth 1,
//   so screen x 40..43 keeps the clear colour.
// Every depth is a multiple of 1/64 and no two sprites meet at equal depth; sprite edges lie on
// pixel edges (no centre on an edge), and the tint is 1, so colours are the texels exactly.
#include <cstddef>

#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

namespace {
constexpr uint32_t kAtlasSize = 32;

struct SpriteVertex {
  float pos[4];    // clip space, w = 1
  float shift[4];  // (dx, dy, layer, 0)
};

// Two triangles covering pixels [x0, x1) x [y0, y1) of a w x h frame, showing atlas texel
// (x + dx, y + dy) of `layer` at pixel (x, y).
void sprite(std::vector<SpriteVertex>& v, int w, int h, int x0, int y0, int x1, int y1, int ax0, int ay0, int layer) {
  auto ndc = [](int p, int size) { return float(double(2 * p) / double(size) - 1.0); };
  const float l = ndc(x0, w), r = ndc(x1, w), b = ndc(y0, h), t = ndc(y1, h);
  const float s[4] = {float(ax0 - x0), float(ay0 - y0), float(layer), 0};
  const float corners[6][2] = {{l, b}, {r, b}, {r, t}, {l, b}, {r, t}, {l, t}};
  for (const auto& c : corners) v.push_back({{c[0], c[1], 0, 1}, {s[0], s[1], s[2], s[3]}});
}
}  // namespace

void buildAtlasSprites(CommandList& cl, int w, int h) {
  // The hand-made atlas: colour (RGBA8) and (depth, covered) (RG32F), 2 layers.
  const size_t texels = size_t(kAtlasSize) * kAtlasSize;
  std::vector<uint8_t> colour(2 * texels * 4, 0);
  std::vector<float> depth(2 * texels * 2, 0.0f);
  for (uint32_t layer = 0; layer < 2; ++layer)
    for (uint32_t y = 0; y < kAtlasSize; ++y)
      for (uint32_t x = 0; x < kAtlasSize; ++x) {
        const size_t i = size_t(layer) * texels + size_t(y) * kAtlasSize + x;
        uint8_t* c = &colour[i * 4];
        float* d = &depth[i * 2];
        bool covered = true;
        float z = 1.0f;
        if (layer == 1) {  // C: a checker, empty border of 2 texels
          covered = x >= 2 && y >= 2 && x < kAtlasSize - 2 && y < kAtlasSize - 2;
          const bool dark = ((x / 4 + y / 4) & 1) != 0;
          c[0] = dark ? 40 : 200, c[1] = dark ? 60 : 210, c[2] = 90;
          z = 0.7f;
        } else if (x < 16) {  // A: a gradient with an empty disc
          const int dx = int(x) - 8, dy = int(y) - 16;
          covered = dx * dx + dy * dy >= 16;
          c[0] = uint8_t(120 + 8 * x), c[1] = uint8_t(40 + 4 * y), c[2] = 30;
          z = float(0.25 + double(x) / 64.0);
        } else {  // B: stripes
          c[0] = 30, c[1] = uint8_t((y / 2) & 1 ? 90 : 160), c[2] = uint8_t(100 + 9 * (x - 16));
          z = float(0.3 + double(x - 16) / 16.0);
        }
        c[3] = covered ? 255 : 0;
        d[0] = covered ? z : 1.0f;
        d[1] = covered ? 1.0f : 0.0f;
      }
  TextureDesc cd;
  cd.kind = TextureKind::Tex2DArray;
  cd.format = Format::RGBA8;
  cd.width = cd.height = kAtlasSize;
  cd.layers = 2;
  const ResourceId atlasColour = cl.createTexture(cd);
  TextureDesc dd = cd;
  dd.format = Format::RG32F;
  const ResourceId atlasDepth = cl.createTexture(dd);
  for (uint32_t layer = 0; layer < 2; ++layer) {
    cl.uploadTexture(atlasColour, 0, layer, std::span<const uint8_t>(&colour[layer * texels * 4], texels * 4));
    cl.uploadTexture(atlasDepth, 0, layer,
                     std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(&depth[layer * texels * 2]), texels * 8));
  }

  beginFrame(cl, w, h, true, {0.2f, 0.2f, 0.25f, 1});
  DepthState ds;
  ds.test = true;
  cl.setDepthState(ds);
  std::vector<SpriteVertex> v;
  sprite(v, w, h, 4, 4, 36, 36, 0, 0, 1);     // C
  sprite(v, w, h, 20, 16, 36, 48, 0, 0, 0);   // A
  sprite(v, w, h, 28, 10, 44, 42, 16, 0, 0);  // B
  std::span<const uint8_t> vb(reinterpret_cast<const uint8_t*>(v.data()), v.size() * sizeof(SpriteVertex));
  cl.bindVertexBuffer(cl.createBuffer(BufferKind::Vertex, vb));
  VertexLayout layout;
  layout.stride = sizeof(SpriteVertex);
  layout.attribs[0] = {0, 4, AttribType::F32, offsetof(SpriteVertex, pos)};
  layout.attribs[2] = {2, 4, AttribType::F32, offsetof(SpriteVertex, shift)};
  cl.setVertexLayout(layout);
  cl.bindTexture(0, atlasColour);
  cl.bindTexture(1, atlasDepth);
  cl.useProgram(cl.createProgram("atlas_sprite"));
  setVec4(cl, 7, {1, 1, 1, 1});
  for (uint32_t s = 0; s < 3; ++s) cl.draw(s * 6, 6);
}

}  // namespace tessera::scenes
