// Exact texture lookups of the oracle (see sample.h for the rules; this file says why and where GL
// says so). Lambda is computed in sample_lod.cpp; the interval lookups of provenance mode are in
// sample_interval.cpp, which reuses makePlan() and sampleN() through sample_detail.h.
//
// Structure: a lookup is split into a per-quad "plan" (completeness, lambda -> filter, levels and
// level weights, border texel in the storage domain) and a per-pixel filter templated on the format,
// so the per-pixel path has no allocation, no virtual call and no format switch.
//
// Weights: every lookup is a sum of texels times integer weights whose total is 2^24:
// 8-bit mip blend (256) x 8-bit alpha (256) x 8-bit beta (256). NEAREST uses one tap of weight
// 2^16 per level. unorm8 sums are exact integers (< 255 * 2^24 < 2^32) converted to float once;
// float texels times integer weights are exact in double, summed in a fixed order, scaled by 2^-24
// (exact) and rounded to float once.
#include "raster/sample.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "raster/lod_probe.h"
#include "raster/provenance.h"
#include "raster/round.h"
#include "raster/sample_detail.h"
#include "raster/sample_simd.h"
#include "raster/stage_times.h"

namespace tessera {

using sample_detail::floorToInt;
using sample_detail::kLevelWeightOne;
using sample_detail::LevelRef;
using sample_detail::makePlan;
using sample_detail::Plan;
using sample_detail::roundHalfEven;
using sample_detail::sampleN;
using sample_detail::sampleQuadInterval;

namespace {

constexpr uint32_t kWeightOne = 1u << kSubtexelBits;        // 256: one 8-bit weight
constexpr double kTotalWeight = 16777216.0;                 // 2^24 = 256^3
static_assert(kUnormDenominator == 255.0 * kTotalWeight);   // raster/round.h
// Texel-space coordinates are clamped to +-2^52 before conversion to int64 (2^52 * 256 < 2^63).
// Floats of that magnitude are multiples of 2^29, far beyond any meaningful coordinate.
constexpr float kCoordLimit = 4503599627370496.0f;  // 2^52
// Below this magnitude a coordinate needs neither the NaN test nor the clamps, and 256 u rounds with
// roundHalfEvenNear (|256 u| <= 2^48): one compare per tap instead of the guards (NaN fails it).
constexpr float kCoordFast = 1099511627776.0f;  // 2^40

// GL 4.6 §8.17 texture completeness, and §11.1.3.5: sampling an incomplete texture returns
// (0, 0, 0, 1). An integer-format texture is incomplete unless the mag filter is NEAREST and the
// min filter is NEAREST or NEAREST_MIPMAP_NEAREST. A mipmap min filter on a texture whose storage
// has one level is complete (immutable storage clamps the max level to levels - 1).
bool isComplete(const TextureData* tex, const SamplerState& s) {
  if (tex == nullptr) return false;
  const TextureDesc& d = tex->desc;
  if (d.kind == TextureKind::Buffer) return false;  // only texelFetch (fetchBuffer) reads buffers
  if (d.width == 0 || d.height == 0 || d.layers == 0 || d.levels == 0 || tex->levels.empty()) return false;
  if (isInteger(d.format)) {
    if (s.magFilter != Filter::Nearest) return false;
    if (s.minFilter != Filter::Nearest && s.minFilter != Filter::NearestMipmapNearest) return false;
  }
  return true;
}

inline void writeIncomplete(float out[4]) {
  out[0] = 0.0f;
  out[1] = 0.0f;
  out[2] = 0.0f;
  out[3] = 1.0f;
}

LevelRef levelRef(const TextureData& tex, uint32_t level) {
  // levelWidth()/levelHeight() inlined: max(1, size >> level).
  LevelRef r;
  const uint32_t w = level < 32 ? tex.desc.width >> level : 0, h = level < 32 ? tex.desc.height >> level : 0;
  r.w = int32_t(w > 0 ? w : 1);
  r.h = int32_t(h > 0 ? h : 1);
  r.fw = float(r.w);
  r.fh = float(r.h);
  r.layerStride = uint64_t(r.w) * uint32_t(r.h) * texelBytes(tex.desc.format);
  r.data = tex.levels[level].data();
  // In provenance mode a rendered texture is read through its lower / upper interval images, so a
  // lookup of texels that are themselves intervals is bounded too (filtering has non-negative
  // weights, hence is monotone in every texel).
  if (tex.prov) {
    const SampleBound b = shadeProvenance().bound;
    if (b == SampleBound::Lo) r.data = tex.prov->lo->levels[level].data();
    if (b == SampleBound::Hi) r.data = tex.prov->hi->levels[level].data();
  }
  return r;
}

}  // namespace

namespace sample_detail {

Plan makePlan(const TexUnit& u, int32_t lambda8, int32_t magSwitch8) {
  Plan p;
  const SamplerState& s = u.sampler.state;
  if (!isComplete(u.tex, s)) return p;
  const TextureData& tex = *u.tex;
  p.complete = true;
  p.wrapS = s.wrapS;
  p.wrapT = s.wrapT;
  p.lastLayer = tex.desc.layers - 1;
  // q: the last level of the storage (GL 4.6 §8.14.3 with level_base = 0, level_max = levels - 1).
  // The sampler's maxLod needs no separate clamp: lambda <= maxLod already bounds the levels chosen
  // below, and the one level it could add (d1 + 1 when lambda == maxLod is an integer) gets weight 0.
  const uint32_t storedLevels = tex.desc.levels < tex.levels.size() ? tex.desc.levels : uint32_t(tex.levels.size());
  const int32_t q = int32_t(storedLevels) - 1;

  int32_t d1 = 0, d2 = 0;
  uint32_t frac = 0;  // weight of d2, 0..255
  if (lambda8 <= magSwitch8) {
    // GL 4.6 §8.15: magnification iff lambda <= c, with c = 0 (docs/spec-choices.md T4; llvmpipe's choice).
    // The base level with the mag filter.
    p.linear = s.magFilter == Filter::Linear;
  } else {
    switch (s.minFilter) {
      case Filter::Nearest:
      case Filter::Linear:
        // GL 4.6 §8.14.2: a non-mipmapped min filter uses level_base.
        p.linear = s.minFilter == Filter::Linear;
        break;
      case Filter::NearestMipmapNearest:
      case Filter::LinearMipmapNearest: {
        // GL 4.6 §8.14.3: d = base if lambda <= 1/2, else base + ceil(lambda + 1/2) - 1,
        // clamped to q. In 8.8: ceil((lambda8 + 128) / 256) - 1 with lambda8 > 128 > 0.
        p.linear = s.minFilter == Filter::LinearMipmapNearest;
        const int32_t d = lambda8 <= 128 ? 0 : ((lambda8 + 128 + 255) >> 8) - 1;
        d1 = d2 = d < q ? d : q;
        break;
      }
      case Filter::NearestMipmapLinear:
      case Filter::LinearMipmapLinear:
      default: {
        // GL 4.6 §8.14.3: d1 = base + floor(lambda), d2 = d1 + 1, both clamped to q; the blend
        // weight of d2 is frac(lambda), here exactly the 8 fractional bits of lambda8.
        p.linear = s.minFilter == Filter::LinearMipmapLinear;
        const int32_t f = lambda8 >> 8;
        d1 = f < q ? f : q;
        d2 = f + 1 < q ? f + 1 : q;
        frac = uint32_t(lambda8 & 0xff);
        break;
      }
    }
  }
  p.lv[0] = levelRef(tex, uint32_t(d1));
  // A blend with weight 0, or of a level with itself, is the single-level result: sample once.
  // (Exact for unorm8; for floats it avoids 0 * Inf from an unused level.)
  if (d2 != d1 && frac != 0) {
    p.levelCount = 2;
    p.lv[1] = levelRef(tex, uint32_t(d2));
    p.levelWeight[0] = kLevelWeightOne - frac;
    p.levelWeight[1] = frac;
  } else {
    p.levelCount = 1;
    p.levelWeight[0] = kLevelWeightOne;
  }

  // The border texel is read only through CLAMP_TO_BORDER (texelPtr); other plans skip making it.
  const Format fmt = tex.desc.format;
  if (p.wrapS != Wrap::ClampToBorder && p.wrapT != Wrap::ClampToBorder) return p;
  if (isUnorm(fmt)) {
    for (int c = 0; c < channelCount(fmt); ++c) {
      const float b = s.borderColor[size_t(c)];
      const double cl = std::isnan(b) ? 0.0 : (b < 0.0f ? 0.0 : (b > 1.0f ? 1.0 : double(b)));
      p.border[c] = uint8_t(roundHalfEven(cl * 255.0));  // 0..255
    }
  } else if (isFloat(fmt)) {
    std::memcpy(p.border, s.borderColor.data(), size_t(channelCount(fmt)) * sizeof(float));
  } else {
    std::memcpy(p.border, &s.borderColor[0], sizeof(float));
  }
  return p;
}

}  // namespace sample_detail

namespace {

// --- per-format texel access ---------------------------------------------------------------------

template <Format F>
struct Fmt;
template <>
struct Fmt<Format::RGBA8> {
  static constexpr int kChannels = 4;
  static constexpr bool kUnorm = true;
};
template <>
struct Fmt<Format::R8> {
  static constexpr int kChannels = 1;
  static constexpr bool kUnorm = true;
};
template <>
struct Fmt<Format::RG32F> {
  static constexpr int kChannels = 2;
  static constexpr bool kUnorm = false;
};
template <>
struct Fmt<Format::RGBA32F> {
  static constexpr int kChannels = 4;
  static constexpr bool kUnorm = false;
};
template <>
struct Fmt<Format::D32F> {
  static constexpr int kChannels = 1;
  static constexpr bool kUnorm = false;
};

// Accumulators: unorm8 sums are exact in uint32 (at most 255 * 2^24 < 2^32); float sums in double.
template <Format F>
using Acc = std::conditional_t<Fmt<F>::kUnorm, uint32_t, double>;

inline float loadF32(const uint8_t* p) {
  float v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// An unorm lookup's value from its exact sum (total weight 255 x 2^24): the one conversion to float,
// acc / (255 * 2^24) as a multiply that gives the division's float (raster/round.h says why).
inline float unormFromSum(uint32_t acc) { return float(double(acc) * kUnormReciprocal); }

// Channel c of a texel in the accumulator domain (a float is exact in double).
template <Format F>
inline Acc<F> channel(const uint8_t* texel, int c) {
  if constexpr (Fmt<F>::kUnorm) {
    return texel[c];
  } else {
    return double(loadF32(texel + 4 * c));
  }
}

// NEAREST texel index (GL 4.6 §8.14.2: i = floor(u)). NaN coordinates are treated as 0 (GL leaves
// them undefined); the clamp keeps the int64 conversion defined.
inline int64_t nearestIndex(float u) {
  if (std::fabs(u) <= kCoordFast) return floorToInt(double(u));
  if (std::isnan(u)) return 0;
  if (u < -kCoordLimit) u = -kCoordLimit;
  if (u > kCoordLimit) u = kCoordLimit;
  return floorToInt(double(u));
}

// LINEAR: i0 = floor(u - 1/2), alpha = frac(u - 1/2) rounded half to even to 8 bits
// (GL 4.6 §8.14.2, LINEAR; 8-bit subtexel precision as D3D / llvmpipe's AoS path).
// Computed as U = round_half_even(256 * u) - 128 (256 * u is exact in double), then i0 = U >> 8 and
// alpha8 = U & 255. This equals the rule above; when alpha rounds up to 256 the carry moves to i0,
// which gives the same filtered value (the full weight lands on the same texel).
inline int64_t linearFixed(float u) {
  if (std::fabs(u) <= kCoordFast) return roundHalfEvenNear(double(u) * 256.0) - 128;  // same value
  if (std::isnan(u)) u = 0.0f;
  if (u < -kCoordLimit) u = -kCoordLimit;
  if (u > kCoordLimit) u = kCoordLimit;
  return roundHalfEven(double(u) * 256.0) - 128;  // |256 u| <= 2^60
}

// Mathematical i mod n for n > 0. The sizes of power-of-two textures take a mask (two's complement
// makes it right for negative i too); others a 32-bit division when i fits, which is the common case.
inline int64_t floorMod(int64_t i, int64_t n) {
  if ((n & (n - 1)) == 0) return i & (n - 1);
  int64_t m;
  if (i >= INT32_MIN && i <= INT32_MAX && n <= INT32_MAX) {
    m = int32_t(i) % int32_t(n);
  } else {
    m = i % n;
  }
  return m < 0 ? m + n : m;
}

// GL 4.6 §8.14.2 Table 8.20 (wrapCoord() is the public name). Returns -1 for a border texel.
inline int32_t wrapIndex(Wrap w, int64_t i, int32_t size) {
  if (size <= 0) return -1;
  switch (w) {
    case Wrap::Repeat:  // i mod size
      return int32_t(floorMod(i, size));
    case Wrap::MirroredRepeat: {
      // (size - 1) - mirror((i mod 2 size) - size), mirror(a) = a >= 0 ? a : -(1 + a)
      const int64_t a = floorMod(i, int64_t(2) * size) - size;
      const int64_t mir = a >= 0 ? a : -(1 + a);
      return int32_t(size - 1 - mir);
    }
    case Wrap::ClampToEdge:  // clamp(i, 0, size - 1)
      return int32_t(i < 0 ? 0 : (i >= size ? size - 1 : i));
    case Wrap::ClampToBorder:  // clamp(i, -1, size); -1 and size are the border texel
    default:
      return (i < 0 || i >= size) ? -1 : int32_t(i);
  }
}

// The wrapped pair (i0, i0 + 1) of a LINEAR footprint. REPEAT derives the second from the first
// (one modulo instead of two); the result is the same as two wrapIndex() calls.
inline void wrapPair(Wrap w, int64_t i0, int32_t size, int32_t& w0, int32_t& w1) {
  if (w == Wrap::Repeat && size > 0) {
    w0 = int32_t(floorMod(i0, size));
    w1 = w0 + 1 == size ? 0 : w0 + 1;
    return;
  }
  w0 = wrapIndex(w, i0, size);
  w1 = wrapIndex(w, i0 + 1, size);
}

inline const uint8_t* texelPtr(const Plan& p, const uint8_t* layerBase, const LevelRef& L, int32_t i, int32_t j,
                               uint32_t bpt) {
  if (i < 0 || j < 0) return p.border;  // CLAMP_TO_BORDER outside the image
  return layerBase + (uint64_t(j) * uint32_t(L.w) + uint32_t(i)) * bpt;
}

// texelPtr for a filter that knows at compile time whether a wrap mode is CLAMP_TO_BORDER: without
// one, wrapIndex never gives -1 and the border test is dropped.
template <bool kBorder>
inline const uint8_t* texelAt(const Plan& p, const uint8_t* layerBase, const LevelRef& L, int32_t i, int32_t j,
                              uint32_t bpt) {
  if constexpr (kBorder) {
    return texelPtr(p, layerBase, L, i, j, bpt);
  } else {
    return layerBase + (uint64_t(uint32_t(j)) * uint32_t(L.w) + uint32_t(i)) * bpt;
  }
}

// Adds one level's filtered value times `levelW` (total weight levelW * 2^16) to acc. Each level is
// summed in locals first (a uint8_t texel pointer may alias anything, which would otherwise keep
// acc[] in memory); float sums are ((t00 w00 + t10 w10) + t01 w01) + t11 w11 per level, then
// level d1 + level d2, in this fixed order. Every float x integer-weight (<= 2^24) product is exact.
// The taps a lookup gave a non-zero weight, and whether any weight is fractional (not 0 or 1): what
// sampleBlended needs, recorded by the filter itself so provenance mode does not redo the lookup.
struct TapLog {
  const uint8_t* taps[8];
  int n = 0;
  bool fractional = false;
};

template <Format F, bool kBorder, bool kLog = false>
inline void accumulateLevel(const Plan& p, const LevelRef& L, float s, float t, uint32_t layer, uint32_t levelW,
                            Acc<F> acc[4], TapLog* log = nullptr) {
  constexpr uint32_t bpt = texelBytes(F);
  constexpr int C = Fmt<F>::kChannels;
  const uint8_t* base = L.data + layer * L.layerStride;
  // GL 4.6 §8.14.2: u = s * w_level, v = t * h_level, in float32 (docs/spec-choices.md T7).
  const float u = s * L.fw;
  const float v = t * L.fh;
  if (!p.linear) {
    const int32_t i = wrapIndex(p.wrapS, nearestIndex(u), L.w);
    const int32_t j = wrapIndex(p.wrapT, nearestIndex(v), L.h);
    const uint8_t* tx = texelAt<kBorder>(p, base, L, i, j, bpt);
    if constexpr (kLog) log->taps[log->n++] = tx;
    const Acc<F> w = Acc<F>(levelW * kWeightOne * kWeightOne);
    for (int c = 0; c < C; ++c) acc[c] += channel<F>(tx, c) * w;
    return;
  }
  const int64_t U = linearFixed(u), V = linearFixed(v);
  const uint32_t a = uint32_t(U & 0xff), b = uint32_t(V & 0xff);
  const int64_t i0 = U >> 8, j0 = V >> 8;  // arithmetic shift = floor division by 256
  int32_t wi0, wi1, wj0, wj1;
  wrapPair(p.wrapS, i0, L.w, wi0, wi1);
  wrapPair(p.wrapT, j0, L.h, wj0, wj1);
  const uint8_t* t00 = texelAt<kBorder>(p, base, L, wi0, wj0, bpt);
  const uint8_t* t10 = texelAt<kBorder>(p, base, L, wi1, wj0, bpt);
  const uint8_t* t01 = texelAt<kBorder>(p, base, L, wi0, wj1, bpt);
  const uint8_t* t11 = texelAt<kBorder>(p, base, L, wi1, wj1, bpt);
  if constexpr (kLog) {
    log->fractional = log->fractional || a != 0 || b != 0;
    log->taps[log->n++] = t00;
    if (a != 0) log->taps[log->n++] = t10;
    if (b != 0) log->taps[log->n++] = t01;
    if (a != 0 && b != 0) log->taps[log->n++] = t11;
  }
  const uint32_t na = kWeightOne - a, nb = kWeightOne - b;
  // tau = (1-a)(1-b) t00 + a(1-b) t10 + (1-a) b t01 + a b t11 (GL 4.6 §8.14.2; rr's term order).
  const Acc<F> w00 = Acc<F>(na * nb * levelW), w10 = Acc<F>(a * nb * levelW);
  const Acc<F> w01 = Acc<F>(na * b * levelW), w11 = Acc<F>(a * b * levelW);
  for (int c = 0; c < C; ++c) {
    Acc<F> sum = channel<F>(t00, c) * w00;
    sum += channel<F>(t10, c) * w10;
    sum += channel<F>(t01, c) * w01;
    sum += channel<F>(t11, c) * w11;
    acc[c] += sum;
  }
}

// One filtered lookup with a plan; expands to RGBA per GL 4.6 §15.2.1 Table 15.1
// (R -> (r, 0, 0, 1), RG -> (r, g, 0, 1), depth without compare -> (d, 0, 0, 1)).
template <Format F, bool kBorder, bool kLog = false>
inline void samplePlanned(const Plan& p, float s, float t, uint32_t layer, float out[4], TapLog* log = nullptr) {
  constexpr int C = Fmt<F>::kChannels;
  if (layer > p.lastLayer) layer = p.lastLayer;  // defensive: callers pass a selected layer
  Acc<F> acc[4] = {0, 0, 0, 0};
  accumulateLevel<F, kBorder, kLog>(p, p.lv[0], s, t, layer, p.levelWeight[0], acc, log);
  if (p.levelCount == 2) accumulateLevel<F, kBorder, kLog>(p, p.lv[1], s, t, layer, p.levelWeight[1], acc, log);
  for (int c = 0; c < C; ++c) {
    if constexpr (Fmt<F>::kUnorm) {
      out[c] = unormFromSum(acc[c]);  // the one conversion to float
    } else {
      out[c] = float(acc[c] * (1.0 / kTotalWeight));  // exact scaling, then one rounding
    }
  }
  for (int c = C; c < 4; ++c) out[c] = c == 3 ? 1.0f : 0.0f;
}

// R32UI: integer textures are only ever point-sampled (completeness guarantees NEAREST filters).
inline void samplePlannedUint(const Plan& p, float s, float t, uint32_t layer, float out[4]) {
  if (layer > p.lastLayer) layer = p.lastLayer;
  const LevelRef& L = p.lv[0];
  const int32_t i = wrapIndex(p.wrapS, nearestIndex(s * L.fw), L.w);
  const int32_t j = wrapIndex(p.wrapT, nearestIndex(t * L.fh), L.h);
  uint32_t v;
  std::memcpy(&v, texelPtr(p, L.data + layer * L.layerStride, L, i, j, 4), 4);
  out[0] = float(v);
  out[1] = 0.0f;
  out[2] = 0.0f;
  out[3] = 1.0f;
}

// n lookups of format F sharing one plan, with the border test compiled in only where a wrap mode
// is CLAMP_TO_BORDER.
template <Format F>
inline void sampleEach(bool border, const Plan& p, int n, const float* s, const float* t, const uint32_t* layers,
                       float (*out)[4]) {
  if (border) {
    for (int i = 0; i < n; ++i) samplePlanned<F, true>(p, s[i], t[i], layers[i], out[i]);
  } else {
    for (int i = 0; i < n; ++i) samplePlanned<F, false>(p, s[i], t[i], layers[i], out[i]);
  }
}

// The RGBA8 quad kernel of the running SIMD target (raster/sample_simd.h), resolved once per tile by
// bindSampleKernels() (a dispatch is a call into libhwy); outside a tile, resolved per call.
constinit thread_local sample_simd::Rgba8LinearFn t_rgba8Kernel = nullptr;
constinit thread_local bool t_rgba8KernelSet = false;

}  // namespace

namespace sample_detail {

// n lookups sharing one plan; one format dispatch and one border choice for all of them.
void sampleN(const TexUnit& u, const Plan& p, int n, const float* s, const float* t, const uint32_t* layers,
             float (*out)[4]) {
  if (!p.complete) {
    for (int i = 0; i < n; ++i) writeIncomplete(out[i]);
    return;
  }
  const bool border = p.wrapS == Wrap::ClampToBorder || p.wrapT == Wrap::ClampToBorder;
  switch (u.tex->desc.format) {
    case Format::RGBA8:
      // A quad's LINEAR lookups in one layer go to the SIMD kernel (raster/sample_simd.h: same bits),
      // which declines what it does not take.
      if (n == 4 && p.linear && !border && layers[0] == layers[1] && layers[0] == layers[2] &&
          layers[0] == layers[3]) {
        const sample_simd::Rgba8LinearFn kernel = t_rgba8KernelSet ? t_rgba8Kernel : sample_simd::rgba8LinearKernel();
        if (kernel && kernel(p, layers[0] > p.lastLayer ? p.lastLayer : layers[0], s, t, 4, nullptr, nullptr, out))
          return;
      }
      return sampleEach<Format::RGBA8>(border, p, n, s, t, layers, out);
    case Format::R8: return sampleEach<Format::R8>(border, p, n, s, t, layers, out);
    case Format::RG32F: return sampleEach<Format::RG32F>(border, p, n, s, t, layers, out);
    case Format::RGBA32F: return sampleEach<Format::RGBA32F>(border, p, n, s, t, layers, out);
    case Format::D32F: return sampleEach<Format::D32F>(border, p, n, s, t, layers, out);
    case Format::R32UI:
      for (int i = 0; i < n; ++i) samplePlannedUint(p, s[i], t[i], layers[i], out[i]);
      break;
    default:
      for (int i = 0; i < n; ++i) writeIncomplete(out[i]);
      break;
  }
}

namespace {

// The channels (bit c) in which the logged taps differ, where some weight was fractional.
inline uint32_t differingChannels(const TapLog& log, int channels) {
  if (!log.fractional) return 0;
  uint32_t mask = 0;
  for (int c = 0; c < channels; ++c)
    for (int i = 1; i < log.n; ++i)
      if (log.taps[i][c] != log.taps[0][c]) mask |= 1u << c;
  return mask;
}

template <Format F>
uint32_t sampleLogged(const Plan& p, float s, float t, uint32_t layer, float out[4]) {
  TapLog log;
  log.fractional = p.levelCount == 2;  // makePlan keeps a second level only with weight in (0, 1)
  if (p.wrapS == Wrap::ClampToBorder || p.wrapT == Wrap::ClampToBorder) {
    samplePlanned<F, true, true>(p, s, t, layer, out, &log);
  } else {
    samplePlanned<F, false, true>(p, s, t, layer, out, &log);
  }
  return differingChannels(log, Fmt<F>::kChannels);
}

}  // namespace

uint32_t sampleBlended(const TexUnit& u, const Plan& p, float s, float t, uint32_t layer, float out[4]) {
  if (p.complete) {
    switch (u.tex->desc.format) {
      case Format::RGBA8: return sampleLogged<Format::RGBA8>(p, s, t, layer, out);
      case Format::R8: return sampleLogged<Format::R8>(p, s, t, layer, out);
      default: break;
    }
  }
  float v[1][4];
  sampleN(u, p, 1, &s, &t, &layer, v);
  for (int c = 0; c < 4; ++c) out[c] = v[0][c];
  return 0;
}

namespace {

// One axis of one level at one coordinate, as accumulateLevel finds it: the wrapped texel indices
// (-1 = border) and, for LINEAR, the 8-bit weight of the second.
struct AxisTap {
  int32_t i0 = 0, i1 = 0;
  uint32_t w = 0;
};

inline AxisTap axisTap(const Plan& p, Wrap wrap, float x, float scale, int32_t size) {
  AxisTap a;
  const float u = x * scale;  // GL 4.6 §8.14.2, in float32 as accumulateLevel
  if (!p.linear) {
    a.i0 = wrapIndex(wrap, nearestIndex(u), size);
    return a;
  }
  const int64_t U = linearFixed(u);
  a.w = uint32_t(U & 0xff);
  wrapPair(wrap, U >> 8, size, a.i0, a.i1);
  return a;
}

// One row's part of a level's filter at one s coordinate: (256 - a) t0 + a t1 per channel for
// LINEAR (t0 alone for NEAREST), and the byte range of the taps given weight (t1 only if a != 0).
struct RowTerm {
  uint32_t h[4];
  uint8_t lo[4], hi[4];
};

// accumulateLevel<F, kBorder, true> with level weight 1 at every grid point, factored by rows: its
// sum (256-a)(256-b) t00 + a(256-b) t10 + (256-a) b t01 + a b t11 is, in exact uint32 integers (at
// most 255 x 2^16), (256-b) H(j0) + b H(j1) with H(j) = (256-a) t(i0, j) + a t(i1, j), and the grid's
// t coordinates mostly share their rows. The taps logged are accumulateLevel's: t00; t10 if a != 0;
// t01 if b != 0; t11 if both.
template <Format F, bool kBorder>
void gridLevel(const Plan& p, const LevelRef& L, uint32_t layer, const float* s, int ns, const float* t, int nt,
               LevelGrid& g) {
  constexpr uint32_t bpt = texelBytes(F);
  constexpr int C = Fmt<F>::kChannels;
  const uint8_t* base = L.data + layer * L.layerStride;
  AxisTap xs[kGridMax], ys[kGridMax];
  for (int a = 0; a < ns; ++a) xs[a] = axisTap(p, p.wrapS, s[a], L.fw, L.w);
  for (int b = 0; b < nt; ++b) ys[b] = axisTap(p, p.wrapT, t[b], L.fh, L.h);
  // The distinct rows the t coordinates weigh, and each coordinate's one or two of them.
  int32_t rows[2 * kGridMax];
  int nr = 0;
  int rowOf[kGridMax][2];
  auto rowIndex = [&](int32_t j) {
    for (int r = 0; r < nr; ++r)
      if (rows[r] == j) return r;
    rows[nr] = j;
    return nr++;
  };
  for (int b = 0; b < nt; ++b) {
    rowOf[b][0] = rowIndex(ys[b].i0);
    rowOf[b][1] = ys[b].w != 0 ? rowIndex(ys[b].i1) : rowOf[b][0];
  }
  RowTerm rt[kGridMax][2 * kGridMax];
  for (int a = 0; a < ns; ++a) {
    const AxisTap& x = xs[a];
    for (int r = 0; r < nr; ++r) {
      RowTerm& h = rt[a][r];
      const uint8_t* t0 = texelAt<kBorder>(p, base, L, x.i0, rows[r], bpt);
      if (!p.linear || x.w == 0) {
        for (int c = 0; c < C; ++c) h.h[c] = channel<F>(t0, c) * kWeightOne, h.lo[c] = h.hi[c] = t0[c];
        continue;
      }
      const uint8_t* t1 = texelAt<kBorder>(p, base, L, x.i1, rows[r], bpt);
      for (int c = 0; c < C; ++c) {
        h.h[c] = channel<F>(t0, c) * (kWeightOne - x.w) + channel<F>(t1, c) * x.w;
        h.lo[c] = std::min(t0[c], t1[c]), h.hi[c] = std::max(t0[c], t1[c]);
      }
    }
  }
  for (int a = 0; a < ns; ++a)
    for (int b = 0; b < nt; ++b) {
      const int i = a * nt + b;
      const RowTerm& h0 = rt[a][rowOf[b][0]];
      const AxisTap& y = ys[b];
      // NEAREST: h0.h = 256 t, times 256 is accumulateLevel's weight 2^16. LINEAR with b = 0: 256 H(j0).
      if (!p.linear || y.w == 0) {
        g.fractional[i] = p.linear && xs[a].w != 0;
        for (int c = 0; c < C; ++c) g.sum[i][c] = h0.h[c] * kWeightOne, g.lo[i][c] = h0.lo[c], g.hi[i][c] = h0.hi[c];
        continue;
      }
      const RowTerm& h1 = rt[a][rowOf[b][1]];
      const uint32_t nb = kWeightOne - y.w;
      g.fractional[i] = true;
      for (int c = 0; c < C; ++c) {
        g.sum[i][c] = h0.h[c] * nb + h1.h[c] * y.w;
        g.lo[i][c] = std::min(h0.lo[c], h1.lo[c]), g.hi[i][c] = std::max(h0.hi[c], h1.hi[c]);
      }
    }
}

// A level's grid, from the pass's memo when a plan before this one computed it (the key: the level's
// texels, the layer, the texel filter and the coordinates' bits; wrap modes and border are the unit's).
template <Format F>
const LevelGrid& levelGrid(const Plan& p, const LevelRef& L, uint32_t layer, const float* s, int ns, const float* t,
                           int nt, GridMemo* memo, LevelGrid& local, const LevelGrid* keep = nullptr) {
  auto matches = [&](const LevelGrid& g) {
    return g.data == L.data && g.layer == layer && g.linear == p.linear && g.ns == ns && g.nt == nt &&
           std::memcmp(g.s, s, size_t(ns) * sizeof(float)) == 0 && std::memcmp(g.t, t, size_t(nt) * sizeof(float)) == 0;
  };
  LevelGrid* g = &local;
  if (memo) {
    for (int i = 0; i < memo->n; ++i)
      if (matches(memo->e[i])) {
        ++memo->hits;
        return memo->e[i];
      }
    // Round robin, passing over `keep`: the first level's grid, still to be read.
    if (&memo->e[memo->next] == keep) memo->next = (memo->next + 1) % GridMemo::kEntries;
    g = &memo->e[memo->next];
    memo->next = (memo->next + 1) % GridMemo::kEntries;
    memo->n = std::min(memo->n + 1, GridMemo::kEntries);
  }
  g->data = L.data, g->layer = layer, g->linear = p.linear, g->ns = ns, g->nt = nt;
  std::memcpy(g->s, s, size_t(ns) * sizeof(float));
  std::memcpy(g->t, t, size_t(nt) * sizeof(float));
  if (p.wrapS == Wrap::ClampToBorder || p.wrapT == Wrap::ClampToBorder) {
    gridLevel<F, true>(p, L, layer, s, ns, t, nt, *g);
  } else {
    gridLevel<F, false>(p, L, layer, s, ns, t, nt, *g);
  }
  return *g;
}

// samplePlanned's sums, conversion and differingChannels' mask at every grid point: acc = the sum
// over levels of levelWeight x the level's sum (exact uint32: accumulateLevel's integers); a channel
// is blended where some weight was fractional (two levels, or a subtexel weight) and its taps differ.
template <Format F>
void gridUnorm(const Plan& p, const float* s, int ns, const float* t, int nt, uint32_t layer, float (*out)[4],
               uint32_t* mask, GridMemo* memo) {
  constexpr int C = Fmt<F>::kChannels;
  if (layer > p.lastLayer) layer = p.lastLayer;  // as samplePlanned
  LevelGrid local[2];
  const LevelGrid& g0 = levelGrid<F>(p, p.lv[0], layer, s, ns, t, nt, memo, local[0]);
  // makePlan keeps a second level only with weight in (0, 1): with one, every point is fractional.
  const LevelGrid* g1 = p.levelCount == 2 ? &levelGrid<F>(p, p.lv[1], layer, s, ns, t, nt, memo, local[1], &g0) : nullptr;
  const uint32_t w0 = p.levelWeight[0], w1 = p.levelWeight[1];
  for (int i = 0; i < ns * nt; ++i) {
    uint32_t m = 0;
    for (int c = 0; c < C; ++c) {
      uint32_t acc = w0 * g0.sum[i][c];
      uint8_t lo = g0.lo[i][c], hi = g0.hi[i][c];
      if (g1) acc += w1 * g1->sum[i][c], lo = std::min(lo, g1->lo[i][c]), hi = std::max(hi, g1->hi[i][c]);
      out[i][c] = unormFromSum(acc);
      if ((g1 || g0.fractional[i]) && lo != hi) m |= 1u << c;
    }
    for (int c = C; c < 4; ++c) out[i][c] = c == 3 ? 1.0f : 0.0f;
    mask[i] = m;
  }
}

}  // namespace

void sampleBlendedGrid(const TexUnit& u, const Plan& p, const float* s, int ns, const float* t, int nt,
                       uint32_t layer, float (*out)[4], uint32_t* mask, GridMemo* memo) {
  if (p.complete) {
    switch (u.tex->desc.format) {
      case Format::RGBA8: return gridUnorm<Format::RGBA8>(p, s, ns, t, nt, layer, out, mask, memo);
      case Format::R8: return gridUnorm<Format::R8>(p, s, ns, t, nt, layer, out, mask, memo);
      default: break;
    }
  }
  for (int a = 0; a < ns; ++a)
    for (int b = 0; b < nt; ++b) mask[a * nt + b] = sampleBlended(u, p, s[a], t[b], layer, out[a * nt + b]);
}

}  // namespace sample_detail

namespace {

// The LOD probe of the calling thread (raster/lod_probe.h); nullptr unless a probed render is running
// on it. constinit: a plain TLS load, no initialisation wrapper, so the fast path pays one load and one
// predictable branch per quad lookup.
constinit thread_local LodQuadLog* t_lodLog = nullptr;

// Appends one lookup to the probe. rho^2 is formed exactly as computeLambda forms it (same operands,
// same order), so it is the value the lambda came from.
void probeLookup(LodQuadLog& log, const TexUnit& u, double dudx, double dvdx, double dudy, double dvdy,
                 int32_t lambda8, int levels, bool grad) {
  const int i = log.count++;
  if (i >= LodQuadLog::kCapacity) return;
  LodQuadLog::Entry& e = log.e[size_t(i)];
  e.unit = &u;
  e.look = LodLookup{};
  if (u.tex != nullptr) {
    e.look.width = u.tex->desc.width;
    e.look.height = u.tex->desc.height;
    e.look.layers = u.tex->desc.layers;
  }
  const double rx = dudx * dudx + dvdx * dvdx;
  const double ry = dudy * dudy + dvdy * dvdy;
  e.look.rho2 = rx > ry ? rx : ry;
  e.look.lambda8 = lambda8;
  e.look.levels = uint8_t(levels);
  e.look.grad = grad ? 1 : 0;
}

// The last lambda and plan of the calling thread's implicit-LOD lookups, reused by the next quad of the
// same triangle on the same unit. A plan is a function of exactly (unit, lambda8), and lambda8 of
// (unit, rho^2, shader bias); within one triangle of one tile nothing else either reads can change
// (the draw state, its units and their textures are fixed while a tile runs). Two levels: affine
// coordinates give every quad of a triangle the same rho^2, so a fill-bound frame computes one lambda
// and one plan per triangle and tile; under perspective rho^2 changes from quad to quad, but lambda
// is 8.8 fixed point and neighbouring quads mostly share it, so only the plan is kept. The rasterizer
// opens the cache per triangle (beginPlanCache: a new epoch) and closes it after each tile; other
// callers of the sampler (tests, tools) never see it. Provenance mode, whose plans depend on the
// bound being shaded, never opens it.
struct PlanCache {
  bool open = false;
  uint64_t epoch = 0, validEpoch = 0;  // the entry is valid iff validEpoch == epoch
  const TexUnit* unit = nullptr;
  uint64_t rho2Bits = 0;
  uint32_t biasBits = 0;
  int32_t lambda8 = 0;
  Plan plan;
};
constinit thread_local PlanCache t_planCache;

constexpr uint32_t kLayer0[4] = {0, 0, 0, 0};  // the layers of a 2D lookup's quad

// The quad's coarse derivatives (docs/spec-choices.md T1, llvmpipe's quad_lod): ddx = c[1] - c[0],
// ddy = c[2] - c[0], in double, of u = s * w_base, v = t * h_base (GL 4.6 §8.14.1; the array layer is
// not part of rho).
struct QuadDerivatives {
  double dudx, dvdx, dudy, dvdy;
  QuadDerivatives(const TexUnit& u, const float s[4], const float t[4]) {
    const double W = double(u.tex->desc.width), H = double(u.tex->desc.height);
    dudx = (double(s[1]) - double(s[0])) * W;
    dvdx = (double(t[1]) - double(t[0])) * H;
    dudy = (double(s[2]) - double(s[0])) * W;
    dvdy = (double(t[2]) - double(t[0])) * H;
  }
  bool finite() const { return std::isfinite(dudx) && std::isfinite(dvdx) && std::isfinite(dudy) && std::isfinite(dvdy); }
};

// The cache's plan moved to lambda8 from cache.lambda8, on the same unit. Under a *_MIPMAP_LINEAR min
// filter, two minifying lambdas (> 0, the mag/min switch of makePlan's cached form) with the same
// integer part and non-zero fractions choose the same two levels (makePlan: d1 = floor(lambda),
// d2 = d1 + 1, both clamped to q, and the same level count), so only the weights of a two-level plan
// change, to makePlan's; any other change takes a new plan.
void replan(const TexUnit& u, PlanCache& cache, int32_t lambda8) {
  const Filter mf = u.sampler.state.minFilter;
  const int32_t old = cache.lambda8;
  if ((mf == Filter::LinearMipmapLinear || mf == Filter::NearestMipmapLinear) && cache.plan.complete && old > 0 &&
      lambda8 > 0 && (old >> 8) == (lambda8 >> 8) && (old & 0xff) != 0 && (lambda8 & 0xff) != 0) {
    if (cache.plan.levelCount == 2) {
      const uint32_t frac = uint32_t(lambda8 & 0xff);
      cache.plan.levelWeight[0] = kLevelWeightOne - frac;
      cache.plan.levelWeight[1] = frac;
    }
    return;
  }
  cache.plan = makePlan(u, lambda8);
}

// Brings the open plan cache to the quad's lambda and plan; false, leaving it alone, when a derivative
// is not finite (the caller then computes them without the cache).
bool updatePlanCache(const TexUnit& u, const QuadDerivatives& d, float bias) {
  PlanCache& cache = t_planCache;
  if (!d.finite()) return false;
  // rho^2 exactly as computeLambda forms it (same operands, same order).
  const double rx = d.dudx * d.dudx + d.dvdx * d.dvdx;
  const double ry = d.dudy * d.dudy + d.dvdy * d.dvdy;
  const double rho2 = rx > ry ? rx : ry;
  const uint64_t rho2Bits = std::bit_cast<uint64_t>(rho2);
  const uint32_t biasBits = std::bit_cast<uint32_t>(bias);
  const bool valid = cache.validEpoch == cache.epoch && cache.unit == &u;
  if (!valid || cache.rho2Bits != rho2Bits || cache.biasBits != biasBits) {
    // computeLambda's steps for finite derivatives, on the rho^2 it would form.
    const int32_t lambda8 = sample_detail::finishLambda(sample_detail::lambdaBaseFromRho2(rho2), u.sampler, bias);
    if (!valid) cache.plan = makePlan(u, lambda8);
    else if (cache.lambda8 != lambda8) replan(u, cache, lambda8);
    cache.unit = &u, cache.rho2Bits = rho2Bits, cache.biasBits = biasBits, cache.lambda8 = lambda8;
    cache.validEpoch = cache.epoch;
  }
  return true;
}

// Implicit-LOD quad lookup shared by the 2D and 2D-array forms (layers: per pixel, already selected).
void sampleQuadImpl(const TexUnit& u, const float s[4], const float t[4], const uint32_t layers[4], float bias,
                    float out[4][4]) {
  if (!isComplete(u.tex, u.sampler.state)) {
    for (int i = 0; i < 4; ++i) writeIncomplete(out[i]);
    if (LodQuadLog* log = t_lodLog) probeLookup(*log, u, 0.0, 0.0, 0.0, 0.0, 0, 0, false);
    return;
  }
  const QuadDerivatives d(u, s, t);
  PlanCache& cache = t_planCache;
  if (cache.open && updatePlanCache(u, d, bias)) {
    if (LodQuadLog* log = t_lodLog)
      probeLookup(*log, u, d.dudx, d.dvdx, d.dudy, d.dvdy, cache.lambda8, cache.plan.levelCount, false);
    sampleN(u, cache.plan, 4, s, t, layers, out);
    return;
  }
  const int32_t lambda8 = computeLambda(d.dudx, d.dvdx, d.dudy, d.dvdy, u.sampler, bias);
  const Plan p = makePlan(u, lambda8);
  if (LodQuadLog* log = t_lodLog) probeLookup(*log, u, d.dudx, d.dvdx, d.dudy, d.dvdy, lambda8, p.levelCount, false);
  sampleN(u, p, 4, s, t, layers, out);
}

// Plans that differ at most in their level weights (sampleQuads2D's runs).
bool sameButWeights(const Plan& a, const Plan& b) {
  if (a.complete != b.complete || a.linear != b.linear || a.wrapS != b.wrapS || a.wrapT != b.wrapT ||
      a.lastLayer != b.lastLayer || a.levelCount != b.levelCount || std::memcmp(a.border, b.border, sizeof a.border))
    return false;
  for (int l = 0; l < a.levelCount; ++l) {
    const LevelRef &x = a.lv[l], &y = b.lv[l];
    if (x.data != y.data || x.layerStride != y.layerStride || x.w != y.w || x.h != y.h) return false;
  }
  return true;
}

// n quads of sampleQuads2D in one kernel call with plan `p` but each quad's own level weights
// (weightL: per lookup), in layer 0; false, with nothing the caller needs written, where sampleN's
// kernel conditions or the kernel's own do not hold.
bool kernelRun(const Plan& p, size_t n, const float (*s)[4], const float (*t)[4], const uint32_t* weight0,
               const uint32_t* weight1, float (*out)[4][4]) {
  if (!p.complete || !p.linear || p.wrapS == Wrap::ClampToBorder || p.wrapT == Wrap::ClampToBorder) return false;
  const sample_simd::Rgba8LinearFn kernel = t_rgba8KernelSet ? t_rgba8Kernel : sample_simd::rgba8LinearKernel();
  return kernel && kernel(p, 0, s[0], t[0], 4 * n, weight0, weight1, out[0]);
}

inline bool intervalMode(const TexUnit& u) {
  const ShadeProvenance& pv = shadeProvenance();
  return pv.active && pv.bound != SampleBound::Value && isComplete(u.tex, u.sampler.state);
}

// Stage times (raster/stage_times.h): the calling thread's texture-lookup tick counter, or nullptr.
constinit thread_local uint64_t* t_sampleTicks = nullptr;

// Adds the lookup's ticks to the thread's counter when stage times are on; one TLS load otherwise.
class SampleTimer {
 public:
  SampleTimer() : acc_(t_sampleTicks), t0_(acc_ ? detail::stageClock() : 0) {}
  ~SampleTimer() {
    if (acc_) *acc_ += detail::stageClock() - t0_;
  }
  SampleTimer(const SampleTimer&) = delete;
  SampleTimer& operator=(const SampleTimer&) = delete;

