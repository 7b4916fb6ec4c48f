// Internal to the sampler; not a public header. Other modules include raster/sample.h.
//
// Implements: what the three files of the sampler share: raster/sample.cpp (exact lookups: level
// planning, wrap, filtering, layer selection, buffer fetches), raster/sample_lod.cpp (lambda:
// GL 4.6 §8.14.1) and raster/sample_interval.cpp (provenance mode: the legal [lo, hi] bounds of a
// lookup). That is the per-quad lookup plan, the integer rounding helpers, the grid lookups that
// provenance mode's coordinate alternatives use (sampleBlendedGrid, with its memo of level grids),
// and the entry points each file offers the others.
// Does not implement: the per-pixel filter (sample.cpp keeps its per-format templates local, so the
// per-pixel path stays inside one translation unit) or the tolerances (raster/tolerances.h).
#pragma once

#include <cstdint>

#include "raster/limits.h"
#include "raster/sample.h"
#include "raster/types.h"

namespace tessera::sample_detail {

constexpr uint32_t kLevelWeightOne = 1u << kLodFracBits;  // 256: one 8-bit mip blend weight

// floor(x) as an integer for |x| < 2^62, without libm (std::floor is a library call on baseline
// x86-64 and would dominate the per-tap cost).
inline int64_t floorToInt(double x) {
  int64_t t = int64_t(x);  // truncation toward zero, exact for |x| < 2^63
  if (double(t) > x) --t;
  return t;
}

// Round half to even of x (|x| < 2^62) to an integer, independent of the FP rounding mode.
inline int64_t roundHalfEven(double x) {
  int64_t f = floorToInt(x);
  // d is exact unless -1/2 < x < 0, where rounding can only move it towards 1, never across 1/2.
  const double d = x - double(f);
  if (d > 0.5 || (d == 0.5 && (f & 1) != 0)) ++f;
  return f;
}

struct LevelRef {
  const uint8_t* data = nullptr;  // layer 0 of the level
  uint64_t layerStride = 0;       // bytes per layer
  int32_t w = 0, h = 0;
  float fw = 0.0f, fh = 0.0f;  // w, h as float (exact: <= 16384)
};

// Everything about a lookup that does not depend on the pixel.
struct Plan {
  bool complete = false;
  bool linear = false;  // texel filter within a level: LINEAR (true) or NEAREST
  Wrap wrapS = Wrap::Repeat, wrapT = Wrap::Repeat;
  uint32_t lastLayer = 0;
  int levelCount = 0;  // 1 or 2
  LevelRef lv[2];
  uint32_t levelWeight[2] = {kLevelWeightOne, 0};  // sums to 256
  // The border texel, stored like a texel of the texture (GL 4.6 §8.14.2: the border colour is
  // "interpreted as an RGBA color to match the texture's internal format"; fixed-point components
  // are clamped to [0, 1]). unorm8 borders are quantized to 8 bits (round half to even of c * 255)
  // so that filtering stays in exact integers; float borders are stored as given; R32UI stores the
  // bits of borderColor[0] (what a float border set with glSamplerParameterfv becomes when read as
  // an integer, as in Mesa). A border tap then reads this texel like any other.
  alignas(16) uint8_t border[16] = {};
};

// sample.cpp: the plan of a lookup at lambda (8.8): completeness, filter, levels and their weights,
// border texel. In provenance mode the levels of a rendered texture are read through its lower or
// upper interval image, as shadeProvenance().bound says.
// magSwitch8: the mag/min switch point c in 8.8 (GL 4.6 §8.14: 0, or 1/2 = 128 for mag LINEAR with min
// NEAREST_MIPMAP_*; the oracle uses 0, provenance also tries 128 where it is legal).
Plan makePlan(const TexUnit& u, int32_t lambda8, int32_t magSwitch8 = 0);

// sample.cpp: n lookups sharing one plan (out[i] = RGBA of lookup i); an incomplete plan gives
// (0, 0, 0, 1).
void sampleN(const TexUnit& u, const Plan& p, int n, const float* s, const float* t, const uint32_t* layers,
             float (*out)[4]);

// sample.cpp: one lookup (out = the value sampleN gives) and the channels (bit c, the result) in which
// its unorm filter gave weight to texels of different values with a weight not in {0, 1}, i.e. where
// the filter's arithmetic can round (FILTER_PRECISION, docs/crosscheck.md). The mask is 0 where every
// weight is 0 or 1, where the weighted texels are equal, and for formats other than unorm. One pass:
// the filter records the taps it weighs. Provenance mode asks both of every alternative.
uint32_t sampleBlended(const TexUnit& u, const Plan& p, float s, float t, uint32_t layer, float out[4]);

// sample.cpp: sampleBlended at every point (s[a], t[b]) of one plan and layer, a < ns, b < nt, each at
// most kGridMax: out[a * nt + b] and mask[a * nt + b]. The same bits as sampleBlended point by point
// (tests/raster/test_sample_grid.cpp); the texel index, wrap and weight along each axis are found once
// per coordinate and level instead of once per point. Provenance mode's coordinate alternatives are
// such a grid (sample_interval.cpp).
//
// memo (optional) keeps the last few level grids: the plans of one pass that share a level at the same
// coordinates (a trilinear pair at several weights, a single level and a pair ending in it) compute
// it once. Valid only while the unit, its sampler and shadeProvenance().bound stay the same: a pass
// calls begin() first.
constexpr int kGridMax = 8;
// One level's filter at every grid point without its level weight: the sum of texel x weight (weights
// summing to 2^16, exact in uint32), the byte range of the taps given weight, whether a weight was
// fractional. The key is the level's texels, the layer, the texel filter and the coordinates.
struct LevelGrid {
  const uint8_t* data;
  uint32_t layer;
  bool linear;
  int ns, nt;
  float s[kGridMax], t[kGridMax];
  uint32_t sum[kGridMax * kGridMax][4];
  uint8_t lo[kGridMax * kGridMax][4], hi[kGridMax * kGridMax][4];
  bool fractional[kGridMax * kGridMax];
};
struct GridMemo {
  static constexpr int kEntries = 4;
  LevelGrid e[kEntries];
  int n = 0, next = 0;
  uint64_t hits = 0;  // grids taken from the memo (tests)
  void begin() { n = next = 0; }
};
void sampleBlendedGrid(const TexUnit& u, const Plan& p, const float* s, int ns, const float* t, int nt,
                       uint32_t layer, float (*out)[4], uint32_t* mask, GridMemo* memo = nullptr);

// sample_lod.cpp: lambda' and lambda from lambda_base (8.8): GL 4.6 §8.14.1, eq. 8.6 - 8.8.
int32_t finishLambda(int32_t base, const SamplerQ& s, float shaderBias);

// sample_lod.cpp: lambda_base (8.8) of rho^2; NaN / Inf give kLodMax, 0 gives kLodMinusInf.
int32_t lambdaBaseFromRho2(double rho2);

// sample_lod.cpp, for tests: the first `steps` bits of log2(m), m in [1, 2) as Q1.62, from the
// bit-by-bit loop of log2Fixed, and the 8 bits of lambda from its threshold table (equal by
// construction).
int64_t log2BitsLoop(uint64_t m, int steps);
int64_t log2BitsTable(uint64_t m);

// sample_interval.cpp: a quad lookup in provenance mode. Each pixel's interval over the legal
// alternatives; out = its lower or upper bound, as shadeProvenance().bound says, and the classes of
// the freedoms that widened it are ORed into shadeProvenance().classes. r: array layer coordinates
// or nullptr (2D); grad: {dsdx, dtdx, dsdy, dtdy} of textureGrad or nullptr (implicit derivatives).
// Precondition: the texture is complete.
void sampleQuadInterval(const TexUnit& u, const float s[4], const float t[4], const float* r, float bias,
                        const double* grad, float out[4][4]);

}  // namespace tessera::sample_detail
