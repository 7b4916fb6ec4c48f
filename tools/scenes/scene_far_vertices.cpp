// far_vertices: clip_planes with every other vertex moved to x = -3.4e38 (near -FLT_MAX), a valid
// frame whose clipping meets the limits of float: left, the fan of the disc under three user clip
// distances (orthographic, so the far vertices' clip x is -3.4e38 with w = 1); right, the floor in
// perspective, whose far vertices are also cut by the near plane. The triangles that keep every
// vertex finite and near reach the viewport as thin slivers and wide wedges whose clipped edges run
// towards x = -infinity.
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

void buildFarVertices(CommandList& cl, int w, int h) {
  beginFrame(cl, w, h, true, {0, 0, 0, 1});
  cl.useProgram(cl.createProgram("vertex_color"));
  DepthState ds;
  ds.test = true;
  cl.setDepthState(ds);

  constexpr float kFar = -3.4e38f;  // a finite float, 0.9992 * FLT_MAX
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
  for (Mesh* m : {&disc, &floor})
    for (size_t v = 1; v < m->vertices.size(); v += 2) m->vertices[v].pos.x = kFar;

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

}  // namespace tessera::scenes
