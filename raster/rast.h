// Per-tile execution (the "rast" half of the backend, like llvmpipe's lp_rast.c).
//
// Implements: running one tile's bin in submission order: clears, and triangles walked as 8x8
// blocks (trivial reject / full-block fast path without per-pixel edge tests; otherwise one coverage
// mask of exact int64 edge tests at pixel centres, coverage_simd.h) of 2x2 quads,
// perspective-correct interpolation in double from the exact edge values (helper pixels extrapolated
// the same way; a block's quads at once through interpolate_simd.h, or per quad below under the
// "reference" SIMD target), early depth test (equivalent to the late test for programs that write
// no depth; a program that writes gl_FragDepth gets the late test on its value, spec-choices F11),
// fragment shading in batches, then fragops.h per pixel. Consecutive triangles whose fragments' fate
// does not depend on shading (no blending, no discard, no gl_FragDepth) run as a visibility run:
// coverage and depth first, then only the fragments that stay visible are shaded (without a depth test,
// a triangle that covers its box in the tile whole records it in one fill, not block by block). A
// block whose covered pixels must all fail a LESS or LEQUAL depth test, by the triangle's least vertex
// depth against the block's largest stored depth (hierarchical Z), is not walked; its fragments count
// as failing.
// A tile owns its pixels, so tiles run in parallel and the result is independent of thread count.
// Does not implement: setup or binning (setup.h).
#pragma once

#include <cstring>
#include <limits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "raster/coverage_simd.h"
#include "raster/fragops_simd.h"
#include "raster/interpolate_simd.h"
#include "raster/pipeline.h"
#include "raster/stage_times.h"

