// Interval sampling: the per-pixel [lo, hi] bounds of a texture lookup in provenance mode
// (provenance.h). The exact lookups are in sample.cpp; this file calls them once per legal alternative.
//
// The alternatives a GL implementation may take for one lookup (tolerances: raster/tolerances.h, each
// derived in docs/crosscheck.md):
// - lambda: exact rho vs the spec's bounds max(mu, mv) <= f <= mu + mv (GL 4.6 §8.14.1 eq. 8.7), coarse
//   vs fine derivatives (GLSL §8.14.1), and log2 precision (tolerance::kLod8); the mag/min switch point
//   c = 1/2 where §8.14 allows it;
// - texel coordinates: the sample-position shift times the coordinate derivatives, float interpolation
//   error, and half an 8-bit weight step (tolerance::kSamplePosPx, kInterpRel, kWeightTexel);
// - array layer: r + 1/2 near an integer (tolerance::kLayer);
// - unorm filtering precision: +-1 LSB when the lookup blends texels (tolerance::kFilterUnorm).
// Each alternative is looked up with the exact path's own plan and per-pixel filter (makePlan, sampleN),
// and the interval starts from the lookup at the oracle's lambda, coordinates and layer.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "raster/provenance.h"
#include "raster/sample.h"
#include "raster/sample_detail.h"
#include "raster/tolerances.h"

