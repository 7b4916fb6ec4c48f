// depth_ties: exact depth ties. Four sloped quads (perspective, so depth varies across each), each
// drawn twice with the same vertices, MVP and program, so both draws produce the same depth bits
// (GL's invariance rule, Appendix A) and the second draw's comparison meets an exact tie. The first
// pass writes dark colours under LESS; the second, in bright colours, uses LESS, LEQUAL, GREATER and
// GEQUAL per column: only LEQUAL and GEQUAL pass, so the strictness of every function is visible.
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

void buildDepthTies(CommandList& cl, int w, int h) {
  beginFrame(cl, w, h, true, {0, 0, 0, 1});
  cl.useProgram(cl.createProgram("vertex_color"));
  setMatrix(cl, 0, mul(perspective(60.0, double(w) / h, 0.5, 10.0), lookAt({0, 0.4f, 2.5f}, {0, 0, 0}, {0, 1, 0})));
  Mesh m;
  for (int pass = 0; pass < 2; ++pass)
    for (int i = 0; i < 4; ++i) {
      const float x0 = -1.3f + 0.65f * float(i), x1 = x0 + 0.55f;
      const float c = pass == 0 ? 0.25f : 0.95f;
      const glm::vec4 col{c, pass == 0 ? 0.2f : 0.8f * float(i & 1), c * float(i) / 3.0f, 1};
      m.quad({x0, -0.8f, 0.6f}, {x1, -0.8f, 0.3f}, {x1, 0.8f, -0.9f}, {x0, 0.8f, -0.6f}, col, col, col, col);
    }
  bindMesh(cl, m);
  DepthState ds;
  ds.test = true;
  cl.setDepthState(ds);
  cl.drawIndexed(0, 24);
  const CompareFunc funcs[4] = {CompareFunc::Less, CompareFunc::LEqual, CompareFunc::Greater, CompareFunc::GEqual};
  for (uint32_t i = 0; i < 4; ++i) {
    ds.func = funcs[i];
    cl.setDepthState(ds);
    cl.drawIndexed(24 + 6 * i, 6);
  }
}

}  // namespace tessera::scenes