namespace tessera::detail {

// One (level, layer) image of an attachment, addressed like TextureData::texel() without
// recomputing the level's size per pixel.
struct AttachmentPlane {
  uint8_t* base = nullptr;
  uint64_t rowBytes = 0;
  uint32_t bpp = 0;
  Format format = Format::RGBA8;
  static AttachmentPlane of(TextureData* tex, uint32_t level, uint32_t layer) {
    if (!tex) return {};
    const uint32_t bpp = texelBytes(tex->desc.format);
    return {tex->texel(level, layer, 0, 0), uint64_t(levelWidth(tex->desc, level)) * bpp, bpp, tex->desc.format};
  }
  uint8_t* at(int32_t x, int32_t y) const {
    return base + uint64_t(uint32_t(y)) * rowBytes + uint64_t(uint32_t(x)) * bpp;
  }
  float depth(int32_t x, int32_t y) const {
    float z;
    std::memcpy(&z, at(x, y), sizeof z);
    return z;
  }
};

// What the walk of a triangle derives from its draw state, its layer and the scene's target: the same
// for every triangle of a draw in a tile, so rast.cpp computes it once per draw and layer (drawConsts).
struct DrawConsts {
  uint32_t state = UINT32_MAX, layer = 0;  // the key; state UINT32_MAX: nothing cached
  bool lateDepth = false;       // the program writes gl_FragDepth
  bool sourceOver = false;      // blending is SRC_ALPHA, ONE_MINUS_SRC_ALPHA, ADD
  bool unblendedRgba8 = false;  // no blending, every written attachment RGBA8 or absent
  bool sourceOverRgba8 = false;  // source-over blending, every written attachment RGBA8 or absent
  // The plain draw (rast.cpp, writePlainRgba8): one colour output, to a present RGBA8 attachment, no
  // blending, no gl_FragDepth and no LOD probe.
  bool plainRgba8 = false;
  bool depthWrite = false;      // the depth test is on with a depth target, and depth writes are on
  bool hizEligible = false;     // the hierarchical Z may skip blocks (rast.cpp, occlusionFloor)
  // Per walk of rast.cpp (Immediate, Visibility, Owned): the gathered quads' depths are interpolated,
  // and their edge values are read (by the depth or the varyings kernel). Made once per draw, not per
  // triangle.
  bool depthsRead[3] = {}, edgesRead[3] = {};
  AttachmentPlane depth, color[kMaxColorAttachments];
};

// Per-thread scratch memory, allocated once and reused for every tile.
struct RastScratch {
  static constexpr size_t kBatch = 64;  // quads per fragment-program call
  std::vector<Quad> quads = std::vector<Quad>(kBatch);
  std::vector<QuadOut> outs = std::vector<QuadOut>(kBatch);
  std::vector<uint8_t> live = std::vector<uint8_t>(kBatch);  // covered and depth-passed pixels
  LodQuadLog lodLog;  // LOD probe: the lookups of the quad being shaded (Scene::lod)
  StageTicks ticks;   // Scene::timeStages: this thread's time per stage (stage_times.h)
  // The colour write's unorm8 kernel (raster/fragops_simd.h), resolved per tile by rasterizeTile.
  Unorm8QuadFn unorm8Quad = nullptr;
  BlendSourceOverQuadFn blendSourceOverQuad = nullptr;  // the same for a source-over blend
  // The last 16 colour values (their bits) the walk converted with unorm8Quad, and the bytes they gave
  // (rast.cpp, quadUnorm8). Zero values give zero bytes, so the initial state is a true entry.
  struct UnormMemo {
    uint64_t in[8] = {};
    uint8_t out[16] = {};
    // out = fn(values) for a quad's 16 values: from the entry when all 64 bytes of the values equal
    // it (exact: fn is a pure function of the bits), otherwise converted, entered, and `ask` cleared.
    void convert(Unorm8QuadFn fn, const float* values, uint8_t* bytes, bool& ask) {
      if (same(values)) {
        std::memcpy(bytes, out, sizeof out);
        return;
      }
      ask = false;
      fn(values, bytes);
      std::memcpy(in, values, sizeof in);
      std::memcpy(out, bytes, sizeof out);
    }
    // Whether the 64 bytes at `values` equal `in`: a comparison of bits, so any order of the loads
    // gives the same answer. With SSE2, four 16-byte compares (about 14 instructions); compilers do not
    // vectorize the 64-bit loop below, which cost about 37 per quad of a constant colour (callgrind,
    // fill_flat_720p).
    bool same(const float* values) const {
#if defined(__SSE2__)
      const auto* a = reinterpret_cast<const __m128i*>(values);
      const auto* b = reinterpret_cast<const __m128i*>(in);
      const __m128i e0 = _mm_cmpeq_epi8(_mm_loadu_si128(a), _mm_loadu_si128(b));
      const __m128i e1 = _mm_cmpeq_epi8(_mm_loadu_si128(a + 1), _mm_loadu_si128(b + 1));
      const __m128i e2 = _mm_cmpeq_epi8(_mm_loadu_si128(a + 2), _mm_loadu_si128(b + 2));
      const __m128i e3 = _mm_cmpeq_epi8(_mm_loadu_si128(a + 3), _mm_loadu_si128(b + 3));
      const __m128i all = _mm_and_si128(_mm_and_si128(e0, e1), _mm_and_si128(e2, e3));
      return _mm_movemask_epi8(all) == 0xFFFF;
#else
      uint64_t v[8], diff = 0;
      std::memcpy(v, values, sizeof v);
      for (int i = 0; i < 8; ++i) diff |= v[i] ^ in[i];
      return diff == 0;
#endif
    }
  } unormMemo;
  // The interpolation kernels (raster/interpolate_simd.h), resolved per tile; nullptr under
  // "reference", where every quad takes interpolateQuadDepth / interpolateQuadVaryings below.
  QuadDepthsFn quadDepths = nullptr;
  QuadVaryingsFn quadVaryings = nullptr;
  // The block coverage kernel (raster/coverage_simd.h; the scalar reference under "reference").
  BlockCoverageFn blockCoverage = nullptr;
  // An 8x8 block's covered quads, gathered for the kernels: position and coverage, edge values in
  // `px`, and the kernels' outputs.
  struct PendingQuad {
    int32_t x, y;
    uint8_t coverage;
  };
  PendingQuad pending[QuadPixels::kMax / 4] = {};
  QuadPixels px;
  alignas(64) float z[QuadPixels::kMax] = {};
  alignas(64) float var[kMaxVaryings * QuadPixels::kMax] = {};
  // A visibility run (rast.cpp): per pixel of the tile (row-major, kTileSize wide), 1 + the run index
  // of the triangle whose fragment is the last to pass the depth test, 0 for none.
  alignas(64) uint16_t owner[kTileSize * kTileSize] = {};
  // The quads each owner shades (groupOwnedQuads in rast.cpp): x, y of the quad, the owned pixels.
  struct OwnedQuad {
    int32_t x, y;
    uint8_t mask;
    uint16_t id;
  };
  std::vector<OwnedQuad> ownedQuads, ownedTemp;
  std::vector<uint32_t> ownedStart, ownedFill;
  // Hierarchical Z (rast.cpp, TriangleRasterizer::occluded): per 8x8 block of the tile (row-major),
  // the largest non-NaN depth stored in it, known where hizKnown has the block's bit. A block's bit
  // is cleared when a triangle that may write its depth visits it, and every bit at the tile's start
  // and at a depth clear.
  static constexpr int kBlocksPerRow = kTileSize / kBlockSize;
  static_assert(kBlocksPerRow * kBlocksPerRow == 64, "a tile's blocks are one 64-bit mask");
  float hizMax[kBlocksPerRow * kBlocksPerRow] = {};
  uint64_t hizKnown = 0;
  // Work the fast path skipped, for benchmarks and tests (StageTimes; not a GL counter): blocks and
  // fragments found hidden by the hierarchical Z without being walked.
  uint64_t hizBlocksSkipped = 0, hizFragmentsSkipped = 0;
  // Provenance mode's lookup shortcuts, moved here from the thread's ShadeProvenance after each tile.
  uint64_t provPlansSkipped = 0, provGridsShared = 0;
  DrawConsts drawConsts;  // of the last draw walked in this tile (reset per tile)
};

void rasterizeTile(const Scene& scene, size_t tileIndex, RastScratch& scratch, PipelineStats& stats);

struct TileRect {
  int32_t x0, y0, x1, y1;  // inclusive
};

// The provenance-mode triangle walk (rast_provenance.cpp): same coverage, depth and shading as the
// fast path, plus near-miss pixels, three program runs per quad (lower bound, upper bound, value)
// and interval bookkeeping in the targets' Provenance images.
void rasterizeTriangleProvenance(const Scene& scene, const TriSetup& t, const TileRect& tile, PipelineStats& stats);

// Interpolation of one pixel (GL 4.6 §14.6.1) from its exact edge values e[i] (opposite vertex i):
// perspective-correct varyings b_i = (e_i / w_i) / sum, each rounded to float once, and depth without
// perspective, z = sum(e_i z_i) / 2A. These three steps are the only place the arithmetic is spelled;
// the per-pixel form (interpolatePixel, used by the provenance path) and the quad form of the fast
// path both call them, so their values are the same bytes by construction (helper pixels
// extrapolate the same way).
//
// A NaN result is the canonical quiet NaN (docs/spec-choices.md R5): which NaN an IEEE operation
// returns for NaN operands depends on their order, and compilers and SIMD kernels may swap the operands
// of a commutative operation, so NaN bits would otherwise depend on the build and the SIMD target.
inline float canonicalNaN(float v) { return v != v ? std::numeric_limits<float>::quiet_NaN() : v; }

inline double pixelDepthWide(const TriSetup& t, const int64_t (&e)[3]) {
  const double ed[3] = {double(e[0]), double(e[1]), double(e[2])};
  return (ed[0] * t.z[0] + ed[1] * t.z[1] + ed[2] * t.z[2]) / double(t.area2);
}

inline float pixelDepth(const TriSetup& t, const int64_t (&e)[3]) { return canonicalNaN(float(pixelDepthWide(t, e))); }

inline void pixelBarycentrics(const TriSetup& t, const int64_t (&e)[3], double (&b)[3]) {
  const double w0 = double(e[0]) * t.invW[0], w1 = double(e[1]) * t.invW[1], w2 = double(e[2]) * t.invW[2];
  const double sum = w0 + w1 + w2;
  b[0] = w0 / sum, b[1] = w1 / sum, b[2] = w2 / sum;
}

inline double pixelVaryingWide(const TriSetup& t, const double (&b)[3], int k) {
  return b[0] * t.var[0][k] + b[1] * t.var[1][k] + b[2] * t.var[2][k];
}

inline float pixelVarying(const TriSetup& t, const double (&b)[3], int k) {
  return canonicalNaN(float(pixelVaryingWide(t, b, k)));
}

inline float interpolatePixel(const TriSetup& t, int varyings, const int64_t (&e)[3], float* var) {
  double b[3];
  pixelBarycentrics(t, e, b);
  for (int k = 0; k < varyings; ++k) var[k] = pixelVarying(t, b, k);
  return pixelDepth(t, e);
}

// The quad form, split so the early depth test runs before the varyings are computed (a quad that
// fails depth entirely never pays for them). The loops run over the four pixels, so a compiler may
// put them in SIMD lanes; lane-wise IEEE operations give the scalar bits (no reassociation or
// contraction: -ffp-contract=off, no -ffast-math). tests/raster/test_interpolate_quad.cpp compares.
inline void interpolateQuadDepth(const TriSetup& t, const int64_t (&e)[4][3], float z[4]) {
  for (int p = 0; p < 4; ++p) z[p] = pixelDepth(t, e[p]);
}

inline void interpolateQuadVaryings(const TriSetup& t, int varyings, const int64_t (&e)[4][3],
                                    float (*var)[kMaxVaryings]) {
  double b[4][3];
  for (int p = 0; p < 4; ++p) pixelBarycentrics(t, e[p], b[p]);
  for (int k = 0; k < varyings; ++k)
    for (int p = 0; p < 4; ++p) var[p][k] = pixelVarying(t, b[p], k);
}

// The number of pixels in a quad mask (bits 0-3). std::popcount is a library call on baseline
// x86-64 (no POPCNT), and the counters take it several times per quad.
inline uint64_t quadPixels(uint32_t mask) {
  static constexpr uint8_t kCount[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};
  return kCount[mask & 0xf];
}

// The number of set bits of a 64-bit mask (an 8x8 block's coverage), inline: std::popcount is a call
// to libgcc's __popcountdi2 on baseline x86-64, which cost 3 % of a flat fill's visibility walk.
inline uint64_t popcount64(uint64_t x) {
  x -= (x >> 1) & 0x5555555555555555u;
  x = (x & 0x3333333333333333u) + ((x >> 2) & 0x3333333333333333u);
  x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0fu;
  return (x * 0x0101010101010101u) >> 56;
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
