// The per-vertex window kernel on every Highway target (raster/window_simd.h says what a record holds
// and why every target gives the reference's bits). Highway compiles this file once per target;
// HWY_ONCE holds the dispatch.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "raster/window_simd.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <limits>

#include "raster/clip.h"
#include "raster/limits.h"
#include "raster/window_simd.h"

HWY_BEFORE_NAMESPACE();
namespace tessera::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using DD = hn::CappedTag<double, 8>;
using DI = hn::RebindToSigned<DD>;
using DU = hn::RebindToUnsigned<DD>;
using DF = hn::Rebind<float, DD>;
using DF32I = hn::Rebind<int32_t, DD>;
using DU32 = hn::Rebind<uint32_t, DD>;

// One group's records into out (elements 0 .. m - 1; a short group through a buffer, so that nothing
// past element m - 1 is written: the next elements may belong to a chunk another thread shades).
template <class V, class D, typename T>
inline void StoreLanes(D d, V v, size_t m, T* out) {
  if (m == hn::Lanes(d)) return hn::StoreU(v, d, out);
  HWY_ALIGN T buf[hn::MaxLanes(d)];
  hn::Store(v, d, buf);
  for (size_t i = 0; i < m; ++i) out[i] = buf[i];
}

// The positions of the VertexOuts v[0 .. m - 1] by component, one lane per vertex; a short group
// (m below the lane count) repeats its last vertex, whose index idx holds in every lane from m - 1 on.
// One gather per component on most targets.
template <class DFx>
inline void LoadPositions(DFx df, const VertexOut* v, size_t m, hn::Vec<hn::Rebind<int32_t, DFx>> idx,
                          hn::Vec<DFx>& x, hn::Vec<DFx>& y, hn::Vec<DFx>& z, hn::Vec<DFx>& w) {
  (void)m;
  const float* base = v[0].pos.data();
  x = hn::GatherIndex(df, base + 0, idx);
  y = hn::GatherIndex(df, base + 1, idx);
  z = hn::GatherIndex(df, base + 2, idx);
  w = hn::GatherIndex(df, base + 3, idx);
}

#if HWY_TARGET != HWY_SCALAR
// Four lanes in one 128-bit vector (AVX2, whose four doubles take four floats): four 16-byte loads and
// a 4x4 transpose instead. A gather is microcoded on AMD, and these four were about a tenth of a
// setup-bound frame on Zen 3 (tiny_tris_1m, perf). Only data moves: the lanes hold the gathers' bits.
inline void LoadPositions(hn::Full128<float> df, const VertexOut* v, size_t m, hn::Vec<hn::Full128<int32_t>> idx,
                          hn::Vec<hn::Full128<float>>& x, hn::Vec<hn::Full128<float>>& y,
                          hn::Vec<hn::Full128<float>>& z, hn::Vec<hn::Full128<float>>& w) {
  (void)idx;
  const auto p0 = hn::LoadU(df, v[0].pos.data());
  const auto p1 = hn::LoadU(df, v[std::min<size_t>(1, m - 1)].pos.data());
  const auto p2 = hn::LoadU(df, v[std::min<size_t>(2, m - 1)].pos.data());
  const auto p3 = hn::LoadU(df, v[std::min<size_t>(3, m - 1)].pos.data());
  const auto xy01 = hn::InterleaveLower(df, p0, p1), xy23 = hn::InterleaveLower(df, p2, p3);  // x x y y
  const auto zw01 = hn::InterleaveUpper(df, p0, p1), zw23 = hn::InterleaveUpper(df, p2, p3);  // z z w w
  x = hn::ConcatLowerLower(df, xy23, xy01);
  y = hn::ConcatUpperUpper(df, xy23, xy01);
  z = hn::ConcatLowerLower(df, zw23, zw01);
  w = hn::ConcatUpperUpper(df, zw23, zw01);
}
#endif

