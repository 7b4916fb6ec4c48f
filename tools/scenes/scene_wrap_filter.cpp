// wrap_filter: a 4 x 3 grid of quads. Columns: REPEAT, MIRRORED_REPEAT, CLAMP_TO_EDGE,
// CLAMP_TO_BORDER (magenta border). Rows, bottom to top: NEAREST, LINEAR (texcoords -1.5 .. 2.5 on
// an 8x8 texture: magnified), LINEAR_MIPMAP_LINEAR (texcoords -7.5 .. 8.5: minified).
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

void buildWrapFilter(CommandList& cl, int w, int h) {
  beginFrame(cl, w, h, false, {0.1f, 0.1f, 0.1f, 1});
  RgbaImage img{8, 8, std::vector<uint8_t>(8 * 8 * 4)};
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = 0; x < 8; ++x)
      img.set(x, y, {uint8_t(x * 32 + 16), uint8_t(y * 32 + 16), uint8_t(((x ^ y) & 1) ? 255 : 40), 255});
  const ResourceId tex = uploadTexture(cl, img, true);
  cl.useProgram(cl.createProgram("textured"));
  setMatrix(cl, 0, ortho(0, 4, 0, 3, -1, 1));
  setTexturedDefaults(cl);
  cl.bindTexture(0, tex);

  const Wrap wraps[4] = {Wrap::Repeat, Wrap::MirroredRepeat, Wrap::ClampToEdge, Wrap::ClampToBorder};
  const Filter filters[3] = {Filter::Nearest, Filter::Linear, Filter::LinearMipmapLinear};
  Mesh m;
  for (int row = 0; row < 3; ++row) {
    const float lo = row == 2 ? -7.5f : -1.5f, hi = row == 2 ? 8.5f : 2.5f;
    const float y0 = float(row) + 0.05f, y1 = float(row) + 0.95f;
    m.quad({0.05f, y0, 0}, {0.95f, y0, 0}, {0.95f, y1, 0}, {0.05f, y1, 0}, {lo, lo, 0, 0}, {hi, lo, 0, 0}, {hi, hi, 0, 0},
           {lo, hi, 0, 0});
  }
  bindMesh(cl, m);
  for (int col = 0; col < 4; ++col) {
    // Shift the quads to column `col` through the MVP so one mesh serves every column.
    setMatrix(cl, 0, ortho(-double(col), 4.0 - col, 0, 3, -1, 1));
    for (int row = 0; row < 3; ++row) {
      SamplerState s;
      s.wrapS = s.wrapT = wraps[col];
      s.minFilter = filters[row];
      s.magFilter = filters[row] == Filter::Nearest ? Filter::Nearest : Filter::Linear;
      s.borderColor = {1, 0, 1, 1};
      cl.bindSampler(0, cl.createSampler(s));
      cl.drawIndexed(uint32_t(row) * 6, 6);
    }
  }
}

}  // namespace tessera::scenes
