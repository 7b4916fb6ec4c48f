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

using DF = hn::CappedTag<float, 4>;  // the four pixels of a quad; one lane on the scalar target
using DI = hn::RebindToSigned<DF>;
using DU = hn::RebindToUnsigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using VU = hn::Vec<DU>;

// The kernel's wraps: REPEAT on a power of two (a mask) and CLAMP_TO_EDGE (a clamp).
HWY_INLINE bool axisTaken(Wrap w, int32_t size) {
  if (size <= 0) return false;
  if (w == Wrap::Repeat) return (size & (size - 1)) == 0;
  return w == Wrap::ClampToEdge;
}

// The wrapped pair (i0, i0 + 1) of GL 4.6 §8.14.2 Table 8.20, as sample.cpp's wrapPair gives it for
// the two wraps the kernel takes (|i0| <= 2^14 + 1: no overflow).
HWY_INLINE void wrapPair(Wrap w, VI i0, int32_t size, VI& w0, VI& w1) {
  const DI di;
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
HWY_INLINE VI linearFixed(VF x) {
  const DF df;
  const VF magic = hn::Set(df, 12582912.0f);  // 1.5 * 2^23
  const VF r = hn::Sub(hn::Add(hn::Mul(x, hn::Set(df, 256.0f)), magic), magic);
  return hn::Sub(hn::ConvertTo(DI(), r), hn::Set(DI(), 128));
}

// The texels at indices idx (non-negative, < 2^31) of the layer at `base`, one uint32 (RGBA8) each.
// Plain loads: a gather instruction is no faster for four lanes, and memcpy reads the bytes as bytes.
HWY_INLINE VU fetch(const uint8_t* base, VI idx) {
  const DI di;
  const DU du;
  HWY_ALIGN int32_t k[4];
  HWY_ALIGN uint32_t texel[4];
  hn::Store(idx, di, k);
  for (size_t q = 0; q < hn::Lanes(di); ++q) std::memcpy(&texel[q], base + uint64_t(uint32_t(k[q])) * 4u, 4);
  return hn::Load(du, texel);
}

// Channels (R, B) and (G, A) of RGBA8 texels, each pair in the two 16-bit halves of a lane.
HWY_INLINE VU even(VU x) { return hn::And(x, hn::Set(DU(), 0x00ff00ffu)); }
HWY_INLINE VU odd(VU x) { return hn::And(hn::ShiftRight<8>(x), hn::Set(DU(), 0x00ff00ffu)); }

// The horizontal step on such pairs: na x + a y <= 255 * 256 per half, so no carry between them.
HWY_INLINE VU horizontal(VU x, VU y, VU na, VU a) { return hn::Add(hn::Mul(x, na), hn::Mul(y, a)); }

// The vertical step of one channel (<= 255 * 2^16) times the level weight (<= 255 * 2^24 in all).
HWY_INLINE VU vertical(VU top, VU bottom, VU nb, VU b, VU levelW) {
  return hn::Mul(hn::Add(hn::Mul(top, nb), hn::Mul(bottom, b)), levelW);
}

// One level's filtered RGBA times levelW, added to acc (R, G, B, A). False, with acc unspecified,
// when a coordinate is outside |s w|, |t h| <= 2^14 (NaN included).
HWY_INLINE bool accumulateLevel(const Plan& p, const LevelRef& L, uint32_t layer, uint32_t levelW, VF s, VF t,
                                VU acc[4]) {
  const DF df;
  const DI di;
  const DU du;
  // GL 4.6 §8.14.2: u = s * w_level, v = t * h_level, in float32 (docs/spec-choices.md T7).
  const VF u = hn::Mul(s, hn::Set(df, L.fw));
  const VF v = hn::Mul(t, hn::Set(df, L.fh));
  const VF limit = hn::Set(df, 16384.0f);
  if (!hn::AllTrue(df, hn::And(hn::Le(hn::Abs(u), limit), hn::Le(hn::Abs(v), limit)))) return false;
  const VI U = linearFixed(u), V = linearFixed(v);
  const VI byteMask = hn::Set(di, 255);
  const VU a = hn::BitCast(du, hn::And(U, byteMask)), b = hn::BitCast(du, hn::And(V, byteMask));
  VI i0, i1, j0, j1;
  wrapPair(p.wrapS, hn::ShiftRight<8>(U), L.w, i0, i1);  // arithmetic shift: floor(U / 256)
  wrapPair(p.wrapT, hn::ShiftRight<8>(V), L.h, j0, j1);
  const uint8_t* base = L.data + uint64_t(layer) * L.layerStride;
  const VI width = hn::Set(di, L.w);
  const VI row0 = hn::Mul(j0, width), row1 = hn::Mul(j1, width);
  const VU t00 = fetch(base, hn::Add(row0, i0)), t10 = fetch(base, hn::Add(row0, i1));
  const VU t01 = fetch(base, hn::Add(row1, i0)), t11 = fetch(base, hn::Add(row1, i1));

  const VU one = hn::Set(du, 256);
  const VU na = hn::Sub(one, a), nb = hn::Sub(one, b);
  // Horizontal step with (R, B) and (G, A) in the two 16-bit halves of a lane: na t + a t' <= 255 * 256.
  const VU h0e = horizontal(even(t00), even(t10), na, a), h0o = horizontal(odd(t00), odd(t10), na, a);
  const VU h1e = horizontal(even(t01), even(t11), na, a), h1o = horizontal(odd(t01), odd(t11), na, a);
  const VU low = hn::Set(du, 0xffffu);
  const VU w = hn::Set(du, levelW);
  acc[0] = hn::Add(acc[0], vertical(hn::And(h0e, low), hn::And(h1e, low), nb, b, w));
  acc[1] = hn::Add(acc[1], vertical(hn::And(h0o, low), hn::And(h1o, low), nb, b, w));
  acc[2] = hn::Add(acc[2], vertical(hn::ShiftRight<16>(h0e), hn::ShiftRight<16>(h1e), nb, b, w));
  acc[3] = hn::Add(acc[3], vertical(hn::ShiftRight<16>(h0o), hn::ShiftRight<16>(h1o), nb, b, w));
  return true;
}

bool QuadRgba8Linear(const Plan& p, uint32_t layer, const float* s, const float* t, float (*out)[4]) {
  if (!p.linear) return false;
  for (int l = 0; l < p.levelCount; ++l) {
    const LevelRef& L = p.lv[l];
    if (!axisTaken(p.wrapS, L.w) || !axisTaken(p.wrapT, L.h)) return false;
    if (int64_t(L.w) * int64_t(L.h) > int64_t(INT32_MAX)) return false;
  }
  const DF df;
  const DU du;
  const size_t n = hn::Lanes(df);
  for (size_t off = 0; off < 4; off += n) {
    const VF vs = hn::LoadU(df, s + off), vt = hn::LoadU(df, t + off);
    VU acc[4] = {hn::Zero(du), hn::Zero(du), hn::Zero(du), hn::Zero(du)};
    for (int l = 0; l < p.levelCount; ++l)
      if (!accumulateLevel(p, p.lv[l], layer, p.levelWeight[l], vs, vt, acc)) return false;
    HWY_ALIGN uint32_t sum[4][4];
    for (int c = 0; c < 4; ++c) hn::Store(acc[c], du, sum[c]);
    // sample.cpp's one conversion to float, acc / (255 * 2^24) as a multiply (raster/round.h).
    for (size_t q = 0; q < n; ++q)
      for (int c = 0; c < 4; ++c) out[off + q][c] = float(double(sum[c][q]) * kUnormReciprocal);
  }
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
  return f != nullptr && f(p, layer, s, t, out);
}

}  // namespace tessera::sample_simd

#endif  // HWY_ONCE
