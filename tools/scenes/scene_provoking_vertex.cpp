// provoking_vertex: flat varyings. Triangles drawn through "object_id" whose three vertices carry
// three different ids, into an R32UI target: every covered pixel must hold the id of the
// provoking vertex, the last one (spec-choices V6), so a rasterizer that takes the first vertex
// (or any other) shows a different id over the whole triangle. Only attachment 0 is bound: the
// program's primitive-id output goes nowhere.
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

void buildProvokingVertex(CommandList& cl, int w, int h) {
  RenderTarget t;
  t.color[0] = createTarget(cl, Format::R32UI, w, h);
  cl.setRenderTarget(t);
  cl.setViewport({0, 0, w, h});
  cl.clearColorUint(0, {0xffffffffu, 0, 0, 0});
  Mesh m;
  // A 3 x 2 grid of triangles, alternately pointing up and down; vertex k of triangle i has id
  // 10 i + k, so the three candidates of a pixel always differ.
  for (uint32_t i = 0; i < 6; ++i) {
    const float x0 = -0.95f + 0.65f * float(i % 3), y0 = i < 3 ? -0.9f : 0.05f, s = 0.6f;
    const uint32_t id = 10 * i;
    const glm::vec4 none{0, 0, 0, 0};
    if (i % 2 == 0) {
      m.triangle({{x0, y0, 0}, none, id}, {{x0 + s, y0, 0}, none, id + 1}, {{x0 + s / 2, y0 + 0.8f, 0}, none, id + 2});
    } else {
      m.triangle({{x0, y0 + 0.8f, 0}, none, id}, {{x0 + s / 2, y0, 0}, none, id + 1},
                 {{x0 + s, y0 + 0.8f, 0}, none, id + 2});
    }
  }
  const uint32_t n = bindMesh(cl, m);
  cl.useProgram(cl.createProgram("object_id"));
  setMatrix(cl, 0, ortho(-1, 1, -1, 1, -1, 1));
  cl.drawIndexed(0, n);
}

}  // namespace tessera::scenes
