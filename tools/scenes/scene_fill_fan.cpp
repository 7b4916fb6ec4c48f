// fill_fan: two triangle fans drawn with additive blending (ONE, ONE) and a colour of 0.25, so a
// pixel covered once reads 64, twice 128, and a gap reads 0. Fan A has its centre and every rim
// vertex on pixel centres (so its edges run through many sample points: the fill rule decides
// them); fan B has every vertex on pixel corners. Orthographic projection in pixel units, so for
// power-of-two sizes every vertex snaps exactly.
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {
namespace {

void fan(Mesh& m, float cx, float cy, int radius, int step) {
  // Rim points walk the square of half-size `radius` counter-clockwise in integer pixel steps.
  std::vector<std::array<float, 2>> rim;
  for (int i = -radius; i < radius; i += step) rim.push_back({cx + float(i), cy - float(radius)});
  for (int i = -radius; i < radius; i += step) rim.push_back({cx + float(radius), cy + float(i)});
  for (int i = radius; i > -radius; i -= step) rim.push_back({cx + float(i), cy + float(radius)});
  for (int i = radius; i > -radius; i -= step) rim.push_back({cx - float(radius), cy + float(i)});
  for (size_t i = 0; i < rim.size(); ++i) {
    const auto& a = rim[i];
    const auto& b = rim[(i + 1) % rim.size()];
    m.triangle({{cx, cy, 0}, {0, 0, 0, 0}, 0}, {{a[0], a[1], 0}, {0, 0, 0, 0}, 0}, {{b[0], b[1], 0}, {0, 0, 0, 0}, 0});
  }
}

}  // namespace

void buildFillFan(CommandList& cl, int w, int h) {
  beginFrame(cl, w, h, false, {0, 0, 0, 1});
  Mesh m;
  const int r = std::max(1, std::min(w / 4, h / 2) - 3);
  fan(m, float(w / 4) + 0.5f, float(h / 2) + 0.5f, r, 3);  // centres on pixel centres
  fan(m, float(3 * w / 4), float(h / 2), r, 5);           // vertices on pixel corners
  const uint32_t n = bindMesh(cl, m);
  cl.useProgram(cl.createProgram("flat_color"));
  setMatrix(cl, 0, ortho(0, w, 0, h, -1, 1));
  setVec4(cl, 4, {0.25f, 0.25f, 0.25f, 0.25f});
  BlendState b;
  b.enabled = true;
  b.srcRgb = b.dstRgb = b.srcAlpha = b.dstAlpha = BlendFactor::One;
  cl.setBlendState(b);
  cl.drawIndexed(0, n);
}

}  // namespace tessera::scenes
