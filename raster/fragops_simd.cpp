// The unorm8 conversion kernel on every Highway target (raster/fragops_simd.h says why its bytes are
// toUnorm8's). Highway compiles this file once per target; HWY_ONCE holds the dispatch.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "raster/fragops_simd.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "raster/fragops.h"
#include "raster/fragops_simd.h"

HWY_BEFORE_NAMESPACE();
namespace tessera::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void Unorm8Quad(const float* in, uint8_t* out) {
  // Full vectors (16 values are 2 of AVX-512, 4 of AVX2, 8 of SSE4, 16 scalar steps): the channels are
  // independent, and each lane's steps are the scalar toUnorm8's.
  const hn::ScalableTag<double> d;
  static_assert(16 % HWY_LANES(double) == 0, "a quad's 16 values are whole vectors");
  const hn::Rebind<float, decltype(d)> df;
  const hn::Rebind<int32_t, decltype(d)> di;
  const hn::Rebind<uint8_t, decltype(d)> du8;
  const size_t n = hn::Lanes(d);
  const auto zero = hn::Zero(d), one = hn::Set(d, 1.0), max = hn::Set(d, 255.0);
  const auto magic = hn::Set(d, 6755399441055744.0);  // 1.5 * 2^52
  for (size_t off = 0; off < 16; off += n) {
    const auto c = hn::PromoteTo(d, hn::LoadU(df, in + off));
    const auto r = hn::Sub(hn::Add(hn::Mul(c, max), magic), magic);  // c * 255 rounded half to even
    // toUnorm8's order: !(c > 0) (NaN included) -> 0, else c >= 1 -> 255, else r.
    const auto v = hn::IfThenElse(hn::Gt(c, zero), hn::IfThenElse(hn::Ge(c, one), max, r), zero);
    hn::StoreU(hn::DemoteTo(du8, hn::DemoteTo(di, v)), du8, out + off);  // integers in [0, 255]: exact
  }
}

Unorm8QuadFn GetUnorm8Quad() { return &Unorm8Quad; }

void BlendSourceOverQuad(const float* src, uint8_t* row0, uint8_t* row1) {
  const hn::CappedTag<double, 4> d;  // at most one pixel per vector: 4, 2 or 1 lanes
  const hn::Rebind<float, decltype(d)> df;
  const hn::Rebind<int32_t, decltype(d)> di;
  const hn::Rebind<uint8_t, decltype(d)> du8;
  const size_t n = hn::Lanes(d);
  // Each pixel's factors a = clamp01(alpha) and 1 - a, as blendSourceOverRgba8 forms them.
  const auto clamp01 = [](double v) { return v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0; };  // NaN -> 0
  double a[4], na[4];
  for (int p = 0; p < 4; ++p) a[p] = clamp01(src[4 * p + 3]), na[p] = 1.0 - a[p];
  const auto zero = hn::Zero(d), one = hn::Set(d, 1.0), max = hn::Set(d, 255.0);
  const auto magic = hn::Set(d, 6755399441055744.0);  // 1.5 * 2^52
  for (size_t off = 0; off < 16; off += n) {
    // Lane off + i is channel (off + i) % 4 of pixel (off + i) / 4: n divides 4, so a vector stays
    // within one pixel's texel.
    uint8_t* const texel = off < 8 ? row0 + off : row1 + (off - 8);
    const auto v = hn::PromoteTo(d, hn::LoadU(df, src + off));
    const auto s = hn::IfThenElse(hn::Gt(v, zero), hn::IfThenElse(hn::Lt(v, one), v, one), zero);  // clamp01
    // The destination byte as kUnorm8ToDouble holds it: the IEEE quotient byte / 255.
    const auto dst = hn::Div(hn::PromoteTo(d, hn::PromoteTo(di, hn::LoadU(du8, texel))), max);
    const auto c = hn::Add(hn::Mul(s, hn::Set(d, a[off / 4])), hn::Mul(dst, hn::Set(d, na[off / 4])));
    const auto r = hn::Sub(hn::Add(hn::Mul(c, max), magic), magic);  // toUnorm8: c * 255 rounded half to even
    const auto u = hn::IfThenElse(hn::Gt(c, zero), hn::IfThenElse(hn::Ge(c, one), max, r), zero);
    hn::StoreU(hn::DemoteTo(du8, hn::DemoteTo(di, u)), du8, texel);  // integers in [0, 255]: exact
  }
}

BlendSourceOverQuadFn GetBlendSourceOverQuad() { return &BlendSourceOverQuad; }

}  // namespace HWY_NAMESPACE
}  // namespace tessera::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE

#include "raster/simd_targets.h"

namespace tessera::detail {

HWY_EXPORT(GetUnorm8Quad);
HWY_EXPORT(GetBlendSourceOverQuad);

namespace {

void scalarUnorm8Quad(const float* in, uint8_t* out) {
  for (int i = 0; i < 16; ++i) out[i] = toUnorm8(in[i]);
}

void scalarBlendSourceOverQuad(const float* src, uint8_t* row0, uint8_t* row1) {
  for (int p = 0; p < 4; ++p) blendSourceOverRgba8(src + 4 * p, (p < 2 ? row0 : row1) + 4 * (p & 1));
}

}  // namespace

Unorm8QuadFn unorm8QuadKernel() {
  return simd::kernelsOn() ? HWY_DYNAMIC_DISPATCH(GetUnorm8Quad)() : &scalarUnorm8Quad;
}

BlendSourceOverQuadFn blendSourceOverQuadKernel() {
  return simd::kernelsOn() ? HWY_DYNAMIC_DISPATCH(GetBlendSourceOverQuad)() : &scalarBlendSourceOverQuad;
}

}  // namespace tessera::detail

#endif  // HWY_ONCE
