// Per-tile execution (the "rast" half of the backend, like llvmpipe's lp_rast.c).
//
// Implements: running one tile's bin in submission order: clears, and triangles walked as 8x8
// blocks (trivial reject / full-block fast path without per-pixel edge tests) of 2x2 quads with
// exact int64 edge tests at pixel centres, perspective-correct interpolation in double from the
// exact edge values (helper pixels extrapolated the same way), early depth test (equivalent to the
// late test for programs that write no depth; a program that writes gl_FragDepth gets the late test
// on its value, spec-choices F11), fragment shading in batches, then fragops.h per pixel.
// A tile owns its pixels, so tiles run in parallel and the result is independent of thread count.
// Does not implement: setup or binning (setup.h).
#pragma once

#include <cstring>
#include <vector>

#include "raster/pipeline.h"
#include "raster/stage_times.h"

namespace tessera::detail {

// Per-thread scratch memory, allocated once and reused for every tile.
struct RastScratch {
  static constexpr size_t kBatch = 64;  // quads per fragment-program call
  std::vector<Quad> quads = std::vector<Quad>(kBatch);
  std::vector<QuadOut> outs = std::vector<QuadOut>(kBatch);
  std::vector<uint8_t> live = std::vector<uint8_t>(kBatch);  // covered and depth-passed pixels
  LodQuadLog lodLog;  // LOD probe: the lookups of the quad being shaded (Scene::lod)
  StageTicks ticks;   // Scene::timeStages: this thread's time per stage (stage_times.h)
};

void rasterizeTile(const Scene& scene, size_t tileIndex, RastScratch& scratch, PipelineStats& stats);

struct TileRect {
  int32_t x0, y0, x1, y1;  // inclusive
};

// The provenance-mode triangle walk (rast_provenance.cpp): same coverage, depth and shading as the
// fast path, plus near-miss pixels, three program runs per quad (lower bound, upper bound, value)
// and interval bookkeeping in the targets' Provenance images.
void rasterizeTriangleProvenance(const Scene& scene, const TriSetup& t, const TileRect& tile, PipelineStats& stats);

// Interpolates one pixel (GL 4.6 §14.6.1) from its exact edge values e[i] (opposite vertex i):
// perspective-correct varyings b_i = (e_i / w_i) / sum, each rounded to float once, and depth without
// perspective, z = sum(e_i z_i) / 2A. Shared by the fast and the provenance path so their values
// are the same bytes by construction (helper pixels extrapolate the same way).
inline float interpolatePixel(const TriSetup& t, int varyings, const int64_t (&e)[3], float* var) {
  const double ed[3] = {double(e[0]), double(e[1]), double(e[2])};
  const double w0 = ed[0] * t.invW[0], w1 = ed[1] * t.invW[1], w2 = ed[2] * t.invW[2];
  const double sum = w0 + w1 + w2;
  const double b0 = w0 / sum, b1 = w1 / sum, b2 = w2 / sum;
  for (int k = 0; k < varyings; ++k) var[k] = float(b0 * t.var[0][k] + b1 * t.var[1][k] + b2 * t.var[2][k]);
  return float((ed[0] * t.z[0] + ed[1] * t.z[1] + ed[2] * t.z[2]) / double(t.area2));
}

inline float loadDepth(const TextureData& d, uint32_t level, uint32_t layer, int32_t x, int32_t y) {
  float z;
  std::memcpy(&z, d.texel(level, layer, uint32_t(x), uint32_t(y)), sizeof z);
  return z;
}

inline void storeDepth(TextureData& d, uint32_t level, uint32_t layer, int32_t x, int32_t y, float z) {
  std::memcpy(d.texel(level, layer, uint32_t(x), uint32_t(y)), &z, sizeof z);
}

}  // namespace tessera::detail