 private:
  uint64_t* acc_;
  uint64_t t0_;
};

}  // namespace

void setLodQuadLog(LodQuadLog* log) { t_lodLog = log; }
void detail::beginPlanCache() {
  t_planCache.open = true;
  ++t_planCache.epoch;
}
void detail::endPlanCache() { t_planCache.open = false; }
void detail::bindSampleKernels() {
  t_rgba8Kernel = sample_simd::rgba8LinearKernel();
  t_rgba8KernelSet = true;
}
void detail::unbindSampleKernels() { t_rgba8KernelSet = false; }
void detail::setSampleTicks(uint64_t* ticks) { t_sampleTicks = ticks; }

void sampleAtLambda(const TexUnit& u, float s, float t, uint32_t layer, int32_t lambda8, float out[4]) {
  const Plan p = makePlan(u, lambda8);
  float res[1][4];
  sampleN(u, p, 1, &s, &t, &layer, res);
  for (int c = 0; c < 4; ++c) out[c] = res[0][c];
}

void sampleQuad2D(const TexUnit& u, const float s[4], const float t[4], float bias, float out[4][4]) {
  const SampleTimer timer;
  if (intervalMode(u)) return sampleQuadInterval(u, s, t, nullptr, bias, nullptr, out);
  sampleQuadImpl(u, s, t, kLayer0, bias, out);
}

void sampleQuads2D(const TexUnit& u, size_t n, const float (*s)[4], const float (*t)[4], float bias,
                   float (*out)[4][4]) {
  const SampleTimer timer;
  PlanCache& cache = t_planCache;
  const bool batched = cache.open && !t_lodLog && !intervalMode(u) && isComplete(u.tex, u.sampler.state) &&
                       u.tex->desc.format == Format::RGBA8;
  if (!batched) {  // the quad-by-quad lookups, as sampleQuad2D
    for (size_t q = 0; q < n; ++q) {
      if (intervalMode(u)) sampleQuadInterval(u, s[q], t[q], nullptr, bias, nullptr, out[q]);
      else sampleQuadImpl(u, s[q], t[q], kLayer0, bias, out[q]);
    }
    return;
  }
  // Each quad's lambda and plan come from the cache exactly as in sampleQuadImpl. A run of quads whose
  // plans differ at most in the level weights (under perspective lambda changes from quad to quad, the
  // levels far less often) is sampled in one kernel call with each quad's own weights. What the kernel
  // declines goes quad by quad through sampleN with the quad's own plan, as in sampleQuadImpl.
  constexpr size_t kRun = 64;  // quads per call at most
  uint32_t weight[2][4 * kRun];
  size_t q = 0;
  while (q < n) {
    if (!updatePlanCache(u, QuadDerivatives(u, s[q], t[q]), bias)) {
      sampleQuadImpl(u, s[q], t[q], kLayer0, bias, out[q]);  // a non-finite derivative: no cache
      ++q;
      continue;
    }
    Plan plan = cache.plan;  // the run's plan; quad i's own is this one with its weights
    size_t m = 0;            // quads in the run
    bool oneWeight = true;   // every quad so far has the plan's weights (`weight` is not filled yet)
    int32_t lambda8 = cache.lambda8;
    do {
      if (oneWeight && cache.plan.levelWeight[0] != plan.levelWeight[0]) {
        oneWeight = false;
        for (size_t i = 0; i < 4 * m; ++i) weight[0][i] = plan.levelWeight[0], weight[1][i] = plan.levelWeight[1];
      }
      if (!oneWeight)
        for (int l = 0; l < 2; ++l)
          for (int p = 0; p < 4; ++p) weight[l][4 * m + size_t(p)] = cache.plan.levelWeight[l];
      ++m;
      if (q + m == n || m == kRun || !updatePlanCache(u, QuadDerivatives(u, s[q + m], t[q + m]), bias)) break;
      // A plan is a function of the unit and lambda: only a new lambda can end the run.
      if (cache.lambda8 != lambda8 && !sameButWeights(cache.plan, plan)) break;
      lambda8 = cache.lambda8;
    } while (true);
    if (!kernelRun(plan, m, s + q, t + q, oneWeight ? nullptr : weight[0], oneWeight ? nullptr : weight[1], out + q))
      for (size_t i = 0; i < m; ++i) {
        if (!oneWeight) plan.levelWeight[0] = weight[0][4 * i], plan.levelWeight[1] = weight[1][4 * i];
        sampleN(u, plan, 4, s[q + i], t[q + i], kLayer0, out[q + i]);
      }
    q += m;
  }
}

void sampleQuad2DArray(const TexUnit& u, const float s[4], const float t[4], const float r[4], float bias,
                       float out[4][4]) {
  const SampleTimer timer;
  if (intervalMode(u)) return sampleQuadInterval(u, s, t, r, bias, nullptr, out);
  const uint32_t layers = u.tex != nullptr ? u.tex->desc.layers : 1u;
  const uint32_t l[4] = {selectLayer(r[0], layers), selectLayer(r[1], layers), selectLayer(r[2], layers),
                         selectLayer(r[3], layers)};
  sampleQuadImpl(u, s, t, l, bias, out);
}

void sampleGrad2DArray(const TexUnit& u, const float s[4], const float t[4], const float r[4], float dsdx, float dtdx,
                       float dsdy, float dtdy, float out[4][4]) {
  const SampleTimer timer;
  if (!isComplete(u.tex, u.sampler.state)) {
    for (int i = 0; i < 4; ++i) writeIncomplete(out[i]);
    if (LodQuadLog* log = t_lodLog) probeLookup(*log, u, 0.0, 0.0, 0.0, 0.0, 0, 0, true);
    return;
  }
  if (intervalMode(u)) {
    const double g[4] = {dsdx, dtdx, dsdy, dtdy};
    return sampleQuadInterval(u, s, t, r, 0.0f, g, out);
  }
  // textureGrad: explicit derivatives replace the implicit ones; there is no shader bias, but the
  // sampler's bias still applies (GL 4.6 §8.14.1: bias_shader = 0 for the Grad functions).
  const TextureDesc& d = u.tex->desc;
  const double W = double(d.width), H = double(d.height);
  const int32_t lambda8 =
      computeLambda(double(dsdx) * W, double(dtdx) * H, double(dsdy) * W, double(dtdy) * H, u.sampler, 0.0f);
  const uint32_t l[4] = {selectLayer(r[0], d.layers), selectLayer(r[1], d.layers), selectLayer(r[2], d.layers),
                         selectLayer(r[3], d.layers)};
  const Plan p = makePlan(u, lambda8);
  if (LodQuadLog* log = t_lodLog)
    probeLookup(*log, u, double(dsdx) * W, double(dtdx) * H, double(dsdy) * W, double(dtdy) * H, lambda8,
                p.levelCount, true);
  sampleN(u, p, 4, s, t, l, out);
}

uint32_t selectLayer(float r, uint32_t layers) {
  // EXT_texture_array / GL 4.6 §8.14.2: layer = clamp(floor(r + 1/2), 0, d - 1), r + 1/2 in float32.
  // r = k + 1/2 selects k + 1 (floor rule; llvmpipe's round-half-even may pick k: ambiguous in GL).
  if (layers == 0) return 0;
  const float rr = r + 0.5f;
  if (std::isnan(rr) || rr < 0.0f) return 0;
  const float last = float(layers - 1);  // exact (<= 2048)
  const float fl = std::floor(rr);
  return fl >= last ? layers - 1 : uint32_t(fl);
}

namespace {

// The texel bytes and count N seen by texelFetch (GL 4.6 §8.9: N = min(floor(size / texelBytes),
// MAX_TEXTURE_BUFFER_SIZE) for buffer textures; level 0, layer 0 as a linear index for 2D textures).
const uint8_t* fetchBase(const TextureData& tex, uint64_t& n) {
  const uint32_t bpt = texelBytes(tex.desc.format);
  if (tex.desc.kind == TextureKind::Buffer) {
    if (tex.buffer == nullptr || bpt == 0) {
      n = 0;
      return nullptr;
    }
    n = tex.buffer->bytes.size() / bpt;
    if (n > kMaxBufferTextureTexels) n = kMaxBufferTextureTexels;
    return tex.buffer->bytes.data();
  }
  if (tex.levels.empty() || tex.desc.layers == 0) {
    n = 0;
    return nullptr;
  }
  n = uint64_t(levelWidth(tex.desc, 0)) * levelHeight(tex.desc, 0);
  return tex.levels[0].data();
}

}  // namespace

void fetchBuffer(const TexUnit& u, int64_t index, float out[4]) {
  const SampleTimer timer;
  if (u.tex == nullptr) {  // no texture: incomplete (GL 4.6 §11.1.3.5)
    writeIncomplete(out);
    return;
  }
  uint64_t n = 0;
  const uint8_t* base = fetchBase(*u.tex, n);
  // Out of range: (0, 0, 0, 0). texelFetch itself would be undefined in GL without robustness, but
  // both GLSL twins that fetch (atlas_displace, texarray_batch) test the index against textureSize
  // and return vec4(0) instead, so the value is defined and provenance treats it as exact.
  if (base == nullptr || index < 0 || uint64_t(index) >= n) {
    for (int c = 0; c < 4; ++c) out[c] = 0.0f;
    return;
  }
  const Format fmt = u.tex->desc.format;
  const uint8_t* p = base + uint64_t(index) * texelBytes(fmt);
  const int channels = channelCount(fmt);
  for (int c = 0; c < 4; ++c) out[c] = c == 3 ? 1.0f : 0.0f;  // Table 15.1 expansion
  for (int c = 0; c < channels; ++c) {
    if (isUnorm(fmt)) {
      out[c] = float(double(p[c]) / 255.0);  // same value as the filtered path's v * 2^24 / (255 * 2^24)
    } else if (isFloat(fmt)) {
      out[c] = loadF32(p + 4 * c);
    } else {
      uint32_t v;
      std::memcpy(&v, p + 4 * c, 4);
      out[c] = float(v);
    }
  }
}

uint32_t fetchBufferUint(const TexUnit& u, int64_t index) {
  const SampleTimer timer;
  // Exact integer texelFetch for R32UI; other formats (not readable through a usampler) return 0,
  // and so do out-of-range indices and a missing texture.
  if (u.tex == nullptr || !isInteger(u.tex->desc.format)) return 0;
  uint64_t n = 0;
  const uint8_t* base = fetchBase(*u.tex, n);
  if (base == nullptr || index < 0 || uint64_t(index) >= n) return 0;
  uint32_t v;
  std::memcpy(&v, base + uint64_t(index) * 4, 4);
  return v;
}

int32_t wrapCoord(Wrap w, int64_t i, int32_t size) { return wrapIndex(w, i, size); }

}  // namespace tessera
