// The RGBA8 LINEAR quad kernel on every Highway target (raster/sample_simd.h says what it accepts and
// why its bits are the scalar filter's). Highway compiles this file once per target (the raster
// library sets HWY_COMPILE_ALL_ATTAINABLE, raster/simd_targets.h): everything outside HWY_ONCE is per
// target, and HWY_ONCE holds the dispatch.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "raster/sample_simd.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <cstdint>
#include <cstring>

#include "raster/round.h"
#include "raster/sample_detail.h"
#include "raster/sample_simd.h"

HWY_BEFORE_NAMESPACE();
namespace tessera::sample_simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using sample_detail::LevelRef;
using sample_detail::Plan;

// Lookups go through in vectors of the target's full width (16 lanes on AVX-512: four quads), the
// rest in vectors of at most four lanes (one quad; one lane on the scalar target). Every lane computes
// its own lookup, so the width changes no bit.
using DWide = hn::CappedTag<float, 16>;
using DQuad = hn::CappedTag<float, 4>;

// The kernel's wraps: REPEAT on a power of two (a mask) and CLAMP_TO_EDGE (a clamp).
HWY_INLINE bool axisTaken(Wrap w, int32_t size) {
  if (size <= 0) return false;
  if (w == Wrap::Repeat) return (size & (size - 1)) == 0;
  return w == Wrap::ClampToEdge;
}

// The wrapped pair (i0, i0 + 1) of GL 4.6 §8.14.2 Table 8.20, as sample.cpp's wrapPair gives it for
// the two wraps the kernel takes (|i0| <= 2^14 + 1: no overflow).
template <class DI, class VI = hn::Vec<DI>>
HWY_INLINE void wrapPair(DI di, Wrap w, VI i0, int32_t size, VI& w0, VI& w1) {
  const VI i1 = hn::Add(i0, hn::Set(di, 1));
  if (w == Wrap::Repeat) {
    const VI mask = hn::Set(di, size - 1);
    w0 = hn::And(i0, mask);
    w1 = hn::And(i1, mask);
  } else {
    const VI zero = hn::Zero(di), last = hn::Set(di, size - 1);
    w0 = hn::Min(hn::Max(i0, zero), last);
    w1 = hn::Min(hn::Max(i1, zero), last);
  }
}

// round(256 x) - 128 with round half to even, for |x| <= 2^14 (so |256 x| <= 2^22): sample.cpp's
// linearFixed. 256 x is exact; adding 1.5 * 2^23 lands in [2^23, 2^24], where floats are the
// integers, so the addition rounds 256 x to an integer, to even on a tie (1.5 * 2^23 is even); the
// subtraction is then exact.
template <class DF, class VF = hn::Vec<DF>>
HWY_INLINE hn::Vec<hn::RebindToSigned<DF>> linearFixed(DF df, VF x) {
  const hn::RebindToSigned<DF> di;
  const VF magic = hn::Set(df, 12582912.0f);  // 1.5 * 2^23
  const VF r = hn::Sub(hn::Add(hn::Mul(x, hn::Set(df, 256.0f)), magic), magic);
  return hn::Sub(hn::ConvertTo(di, r), hn::Set(di, 128));
}

// The texels at indices idx (non-negative, < 2^31) of the layer at `base`, one uint32 (RGBA8) each.
// Plain loads: a gather instruction is no faster for four lanes, and memcpy reads the bytes as bytes.
template <class DI, class VI = hn::Vec<DI>>
HWY_INLINE hn::Vec<hn::RebindToUnsigned<DI>> fetch(DI di, const uint8_t* base, VI idx) {
  const hn::RebindToUnsigned<DI> du;
  HWY_ALIGN int32_t k[hn::MaxLanes(DI())];
  HWY_ALIGN uint32_t texel[hn::MaxLanes(DI())];
  hn::Store(idx, di, k);
  for (size_t q = 0; q < hn::Lanes(di); ++q) std::memcpy(&texel[q], base + uint64_t(uint32_t(k[q])) * 4u, 4);
  return hn::Load(du, texel);
}

