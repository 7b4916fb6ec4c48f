// clip_planes: left half: a colour-ramp disc (triangle fan, orthographic) cut by three enabled
// user clip distances (x <= 0.55, y >= -0.6 and a diagonal); right half: a long textured-looking
// colour floor in perspective whose near end crosses the near plane, so near-plane clipping
// produces new vertices with interpolated colours.
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

void buildClipPlanesWith(CommandList& cl, int w, int h, const std::function<void(Mesh&)>& editMesh) {
  beginFrame(cl, w, h, true, {0, 0, 0, 1});
  cl.useProgram(cl.createProgram("vertex_color"));
  DepthState ds;
  ds.test = true;
  cl.setDepthState(ds);

  Mesh disc;
  const int n = 64;
  for (int i = 0; i < n; ++i) {
    const double a0 = 2.0 * kPi * i / n, a1 = 2.0 * kPi * (i + 1) / n;
    const float c0 = float(i) / n, c1 = float(i + 1) / n;
    disc.triangle({{0, 0, 0}, {1, 1, 1, 1}, 0},
                  {{float(0.9 * detCos(a0)), float(0.9 * detSin(a0)), 0}, {c0, 1 - c0, 0.5f, 1}, 0},
                  {{float(0.9 * detCos(a1)), float(0.9 * detSin(a1)), 0}, {c1, 1 - c1, 0.5f, 1}, 0});
  }
  Mesh floor;
  const int rows = 16;
  for (int i = 0; i < rows; ++i) {
    const float z0 = 1.0f - 2.0f * float(i), z1 = z0 - 2.0f;
    const float c = (i & 1) ? 0.9f : 0.3f;
    floor.quad({-2, -1, z0}, {2, -1, z0}, {2, -1, z1}, {-2, -1, z1}, {c, 0.2f, 1 - c, 1}, {0.2f, c, 1 - c, 1},
               {0.2f, c, c, 1}, {c, 0.2f, c, 1});
  }

  if (editMesh) {
    editMesh(disc);
    editMesh(floor);
  }

  const uint32_t nd = bindMesh(cl, disc);
  cl.setViewport({0, 0, w / 2, h});
  setMatrix(cl, 0, ortho(-1, 1, -1, 1, -1, 1));
  const float planes[12] = {-1, 0, 0, 0.55f, 0, 1, 0, 0.6f, -0.7f, -0.7f, 0, 0.5f};
  cl.setUniforms(8, planes);
  RasterState rs;
  rs.clipMask = 0x7;
  cl.setRasterState(rs);
  cl.drawIndexed(0, nd);

  const uint32_t nf = bindMesh(cl, floor);
  cl.setViewport({w / 2, 0, w - w / 2, h});
  cl.setRasterState({});
  setMatrix(cl, 0,
            mul(perspective(75.0, double(w - w / 2) / h, 0.5, 40.0), lookAt({0, 0, 0}, {0, -0.3f, -1}, {0, 1, 0})));
  cl.drawIndexed(0, nf);
}

void buildClipPlanes(CommandList& cl, int w, int h) { buildClipPlanesWith(cl, w, h, {}); }

}  // namespace tessera::scenes