void WindowVertices(const VertexOut* v, size_t n, const Rect& vp, uint8_t clipMask, const VertexWindows& out) {
  const DD d;
  const DI di;
  const DF df;
  const DF32I d32;
  const size_t lanes = hn::Lanes(d);
  // setup.cpp's toWindow: x_w = x_d * (w / 2) + (x + w / 2), and the same for y.
  const double halfW = 0.5 * vp.w, halfH = 0.5 * vp.h;
  const auto halfWv = hn::Set(d, halfW), halfHv = hn::Set(d, halfH);
  const auto offX = hn::Set(d, vp.x + halfW), offY = hn::Set(d, vp.y + halfH);
  const auto zero = hn::Zero(d), half = hn::Set(d, 0.5), one = hn::Set(d, 1.0);
  const auto guard = hn::Set(d, kGuardBand), sub = hn::Set(d, double(kSubpixelOne));
  const auto fltMax = hn::Set(d, double(std::numeric_limits<float>::max()));
  // raster/round.h's roundHalfEvenNear, read off the bits: for |s| <= 2^51, s + 1.5 * 2^52 is the
  // integer RNE(s) + 1.5 * 2^52 in [2^52, 2^53], whose bits minus the constant's are RNE(s). Every
  // lane whose position the record holds is within that range, with room: the guard band gives
  // |x| <= 16 w exactly (the plane tests of floats in double round no sign), so |x / w| <= 16 (1 +
  // 2^-52), and with |w / 2| <= 2^30 and |x + w / 2| < 2^32 for an int32 viewport, |s| < 2^43
  // sub-pixels; the reference's snap() takes the same two additions there. Other lanes get
  // unspecified bits (the integer subtraction wraps; no conversion can trap).
  constexpr double kMagic = 6755399441055744.0;  // 1.5 * 2^52
  const auto magic = hn::Set(d, kMagic);
  const auto magicBits = hn::Set(di, std::bit_cast<int64_t>(kMagic));
  // The positions of `lanes` consecutive VertexOuts (LoadPositions), by index on most targets.
  static_assert(sizeof(VertexOut) % sizeof(float) == 0 && offsetof(VertexOut, pos) == 0, "pos leads a VertexOut");
  constexpr int32_t kStride = int32_t(sizeof(VertexOut) / sizeof(float));
  const auto iota = hn::Iota(d32, 0);
  for (size_t b = 0; b < n; b += lanes) {
    const size_t m = std::min(lanes, n - b);
    // A short group repeats its last vertex (those lanes are not stored).
    const auto idx = hn::Mul(hn::Min(iota, hn::Set(d32, int32_t(m - 1))), hn::Set(d32, kStride));
    hn::Vec<DF> xf, yf, zf, wf;
    LoadPositions(df, v + b, m, idx, xf, yf, zf, wf);
    const auto x = hn::PromoteTo(d, xf), y = hn::PromoteTo(d, yf), z = hn::PromoteTo(d, zf), w = hn::PromoteTo(d, wf);
    // std::isfinite of each float: |v| <= FLT_MAX, false for infinities and NaN.
    const auto finite = hn::And(hn::And(hn::Le(hn::Abs(x), fltMax), hn::Le(hn::Abs(y), fltMax)),
                                hn::And(hn::Le(hn::Abs(z), fltMax), hn::Le(hn::Abs(w), fltMax)));
    // classifyVertex's six fixed planes, "outside" as !(d >= 0).
    const auto gw = hn::Mul(guard, w);
    const auto bit = [&](hn::Vec<DD> dist, int64_t value) {
      return hn::IfThenZeroElse(hn::RebindMask(di, hn::Ge(dist, zero)), hn::Set(di, value));
    };
    const auto fixed = hn::Or(hn::Or(hn::Or(bit(hn::Add(z, w), 1), bit(hn::Sub(w, z), 2)),
                                     hn::Or(bit(hn::Add(gw, x), 4), bit(hn::Sub(gw, x), 8))),
                              hn::Or(bit(hn::Add(gw, y), 16), bit(hn::Sub(gw, y), 32)));
    // toWindow: divide first, then scale and offset, then snap; depth clamped as std::clamp does.
    const auto invW = hn::Div(one, w);
    const auto xw = hn::Add(hn::Mul(hn::Mul(x, invW), halfWv), offX);
    const auto yw = hn::Add(hn::Mul(hn::Mul(y, invW), halfHv), offY);
    auto zw = hn::Add(hn::Mul(hn::Mul(z, invW), half), half);
    zw = hn::IfThenElse(hn::Lt(zw, zero), zero, zw);
    zw = hn::IfThenElse(hn::Lt(one, zw), one, zw);
    const auto sx = hn::Mul(xw, sub), sy = hn::Mul(yw, sub);
    // Finite and inside the fixed planes: the record holds a window position if w > 0 too, and
    // kVertexNoWindow otherwise.
    const auto held = hn::And(hn::RebindMask(d, finite), hn::RebindMask(d, hn::Eq(fixed, hn::Zero(di))));
    auto code = hn::IfThenElse(hn::RebindMask(di, hn::AndNot(hn::Gt(w, zero), held)),
                               hn::Set(di, int64_t(kVertexNoWindow)), fixed);
    code = hn::IfThenElse(hn::RebindMask(di, finite), code, hn::Set(di, int64_t(kClipNonFinite)));
    StoreLanes(di, hn::Sub(hn::BitCast(di, hn::Add(sx, magic)), magicBits), m, out.x + b);
    StoreLanes(di, hn::Sub(hn::BitCast(di, hn::Add(sy, magic)), magicBits), m, out.y + b);
    StoreLanes(d, invW, m, out.invW + b);
#if HWY_TARGET == HWY_SCALAR
    // The scalar target's DemoteTo clamps; static_cast is the reference's cvtsd2ss.
    out.z[b] = float(hn::GetLane(zw));
#else
    StoreLanes(df, hn::DemoteTo(df, zw), m, out.z + b);  // cvtpd2ps: the same rounding as cvtsd2ss
#endif
    StoreLanes(DU32(), hn::TruncateTo(DU32(), hn::BitCast(DU(), code)), m, out.code + b);
    // The enabled user clip distances (usually none), as classifyVertex tests them.
    if (clipMask)
      for (size_t i = 0; i < m; ++i) {
        if (out.code[b + i] == kClipNonFinite) continue;
        for (uint32_t planes = clipMask; planes; planes &= planes - 1) {
          const int k = std::countr_zero(planes);
          if (!(double(v[b + i].clip[k]) >= 0.0)) out.code[b + i] |= 1u << (kClipFixedPlanes + k);
        }
      }
  }
}

WindowVerticesFn GetWindowVertices() { return &WindowVertices; }

}  // namespace HWY_NAMESPACE
}  // namespace tessera::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE

#include "raster/simd_targets.h"

namespace tessera::detail {

HWY_EXPORT(GetWindowVertices);

WindowVerticesFn windowVerticesKernel() {
  return simd::kernelsOn() ? HWY_DYNAMIC_DISPATCH(GetWindowVertices)() : &windowVerticesReference;
}

}  // namespace tessera::detail

#endif  // HWY_ONCE
