// far_vertices: clip_planes with every other vertex moved to x = -3.4e38 (near -FLT_MAX), a valid
// frame whose clipping meets the limits of float: left, the fan of the disc under three user clip
// distances (orthographic, so the far vertices' clip x is -3.4e38 with w = 1); right, the floor in
// perspective, whose far vertices are also cut by the near plane. The triangles that keep every
// vertex finite and near reach the viewport as thin slivers and wide wedges whose clipped edges run
// towards x = -infinity.
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

void buildFarVertices(CommandList& cl, int w, int h) {
  constexpr float kFar = -3.4e38f;  // a finite float, 0.9992 * FLT_MAX
  buildClipPlanesWith(cl, w, h, [](Mesh& m) {
    for (size_t v = 1; v < m.vertices.size(); v += 2) m.vertices[v].pos.x = kFar;
  });
}

}  // namespace tessera::scenes
