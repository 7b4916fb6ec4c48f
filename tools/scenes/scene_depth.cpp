// depth: two interpenetrating triangles under LESS (their intersection line is decided per pixel
// by float32 depth), a quad drawn with GEQUAL, the first triangle redrawn with EQUAL in another
// colour (same vertices and state give the same depth: GL's invariance rule, Appendix A), and an
// ALWAYS quad with depth writes off.
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

void buildDepth(CommandList& cl, int w, int h) {
  beginFrame(cl, w, h, true, {0, 0, 0, 1});
  cl.useProgram(cl.createProgram("vertex_color"));
  setMatrix(cl, 0, mul(perspective(60.0, double(w) / h, 0.5, 10.0), lookAt({0, 0, 2.5f}, {0, 0, 0}, {0, 1, 0})));
  Mesh m;
  m.triangle({{-1.0f, -0.8f, -0.6f}, {1, 0.2f, 0.2f, 1}, 0}, {{1.0f, -0.6f, 0.5f}, {1, 0.6f, 0.2f, 1}, 0},
             {{0.0f, 0.9f, 0.0f}, {1, 0.2f, 0.6f, 1}, 0});
  m.triangle({{-1.0f, -0.5f, 0.6f}, {0.2f, 0.4f, 1, 1}, 0}, {{1.0f, -0.9f, -0.5f}, {0.2f, 1, 0.8f, 1}, 0},
             {{0.2f, 0.8f, -0.3f}, {0.5f, 0.2f, 1, 1}, 0});
  m.quad({-0.3f, -0.3f, 0.1f}, {0.9f, -0.3f, 0.1f}, {0.9f, 0.2f, 0.1f}, {-0.3f, 0.2f, 0.1f}, {0.9f, 0.9f, 0.9f, 1},
         {0.9f, 0.9f, 0.9f, 1}, {0.6f, 0.6f, 0.6f, 1}, {0.6f, 0.6f, 0.6f, 1});
  m.triangle({{-1.0f, -0.8f, -0.6f}, {0.1f, 0.9f, 0.1f, 1}, 0}, {{1.0f, -0.6f, 0.5f}, {0.1f, 0.9f, 0.1f, 1}, 0},
             {{0.0f, 0.9f, 0.0f}, {0.1f, 0.5f, 0.1f, 1}, 0});
  m.quad({-0.9f, 0.5f, 0.9f}, {-0.5f, 0.5f, 0.9f}, {-0.5f, 0.9f, 0.9f}, {-0.9f, 0.9f, 0.9f}, {1, 1, 0, 1}, {1, 1, 0, 1},
         {1, 1, 0, 1}, {1, 1, 0, 1});
  bindMesh(cl, m);
  DepthState ds;
  ds.test = true;
  cl.setDepthState(ds);
  cl.drawIndexed(0, 6);
  ds.func = CompareFunc::GEqual;
  cl.setDepthState(ds);
  cl.drawIndexed(6, 6);
  // Redraw the first triangle where it is still on top: its vertices, MVP and program are the same,
  // so its depth values are the same bits and EQUAL passes exactly there.
  ds.func = CompareFunc::Equal;
  cl.setDepthState(ds);
  cl.drawIndexed(12, 3);
  ds.func = CompareFunc::Always;
  ds.write = false;
  cl.setDepthState(ds);
  cl.drawIndexed(15, 6);
}

}  // namespace tessera::scenes
