// texarray_batch's TAM index: floor(z + 1/2), not the paper's int(z) (Trapp & Döllner 2015, Listing 1).
// A per-vertex constant k interpolated across a triangle may arrive as k - epsilon; truncation would
// then select entry k - 1. Checked through the whole oracle pipeline (vertex stage, clipping,
// perspective-correct interpolation, the program), in both TAM layouts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "raster/texture.h"
#include "tests/raster/render_helpers.h"
#include "tools/scenes/builder.h"

namespace tessera::scenes {

namespace {

// Layer l of the 5-layer array is one flat colour, distinct per layer.
std::array<uint8_t, 4> layerColour(uint32_t l) { return {uint8_t(20 + 40 * l), uint8_t(220 - 40 * l), 77, 255}; }

// An 8 x 8 frame: the left half a quad with texcoord z = nextafter(3, 0) at every vertex, the right
// half one with z = 3 - 2^-10, both under a perspective projection (w varies over the quad, so the
// interpolation is not trivially exact). Layout 0: entry e names layer e; layout 1 (materials): entry e
// names layer 4 - e with factor 1, no cutoff and alpha kept, so entry 3 shows layer 1.
CommandList indexFrame(bool materials) {
  CommandList cl;
  RenderTarget t;
  t.color[0] = createTarget(cl, Format::RGBA8, 8, 8);
  cl.setRenderTarget(t);
  cl.setViewport({0, 0, 8, 8});
  cl.clearColor(0, {0, 0, 0, 0});
  TextureDesc d;
  d.kind = TextureKind::Tex2DArray;
  d.width = d.height = 2;
  d.layers = 5;
  const ResourceId array = cl.createTexture(d);
  for (uint32_t l = 0; l < 5; ++l) {
    const std::array<uint8_t, 4> c = layerColour(l);
    std::vector<uint8_t> px;
    for (int i = 0; i < 4; ++i) px.insert(px.end(), c.begin(), c.end());
    cl.uploadTexture(array, 0, l, px);
  }
  std::vector<float> tam;
  for (uint32_t e = 0; e < 5; ++e) {
    if (materials)
      tam.insert(tam.end(), {0.0f, float(4 - e), 0.0f, 0.0f, 1.0f, 1.0f, 1.0f, 1.0f});
    else
      tam.insert(tam.end(), {0.0f, float(e)});
  }
  TextureDesc td;
  td.kind = TextureKind::Buffer;
  td.format = materials ? Format::RGBA32F : Format::RG32F;
  td.width = materials ? 10 : 5;
  td.buffer = cl.createBuffer(BufferKind::Texel, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(tam.data()),
                                                                          tam.size() * sizeof(float)));
  const float below = std::nextafter(3.0f, 0.0f), small = 3.0f - 1.0f / 1024.0f;
  Mesh m;
  m.quad({-1, -1, 0}, {0, -1, 0}, {0, 1, -0.5f}, {-1, 1, -0.5f}, {0, 0, below, 0}, {1, 0, below, 0}, {1, 1, below, 0},
         {0, 1, below, 0});
  m.quad({0, -1, 0}, {1, -1, 0}, {1, 1, -0.5f}, {0, 1, -0.5f}, {0, 0, small, 0}, {1, 0, small, 0}, {1, 1, small, 0},
         {0, 1, small, 0});
  const uint32_t n = bindMesh(cl, m);
  cl.useProgram(cl.createProgram("texarray_batch"));
  setMatrix(cl, 0, mul(perspective(60.0, 1.0, 0.1, 10.0), lookAt({0, -0.6f, 1.6f}, {0, 0, 0}, {0, 0, 1})));
  setVec4(cl, 4, {materials ? 1.0f : 0.0f, 0, 0, 0});
  cl.bindTexture(0, cl.createTexture(td));
  cl.bindTexture(1, array);
  SamplerState s;
  s.minFilter = Filter::Nearest;
  s.magFilter = Filter::Nearest;
  cl.bindSampler(1, cl.createSampler(s));
  cl.drawIndexed(0, n);
  return cl;
}

void expectEntryThree(bool materials) {
  const tessera::testing::Rendered r = tessera::testing::renderList(indexFrame(materials), 1);
  const std::vector<uint8_t>& img = r.images.at(0);
  const std::array<uint8_t, 4> want = layerColour(materials ? 1 : 3);
  int covered[2] = {0, 0};  // left (z = nextafter(3, 0)) and right (z = 3 - 2^-10) half
  for (size_t i = 0; i < img.size(); i += 4) {
    if (img[i + 3] == 0) continue;  // the clear colour: outside the quads
    ++covered[(i / 4) % 8 < 4 ? 0 : 1];
    for (int c = 0; c < 4; ++c) ASSERT_EQ(img[i + size_t(c)], want[size_t(c)]) << "pixel " << i / 4;
  }
  // Both quads reached pixels, so both values of z were looked up.
  EXPECT_GT(covered[0], 0);
  EXPECT_GT(covered[1], 0);
}

}  // namespace

TEST(TabRender, IndexJustBelowAnIntegerSelectsTheRightEntry) {
  expectEntryThree(false);
  expectEntryThree(true);
}

}  // namespace tessera::scenes
