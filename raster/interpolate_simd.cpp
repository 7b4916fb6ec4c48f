// The interpolation kernels on every Highway target (raster/interpolate_simd.h says why their floats
// are rast.h's). Highway compiles this file once per target; HWY_ONCE holds the dispatch.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "raster/interpolate_simd.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <limits>

#include "raster/interpolate_simd.h"

HWY_BEFORE_NAMESPACE();
namespace tessera::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// At most 8 lanes: a block's pixel count is a multiple of 4, and a vector never reads past kMax.
using DD = hn::CappedTag<double, 8>;
using DI = hn::Rebind<int64_t, DD>;
using DF = hn::Rebind<float, DD>;

// float(v) per lane, then a NaN replaced by the canonical quiet NaN (rast.h canonicalNaN), stored at
// out. Highway's scalar target clamps out-of-range values in DemoteTo (C++ leaves that conversion
// undefined); IEEE conversion gives infinity, as the scalar code does, so there each lane converts
// with static_cast, which compiles to cvtsd2ss.
inline void StoreFloats(hn::Vec<DD> v, float* out) {
  const DF df;
#if HWY_TARGET == HWY_SCALAR
  (void)df;
  const float f = float(hn::GetLane(v));
  *out = f != f ? std::numeric_limits<float>::quiet_NaN() : f;
#else
  const auto f = hn::DemoteTo(df, v);
  hn::StoreU(hn::IfThenElse(hn::IsNaN(f), hn::Set(df, std::numeric_limits<float>::quiet_NaN()), f), df, out);
#endif
}

// The double results as they are (the wide kernels that tests compare before the rounding to float).
inline void StoreFloats(hn::Vec<DD> v, double* out) { hn::StoreU(v, DD(), out); }

template <typename Out>
void QuadDepthsT(const QuadPixels& px, size_t n, const InterpolationPlane& t, Out* z) {
  const DD d;
  const DI di;
  const auto z0 = hn::Set(d, t.z[0]), z1 = hn::Set(d, t.z[1]), z2 = hn::Set(d, t.z[2]);
  const auto area2 = hn::Set(d, t.area2);
  for (size_t j = 0; j < n; j += hn::Lanes(d)) {
    const auto e0 = hn::ConvertTo(d, hn::Load(di, px.e[0] + j));
    const auto e1 = hn::ConvertTo(d, hn::Load(di, px.e[1] + j));
    const auto e2 = hn::ConvertTo(d, hn::Load(di, px.e[2] + j));
    // pixelDepth: (e0 z0 + e1 z1 + e2 z2) / 2A, left to right.
    const auto num = hn::Add(hn::Add(hn::Mul(e0, z0), hn::Mul(e1, z1)), hn::Mul(e2, z2));
    StoreFloats(hn::Div(num, area2), z + j);
  }
}

template <typename Out>
void QuadVaryingsT(const QuadPixels& px, size_t n, const InterpolationPlane& t, Out* var) {
  if (t.varyings == 0) return;  // the barycentrics serve only the varyings
  const DD d;
  const DI di;
  const auto w0s = hn::Set(d, t.invW[0]), w1s = hn::Set(d, t.invW[1]), w2s = hn::Set(d, t.invW[2]);
  for (size_t j = 0; j < n; j += hn::Lanes(d)) {
    // pixelBarycentrics: w_i = e_i / w_i, b_i = w_i / (w_0 + w_1 + w_2).
    const auto w0 = hn::Mul(hn::ConvertTo(d, hn::Load(di, px.e[0] + j)), w0s);
    const auto w1 = hn::Mul(hn::ConvertTo(d, hn::Load(di, px.e[1] + j)), w1s);
    const auto w2 = hn::Mul(hn::ConvertTo(d, hn::Load(di, px.e[2] + j)), w2s);
    const auto sum = hn::Add(hn::Add(w0, w1), w2);
    const auto b0 = hn::Div(w0, sum), b1 = hn::Div(w1, sum), b2 = hn::Div(w2, sum);
    for (int k = 0; k < t.varyings; ++k) {
      // pixelVarying: b0 v0 + b1 v1 + b2 v2, left to right, rounded to float once.
      const auto v = hn::Add(hn::Add(hn::Mul(b0, hn::Set(d, t.var[0][k])), hn::Mul(b1, hn::Set(d, t.var[1][k]))),
                             hn::Mul(b2, hn::Set(d, t.var[2][k])));
      StoreFloats(v, var + size_t(k) * QuadPixels::kMax + j);
    }
  }
}

void QuadDepths(const QuadPixels& px, size_t n, const InterpolationPlane& t, float* z) { QuadDepthsT(px, n, t, z); }
void QuadVaryings(const QuadPixels& px, size_t n, const InterpolationPlane& t, float* var) { QuadVaryingsT(px, n, t, var); }
void QuadDepthsWide(const QuadPixels& px, size_t n, const InterpolationPlane& t, double* z) { QuadDepthsT(px, n, t, z); }
void QuadVaryingsWide(const QuadPixels& px, size_t n, const InterpolationPlane& t, double* var) {
  QuadVaryingsT(px, n, t, var);
}

QuadDepthsFn GetQuadDepths() { return &QuadDepths; }
QuadVaryingsFn GetQuadVaryings() { return &QuadVaryings; }
QuadDepthsWideFn GetQuadDepthsWide() { return &QuadDepthsWide; }
QuadVaryingsWideFn GetQuadVaryingsWide() { return &QuadVaryingsWide; }

}  // namespace HWY_NAMESPACE
}  // namespace tessera::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE

#include "raster/simd_targets.h"

namespace tessera::detail {

HWY_EXPORT(GetQuadDepths);
HWY_EXPORT(GetQuadVaryings);
HWY_EXPORT(GetQuadDepthsWide);
HWY_EXPORT(GetQuadVaryingsWide);

QuadDepthsFn quadDepthsKernel() {
  return simd::kernelsOn() ? HWY_DYNAMIC_DISPATCH(GetQuadDepths)() : nullptr;
}

QuadVaryingsFn quadVaryingsKernel() {
  return simd::kernelsOn() ? HWY_DYNAMIC_DISPATCH(GetQuadVaryings)() : nullptr;
}

QuadDepthsWideFn quadDepthsWideKernel() { return HWY_DYNAMIC_DISPATCH(GetQuadDepthsWide)(); }
QuadVaryingsWideFn quadVaryingsWideKernel() { return HWY_DYNAMIC_DISPATCH(GetQuadVaryingsWide)(); }

}  // namespace tessera::detail

#endif  // HWY_ONCE
