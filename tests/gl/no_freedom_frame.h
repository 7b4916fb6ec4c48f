// A frame in which the oracle finds no freedom at all, shared by gl_tests (llvmpipe, GL 4.5 core) and
// gl33_tests (softpipe, GL 3.3 core): every GL implementation must reproduce it byte for byte.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "raster/command_list.h"
#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "raster/provenance.h"
#include "tools/scenes/builder.h"

namespace tessera::gl {

// A frame with no freedom at all: axis-aligned rectangles on pixel corners (every centre half a pixel
// from every side; each rectangle's w / h in lowest terms has one even and one odd term, so the
// diagonal that splits it, w (2m + 1) = h (2k + 1), meets no pixel centre), constant colours whose
// bytes are not near a rounding tie, no blending, and a NEAREST lookup magnified 2x so that each
// texel covers exactly one 2 x 2 quad (centres 1/4 texel from every texel boundary, zero output
// gradient inside a quad). The oracle's provenance must find no class anywhere, and then GL must
// reproduce it exactly. Vertices on pixel corners need no sub-pixel bits at all, so the frame is
// free of freedom for GL's minimum of 4 sub-pixel bits too.
inline CommandList noFreedomFrame() {
  using namespace tessera::scenes;
  CommandList cl;
  RenderTarget t;
  t.color[0] = createTarget(cl, Format::RGBA8, 32, 32);
  cl.setRenderTarget(t);
  cl.setViewport({0, 0, 32, 32});
  cl.clearColor(0, {0.2f, 0.4f, 0.6f, 1.0f});  // 51, 102, 153: exact bytes
  Mesh m;
  m.quad({2, 2, 0}, {14, 2, 0}, {14, 9, 0}, {2, 9, 0}, {}, {}, {}, {});      // flat red
  m.quad({17, 3, 0}, {31, 3, 0}, {31, 12, 0}, {17, 12, 0}, {}, {}, {}, {});  // flat green
  const glm::vec4 teal{0.2f, 0.6f, 1.0f, 1.0f};
  m.quad({3, 16, 0}, {13, 16, 0}, {13, 29, 0}, {3, 29, 0}, teal, teal, teal, teal);  // vertex_color, constant
  m.quad({18, 18, 0}, {26, 18, 0}, {26, 24, 0}, {18, 24, 0}, {0, 0, 0, 0}, {1, 0, 0, 0}, {1, 0.75f, 0, 0},
         {0, 0.75f, 0, 0});  // textured: texels 0..3 x 0..2 of a 4 x 4 texture on 8 x 6 pixels
  bindMesh(cl, m);
  cl.useProgram(cl.createProgram("flat_color"));
  setMatrix(cl, 0, ortho(0, 32, 0, 32, -1, 1));
  setVec4(cl, 4, {1, 0, 0, 1});
  cl.drawIndexed(0, 6);
  setVec4(cl, 4, {0, 1, 0, 1});
  cl.drawIndexed(6, 6);
  cl.useProgram(cl.createProgram("vertex_color"));
  setMatrix(cl, 0, ortho(0, 32, 0, 32, -1, 1));
  cl.drawIndexed(12, 6);
  RgbaImage img;
  img.width = img.height = 4;
  img.rgba.resize(64);
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 4; ++x)
      img.set(x, y, {uint8_t(40 * x + 10), uint8_t(50 * y + 20), uint8_t(200 - 30 * x), 255});
  cl.bindTexture(0, uploadTexture(cl, img, false));
  SamplerState nearest;
  nearest.minFilter = Filter::Nearest;
  nearest.magFilter = Filter::Nearest;
  cl.bindSampler(0, cl.createSampler(nearest));
  cl.useProgram(cl.createProgram("textured"));
  setMatrix(cl, 0, ortho(0, 32, 0, 32, -1, 1));
  setTexturedDefaults(cl);
  cl.drawIndexed(18, 6);

  return cl;
}

// The oracle's rendering of noFreedomFrame() with provenance: its pixels (top row first, as GL reads
// them back) and how many pixels carry a class (0 unless the frame is built wrong).
struct NoFreedomOracle {
  CpuBackend cpu{RenderOptions{1, true}};
  PresentedImage presented;
  const TextureData* tex = nullptr;
  size_t classed = 0;
  std::vector<uint8_t> pixels;
  NoFreedomOracle() {
    cpu.execute(noFreedomFrame(), "no freedom");
    presented = cpu.presented().at(0);
    tex = cpu.texture(presented.texture);
    for (uint16_t c : tex->prov->classes[0]) classed += c != 0;
    pixels = imagePixels(*tex, presented.level, presented.layer);
  }
};

// The RGBA bytes at (x, y) in GL window coordinates (bottom row 0) of a 32 x 32 read-back.
inline std::vector<uint8_t> noFreedomPixel(const std::vector<uint8_t>& px, int x, int y) {
  const size_t at = (size_t(31 - y) * 32 + size_t(x)) * 4;
  return std::vector<uint8_t>(px.begin() + long(at), px.begin() + long(at) + 4);
}

}  // namespace tessera::gl