// Channels (R, B) and (G, A) of RGBA8 texels, each pair in the two 16-bit halves of a lane.
template <class DU, class VU = hn::Vec<DU>>
HWY_INLINE VU even(DU du, VU x) { return hn::And(x, hn::Set(du, 0x00ff00ffu)); }
template <class DU, class VU = hn::Vec<DU>>
HWY_INLINE VU odd(DU du, VU x) { return hn::And(hn::ShiftRight<8>(x), hn::Set(du, 0x00ff00ffu)); }

// The horizontal step on such pairs: na x + a y <= 255 * 256 per half, so no carry between them.
template <class VU>
HWY_INLINE VU horizontal(VU x, VU y, VU na, VU a) { return hn::Add(hn::Mul(x, na), hn::Mul(y, a)); }

// The vertical step of one channel (<= 255 * 2^16) times the level weight (<= 255 * 2^24 in all).
template <class VU>
HWY_INLINE VU vertical(VU top, VU bottom, VU nb, VU b, VU levelW) {
  return hn::Mul(hn::Add(hn::Mul(top, nb), hn::Mul(bottom, b)), levelW);
}

// One level's filtered RGBA times levelW, added to acc (R, G, B, A). False, with acc unspecified,
// when a coordinate is outside |s w|, |t h| <= 2^14 (NaN included).
template <class DF, class VF = hn::Vec<DF>, class VU = hn::Vec<hn::RebindToUnsigned<DF>>>
HWY_INLINE bool accumulateLevel(DF df, const Plan& p, const LevelRef& L, uint32_t layer, VU w, VF s, VF t,
                                VU acc[4]) {
  const hn::RebindToSigned<DF> di;
  const hn::RebindToUnsigned<DF> du;
  using VI = hn::Vec<decltype(di)>;
  // GL 4.6 §8.14.2: u = s * w_level, v = t * h_level, in float32 (docs/spec-choices.md T7).
  const VF u = hn::Mul(s, hn::Set(df, L.fw));
  const VF v = hn::Mul(t, hn::Set(df, L.fh));
  const VF limit = hn::Set(df, 16384.0f);
  if (!hn::AllTrue(df, hn::And(hn::Le(hn::Abs(u), limit), hn::Le(hn::Abs(v), limit)))) return false;
  const VI U = linearFixed(df, u), V = linearFixed(df, v);
  const VI byteMask = hn::Set(di, 255);
  const VU a = hn::BitCast(du, hn::And(U, byteMask)), b = hn::BitCast(du, hn::And(V, byteMask));
  VI i0, i1, j0, j1;
  wrapPair(di, p.wrapS, hn::ShiftRight<8>(U), L.w, i0, i1);  // arithmetic shift: floor(U / 256)
  wrapPair(di, p.wrapT, hn::ShiftRight<8>(V), L.h, j0, j1);
  const uint8_t* base = L.data + uint64_t(layer) * L.layerStride;
  const VI width = hn::Set(di, L.w);
  const VI row0 = hn::Mul(j0, width), row1 = hn::Mul(j1, width);
  const VU t00 = fetch(di, base, hn::Add(row0, i0)), t10 = fetch(di, base, hn::Add(row0, i1));
  const VU t01 = fetch(di, base, hn::Add(row1, i0)), t11 = fetch(di, base, hn::Add(row1, i1));

  const VU one = hn::Set(du, 256);
  const VU na = hn::Sub(one, a), nb = hn::Sub(one, b);
  // Horizontal step with (R, B) and (G, A) in the two 16-bit halves of a lane: na t + a t' <= 255 * 256.
  const VU h0e = horizontal(even(du, t00), even(du, t10), na, a), h0o = horizontal(odd(du, t00), odd(du, t10), na, a);
  const VU h1e = horizontal(even(du, t01), even(du, t11), na, a), h1o = horizontal(odd(du, t01), odd(du, t11), na, a);
  const VU low = hn::Set(du, 0xffffu);
  acc[0] = hn::Add(acc[0], vertical(hn::And(h0e, low), hn::And(h1e, low), nb, b, w));
  acc[1] = hn::Add(acc[1], vertical(hn::And(h0o, low), hn::And(h1o, low), nb, b, w));
  acc[2] = hn::Add(acc[2], vertical(hn::ShiftRight<16>(h0e), hn::ShiftRight<16>(h1e), nb, b, w));
  acc[3] = hn::Add(acc[3], vertical(hn::ShiftRight<16>(h0o), hn::ShiftRight<16>(h1o), nb, b, w));
  return true;
}

