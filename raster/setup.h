// Triangle setup and binning (the "setup" half of the backend, like llvmpipe's lp_setup_tri.c).
//
// Implements, per vertex (windowVerticesReference, the rule window_simd.h's kernel reproduces): the
// clip outcode (clip.h), perspective division and the viewport transform in double (GL 4.6 §13.8)
// and snapping to 8 sub-pixel bits with round-half-to-even. Per assembled triangle: classification
// from the three outcodes, clipping (clip.h) and the same transform of the vertices clipping makes,
// face determination and culling from the snapped signed area (§14.6.1), counter-clockwise ordering,
// int64 edge functions with the left/bottom fill rule, the pixel bounding box clamped to
// viewport ∩ scissor ∩ target, and binning into every 64x64 tile the triangle can touch.
// Does not implement: vertex shading or pixel work.
#pragma once

#include "raster/clip.h"
#include "raster/pipeline.h"
#include "raster/window_simd.h"

namespace tessera::detail {

struct SetupParams {
  Rect viewport;
  Rect clampRect;          // viewport ∩ scissor ∩ target, in pixels
  RasterState raster;
  uint32_t stateIndex = 0; // Scene::states index of the draw
  int varyings = 0;
  bool provenance = false;  // bin with bounding boxes one pixel wider (near-miss pixels can be ties)
  bool timeStages = false;  // add polygon clipping's ticks to SetupSink::clipTicks (stage_times.h)
};

// Where setup puts its output: the set-up triangles in order and, per triangle, the tiles it must
// be binned into. Draws set up chunks of triangles in parallel, each into its own sink; the sinks
// are then appended to the scene in triangle order (appendToScene), so bins keep submission order.
struct SetupSink {
  int32_t tilesX = 0;
  std::vector<TriSetup> tris;
  std::vector<uint32_t> tiles;     // tile indices, triangle after triangle
  std::vector<uint32_t> tileEnd;   // per triangle: end of its run in `tiles`
  PipelineStats stats;
  uint64_t clipTicks = 0;  // SetupParams::timeStages
  uint64_t segment = 0;    // the upload segment of the draw (Scene::segment), for appendToScene
  uint64_t boxPixels = 0;  // the pixels of the binned triangles' bounding boxes, summed (Scene::BlockInfo)
  void clear() {
    boxPixels = 0;
    tris.clear();
    tiles.clear();
    tileEnd.clear();
    stats = {};
    clipTicks = 0;
  }
};

// Sets up one triangle (after the vertex/geometry stages) and records what survives in `sink`. The
// vertices are read in place: most triangles need no copy of their 128-byte VertexOuts. Vertex i's
// record (window_simd.h, for params.viewport and params.raster.clipMask) is element s[i] of win: the
// triangle is classified from their outcodes, and an unclipped one takes their window positions.
void setupTriangle(const VertexOut* const (&v)[3], const VertexWindows& win, const size_t (&s)[3],
                   uint32_t primitiveId, uint32_t layer, const SetupParams& params, SetupSink& sink);

// Appends a sink's triangles to the scene and its bins, in order, and adds its stats. The triangles
// move into the scene as one block (Scene::triBlocks), leaving the sink's vector empty.
void appendToScene(SetupSink& sink, Scene& scene, PipelineStats& stats);

// Round half to even of a finite double with |v| < 2^62 to int64 (the snapping and unorm conversion
// rule; never depends on the FPU rounding mode). Inline: it runs per pixel and channel.
inline int64_t roundHalfEven(double v) {
  // Truncation then a correction gives floor without a libm call.
  int64_t f = int64_t(v);
  if (double(f) > v) --f;
  const double diff = v - double(f);  // exact: v and f are within one unit of each other
  if (diff > 0.5 || (diff == 0.5 && (f & 1))) ++f;
  return f;
}

}  // namespace tessera::detail
