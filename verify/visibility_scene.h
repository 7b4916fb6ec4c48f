// The window-space triangles of a frame's presented target, built independently of the CPU oracle's
// setup: the command list's state is replayed here, attributes are fetched by vertex_fetch.h, the
// vertex (and geometry) stage is the SAME Program object the oracle runs, clipping reuses
// raster/clip.h, and the viewport transform is done in double without any snapping.
//
// Implements: scope selection (docs/visibility.md "Scope"), clipping and fan triangulation as GL
// requires, facing and culling from the unsnapped signed area.
// Does not implement: coverage, depth resolution (embree_trace.h, visibility_check.h).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "raster/command_list.h"

namespace tessera::verify {

// One triangle in GL window space (pixels, y up), exactly as the unsnapped geometry puts it.
struct WindowTriangle {
  double x[3], y[3], z[3];   // z = window depth in [0, 1]
  uint32_t draw = 0;         // index into VisibilityScene::draws
  uint32_t primitiveId = 0;  // gl_PrimitiveID: triangle index within its draw
  uint32_t objectId = 0;     // flat[0] of the provoking (last) vertex: what "object_id" writes
  // Culled by the draw's face culling, or zero signed area: never the nearest hit, but still a
  // candidate near its edges, because snapping can flip a sliver's orientation.
  bool culled = false;
};

struct SceneDraw {
  size_t command = 0;  // index of the Draw command
  CompareFunc depthFunc = CompareFunc::Less;
  Rect clampRect;  // viewport ∩ scissor ∩ target: pixels the draw may touch
};

struct VisibilityScene {
  RenderTarget target;  // the presented target
  int32_t width = 0, height = 0;
  std::vector<SceneDraw> draws;
  std::vector<WindowTriangle> triangles;   // submission order: draw, primitive, fan sub-triangle
  std::array<uint32_t, 2> clearIds{0, 0};  // attachment 0 / 1 values where no triangle wins
  float clearDepth = 1.0f;
  uint64_t primitivesClipped = 0;
};

// Throws Error (naming the command index) for a list outside the scope of visibility.h.
VisibilityScene buildVisibilityScene(const CommandList& list);

}  // namespace tessera::verify