// Lookups [off, off + Lanes(df)) of the call; false as QuadRgba8Linear.
template <class DF>
HWY_INLINE bool lookups(DF df, const Plan& p, uint32_t layer, const float* s, const float* t,
                        const uint32_t* const weights[2], size_t off, float (*out)[4]) {
  const hn::RebindToUnsigned<DF> du;
  using VU = hn::Vec<decltype(du)>;
  const hn::Vec<DF> vs = hn::LoadU(df, s + off), vt = hn::LoadU(df, t + off);
  VU acc[4] = {hn::Zero(du), hn::Zero(du), hn::Zero(du), hn::Zero(du)};
  for (int l = 0; l < p.levelCount; ++l) {
    const VU w = weights[l] ? hn::LoadU(du, weights[l] + off) : hn::Set(du, p.levelWeight[l]);
    if (!accumulateLevel(df, p, p.lv[l], layer, w, vs, vt, acc)) return false;
  }
  constexpr size_t kMax = hn::MaxLanes(DF());
  HWY_ALIGN uint32_t sum[4][kMax];
  for (int c = 0; c < 4; ++c) hn::Store(acc[c], du, sum[c]);
  // sample.cpp's one conversion to float, acc / (255 * 2^24) as a multiply (raster/round.h).
  for (size_t q = 0; q < hn::Lanes(df); ++q)
    for (int c = 0; c < 4; ++c) out[off + q][c] = float(double(sum[c][q]) * kUnormReciprocal);
  return true;
}

bool QuadRgba8Linear(const Plan& p, uint32_t layer, const float* s, const float* t, size_t n, const uint32_t* weight0,
                     const uint32_t* weight1, float (*out)[4]) {
  const uint32_t* const weights[2] = {weight0, weight1};
  if (!p.linear || n % 4 != 0) return false;
  for (int l = 0; l < p.levelCount; ++l) {
    const LevelRef& L = p.lv[l];
    if (!axisTaken(p.wrapS, L.w) || !axisTaken(p.wrapT, L.h)) return false;
    if (int64_t(L.w) * int64_t(L.h) > int64_t(INT32_MAX)) return false;
  }
  const DWide dw;
  const DQuad dq;
  size_t off = 0;
  for (; off + hn::Lanes(dw) <= n; off += hn::Lanes(dw))
    if (!lookups(dw, p, layer, s, t, weights, off, out)) return false;
  for (; off < n; off += hn::Lanes(dq))
    if (!lookups(dq, p, layer, s, t, weights, off, out)) return false;
  return true;
}

Rgba8LinearFn GetRgba8Linear() { return &QuadRgba8Linear; }

}  // namespace HWY_NAMESPACE
}  // namespace tessera::sample_simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE

#include "raster/simd_targets.h"

namespace tessera::sample_simd {

HWY_EXPORT(GetRgba8Linear);

Rgba8LinearFn rgba8LinearKernel() {
  return simd::kernelsOn() ? HWY_DYNAMIC_DISPATCH(GetRgba8Linear)() : nullptr;
}

bool sampleQuadRgba8Linear(const sample_detail::Plan& p, uint32_t layer, const float* s, const float* t,
                           float (*out)[4]) {
  const Rgba8LinearFn f = rgba8LinearKernel();
  return f != nullptr && f(p, layer, s, t, 4, nullptr, nullptr, out);
}

}  // namespace tessera::sample_simd

#endif  // HWY_ONCE