namespace tessera::sample_detail {
namespace {

struct Interval {
  float lo[4], hi[4];
  void init(const float v[4]) {
    for (int c = 0; c < 4; ++c) lo[c] = hi[c] = v[c];
  }
  void add(const float v[4]) {
    for (int c = 0; c < 4; ++c) {
      if (v[c] < lo[c] || std::isnan(lo[c])) lo[c] = v[c];
      if (v[c] > hi[c] || std::isnan(hi[c])) hi[c] = v[c];
    }
  }
};

inline bool sameValue(const float a[4], const float b[4]) { return std::memcmp(a, b, 4 * sizeof(float)) == 0; }

// Candidate coordinates along one axis for one plan: both ends of the tolerance, plus every texel
// centre inside it for LINEAR (where the piecewise-linear filter has its kinks).
int coordCandidates(float x, double tol, const Plan& p, bool horizontal, float out[6]) {
  int n = 0;
  out[n++] = float(double(x) - tol);
  out[n++] = float(double(x) + tol);
  if (!p.linear) return n;
  for (int l = 0; l < p.levelCount && n < 6; ++l) {
    const double size = horizontal ? p.lv[l].w : p.lv[l].h;
    const double a = (double(x) - tol) * size - 0.5, b = (double(x) + tol) * size - 0.5;
    if (!(b - a < 4.0)) continue;  // NaN or huge: the two ends already stand for it
    for (double k = std::ceil(a); k <= b && n < 6; k += 1.0) out[n++] = float((k + 0.5) / size);
  }
  return n;
}

// Bounds one pixel's lookup over the legal alternatives. `der` = {dsdx, dtdx, dsdy, dtdy} per
// derivative choice (0: the oracle's, 1: the alternative), in normalized coordinates.
void intervalPixel(const TexUnit& u, float s, float t, float r, bool array, const double der[2][4], int derCount,
                   float bias, uint16_t& classes, Interval& iv) {
  const TextureDesc& d = u.tex->desc;
  const double W = double(d.width), H = double(d.height);
  int32_t lamOracle = 0, lamLo = 0, lamHi = 0;
  int32_t exact[2] = {0, 0};
  for (int k = 0; k < derCount; ++k) {
    const double ux = der[k][0] * W, vx = der[k][1] * H, uy = der[k][2] * W, vy = der[k][3] * H;
    const double rx = ux * ux + vx * vx, ry = uy * uy + vy * vy;
    const double mu = std::max(std::fabs(ux), std::fabs(uy)), mv = std::max(std::fabs(vx), std::fabs(vy));
    const double lower = std::max(mu, mv), upper = mu + mv;
    const int32_t e = lambdaBaseFromRho2(rx > ry ? rx : ry);
    const int32_t a = lambdaBaseFromRho2(lower * lower), b = lambdaBaseFromRho2(upper * upper);
    exact[k] = finishLambda(e, u.sampler, bias);
    const int32_t lo = std::min({e, a, b}), hi = std::max({e, a, b});
    const int32_t flo = finishLambda(lo == kLodMinusInf ? lo : lo - tolerance::kLod8, u.sampler, bias);
    const int32_t fhi = finishLambda(hi >= kLodMax ? hi : hi + tolerance::kLod8, u.sampler, bias);
    if (k == 0) lamOracle = exact[0], lamLo = flo, lamHi = fhi;
    lamLo = std::min(lamLo, flo);
    lamHi = std::max(lamHi, fhi);
  }
  if (derCount > 1 && exact[1] != exact[0]) classes |= kHelperDeriv;

  // Lambda candidates: the ends, the oracle's, and both sides of every switch point inside
  // (integers: level pairs and the mag/min switch at c = 0; k + 1/2: nearest-mip rounding).
  int32_t lam[18];
  int nl = 0;
  lam[nl++] = lamOracle;
  lam[nl++] = lamLo;
  lam[nl++] = lamHi;
  const int32_t kMaxK = int32_t(d.levels) + 1;
  for (int32_t k = 0; k <= kMaxK && nl < 16; ++k)
    for (int32_t off : {0, 1, 128, 129}) {
      const int32_t v = k * 256 + off;
      if (v > lamLo && v < lamHi && nl < 18) lam[nl++] = v;
    }

  // Layer candidates.
  uint32_t layerOracle = 0, layerLo = 0, layerHi = 0;
  if (array) {
    layerOracle = selectLayer(r, d.layers);
    layerLo = selectLayer(r - tolerance::kLayer, d.layers);
    layerHi = selectLayer(r + tolerance::kLayer, d.layers);
    if (layerLo != layerHi) classes |= kLayerTie;
  }

  const double tolS = (std::fabs(der[0][0]) + std::fabs(der[0][2])) * tolerance::kSamplePosPx +
                      std::fabs(double(s)) * tolerance::kInterpRel;
  const double tolT = (std::fabs(der[0][1]) + std::fabs(der[0][3])) * tolerance::kSamplePosPx +
                      std::fabs(double(t)) * tolerance::kInterpRel;

  float nominal[4];
  {
    const Plan p = makePlan(u, lamOracle);
    sampleN(u, p, 1, &s, &t, &layerOracle, reinterpret_cast<float(*)[4]>(nominal));
    iv.init(nominal);
    if (isUnorm(d.format) && (p.linear || p.levelCount == 2)) classes |= kFilterPrecision;
    // A texture rendered in provenance mode is read through its lower or upper interval image
    // (sample.cpp); where that differs from its values, the texels' own freedoms reach this lookup.
    ShadeProvenance& sp = shadeProvenance();
    if (u.tex->prov && sp.bound != SampleBound::Value) {
      const SampleBound b = sp.bound;
      sp.bound = SampleBound::Value;  // makePlan picks the image the texels are read from
      const Plan pv = makePlan(u, lamOracle);
      float v[1][4];
      sampleN(u, pv, 1, &s, &t, &layerOracle, v);
      sp.bound = b;
      if (!sameValue(v[0], nominal)) classes |= kInputInterval;
    }
  }
  // GL 4.6 §8.14: with mag LINEAR and min NEAREST_MIPMAP_NEAREST or NEAREST_MIPMAP_LINEAR the switch
  // point c may be 1/2 instead of the oracle's 0 (spec-choices T4): for lambda in (0, 1/2] the mag
  // filter is then legal too.
  const SamplerState& ss = u.sampler.state;
  const bool halfSwitch = ss.magFilter == Filter::Linear &&
                          (ss.minFilter == Filter::NearestMipmapNearest || ss.minFilter == Filter::NearestMipmapLinear);
  for (int pi = 0; pi < 2 * nl; ++pi) {
    const int li = pi >> 1;
    const bool alt = pi & 1;
    if (alt && !(halfSwitch && lam[li] > 0 && lam[li] <= 128)) continue;
    const Plan p = makePlan(u, lam[li], alt ? 128 : 0);
    const LevelRef& coarse = p.lv[p.levelCount - 1];
    const double qS = tolerance::kWeightTexel / coarse.w, qT = tolerance::kWeightTexel / coarse.h;
    float sc[7], tc[7];
    int ns = coordCandidates(s, tolS + (p.linear ? qS : 0.0), p, true, sc);
    int nt = coordCandidates(t, tolT + (p.linear ? qT : 0.0), p, false, tc);
    sc[ns++] = s;
    tc[nt++] = t;
    for (uint32_t layer = layerLo; layer <= layerHi; ++layer)
      for (int a = 0; a < ns; ++a)
        for (int b = 0; b < nt; ++b) {
          float v[1][4];
          sampleN(u, p, 1, &sc[a], &tc[b], &layer, v);
          if (sameValue(v[0], nominal)) continue;
          iv.add(v[0]);
          // A class names the freedom that alone changes the value: the LOD with the nominal
          // coordinates and layer, or the coordinates with the oracle's LOD and layer. Combinations
          // only widen the interval.
          const bool nominalCoords = a == ns - 1 && b == nt - 1, nominalLayer = layer == layerOracle;
          if ((alt || lam[li] != lamOracle) && nominalCoords && nominalLayer) classes |= kLodNearSwitch;
          if (!alt && lam[li] == lamOracle && !nominalCoords && nominalLayer) classes |= kSubtexelNearHalf;
        }
  }
  if (classes & kFilterPrecision) {
    for (int c = 0; c < channelCount(d.format); ++c) {
      iv.lo[c] = std::max(0.0f, float(double(iv.lo[c]) - tolerance::kFilterUnorm));
      iv.hi[c] = std::min(1.0f, float(double(iv.hi[c]) + tolerance::kFilterUnorm));
    }
  }
}

}  // namespace

// Quad lookup in provenance mode: each pixel's interval; out = lower or upper bound per pixel.
void sampleQuadInterval(const TexUnit& u, const float s[4], const float t[4], const float* r, float bias,
                        const double* grad, float out[4][4]) {
  ShadeProvenance& pv = shadeProvenance();
  for (int p = 0; p < 4; ++p) {
    double der[2][4];
    // 0: coarse (the oracle's) or the explicit gradient; 1: fine, per row / column of the quad.
    if (grad) {
      for (int k = 0; k < 4; ++k) der[0][k] = grad[k];
    } else {
      der[0][0] = double(s[1]) - s[0], der[0][1] = double(t[1]) - t[0];
      der[0][2] = double(s[2]) - s[0], der[0][3] = double(t[2]) - t[0];
    }
    const int row = (p >> 1) * 2, col = p & 1;
    der[1][0] = double(s[row + 1]) - s[row], der[1][1] = double(t[row + 1]) - t[row];
    der[1][2] = double(s[2 + col]) - s[col], der[1][3] = double(t[2 + col]) - t[col];
    Interval iv;
    intervalPixel(u, s[p], t[p], r ? r[p] : 0.0f, r != nullptr, der, 2, bias, pv.classes[size_t(p)], iv);
    for (int c = 0; c < 4; ++c) out[p][c] = pv.bound == SampleBound::Lo ? iv.lo[c] : iv.hi[c];
  }
}

}  // namespace tessera::sample_detail
