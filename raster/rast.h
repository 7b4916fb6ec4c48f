// Per-tile execution (the "rast" half of the backend, like llvmpipe's lp_rast.c).
//
// Implements: running one tile's bin in submission order: clears, and triangles walked as 8x8
// blocks (trivial reject / full-block fast path without per-pixel edge tests) of 2x2 quads with
// exact int64 edge tests at pixel centres, perspective-correct interpolation in double from the
// exact edge values (helper pixels extrapolated the same way), early depth test (equivalent to the
// late test: programs never write depth), fragment shading in batches, then fragops.h per pixel.
// A tile owns its pixels, so tiles run in parallel and the result is independent of thread count.
// Does not implement: setup or binning (setup.h).
#pragma once

#include <vector>

#include "raster/pipeline.h"

namespace tessera::detail {

// Per-thread scratch memory, allocated once and reused for every tile.
struct RastScratch {
  static constexpr size_t kBatch = 64;  // quads per fragment-program call
  std::vector<Quad> quads = std::vector<Quad>(kBatch);
  std::vector<QuadOut> outs = std::vector<QuadOut>(kBatch);
  std::vector<uint8_t> live = std::vector<uint8_t>(kBatch);  // covered and depth-passed pixels
  std::vector<std::array<float, 4>> depth = std::vector<std::array<float, 4>>(kBatch);
};

void rasterizeTile(const Scene& scene, size_t tileIndex, RastScratch& scratch, PipelineStats& stats);

}  // namespace tessera::detail
