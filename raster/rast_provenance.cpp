// Provenance-mode rasterization of one triangle in one tile (see rast.h and provenance.h).
//
// The value path is the same as the fast path: the same exact coverage, interpolation, depth test and
// writeFragment. Around it, this file records for every touched pixel the interval of results that GL
// allows, and why:
// - EDGE_TIE / CLIP_EDGE: the centre lies within the edge margin, so another legal snapping may cover
//   it or not. Both outcomes enter the interval.
// - DEPTH_NEAR_EQUAL: the depth test is within the depth tolerance of flipping. Both outcomes enter.
// - the program's output interval: three runs (lower bound, upper bound, value) with the sampler in
//   interval mode, widened by the output-rounding tolerance.
// - BLEND_PRECISION: blending is evaluated at the 16 corners of (src, src alpha, dst, dst alpha), then
//   widened by +-2.5 LSB for unorm.
// The tolerances are in raster/tolerances.h, each derived in docs/crosscheck.md.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "raster/fragops.h"
#include "raster/provenance.h"
#include "raster/rast.h"
#include "raster/tolerances.h"

namespace tessera::detail {
namespace {

inline double clamp01(double v) { return v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0; }

// Bytes that RNE or any tie-breaking may produce from values in [a, b] (in [0, 1] units).
inline void unormRange(double a, double b, int& lo, int& hi) {
  a = clamp01(a), b = clamp01(b);
  lo = int(std::ceil(a * 255.0 - 0.5));
  hi = int(std::floor(b * 255.0 + 0.5));
  lo = std::clamp(lo, 0, 255), hi = std::clamp(hi, 0, 255);
}

struct FragInterval {
  double lo[4], hi[4];  // program output space
  double tol[4];        // output-rounding tolerance
};

// The fragment interval of attachment `a`, pixel `p`, from the three runs.
FragInterval fragInterval(const QuadOut (&o)[3], int a, int p, bool uintOut) {
  FragInterval f{};
  for (int c = 0; c < 4; ++c) {
    if (uintOut) {
      const uint32_t v0 = o[0].color[a][p].u[c], v1 = o[1].color[a][p].u[c], v2 = o[2].color[a][p].u[c];
      f.lo[c] = double(std::min({v0, v1, v2}));
      f.hi[c] = double(std::max({v0, v1, v2}));
      continue;
    }
    double v[3];
    for (int r = 0; r < 3; ++r) {
      const float x = o[r].color[a][p].f[c];
      v[r] = std::isnan(x) ? 0.0 : double(x);
    }
    f.lo[c] = std::min({v[0], v[1], v[2]});
    f.hi[c] = std::max({v[0], v[1], v[2]});
    // Output rounding: the value run's quad gradient times the position tolerance, plus float error.
    const QuadOut& val = o[2];
    const double g = std::fabs(double(val.color[a][1].f[c]) - val.color[a][0].f[c]) +
                     std::fabs(double(val.color[a][2].f[c]) - val.color[a][0].f[c]);
    f.tol[c] = (std::isfinite(g) ? g * tolerance::kSamplePosPx : 0.0) + std::fabs(v[2]) * tolerance::kInterpRel;
  }
  return f;
}

struct PixelUpdate {
  bool keepValue;   // the oracle writes this fragment
  bool ambiguous;   // another legal outcome differs in whether it writes
  bool dontCare;    // the program used an undefined value
  uint16_t classes; // classes of the fragment (sampler + coverage + depth)
};

void updateUnorm(TextureData& tex, const TargetView& tv, uint32_t layer, int32_t x, int32_t y, const QuadOut (&o)[3],
                 int a, int p, const BlendState& blend, const PixelUpdate& u) {
  const int n = tex.desc.format == Format::RGBA8 ? 4 : 1;
  Provenance& pv = *tex.prov;
  uint8_t* val = tex.texel(tv.level, layer, uint32_t(x), uint32_t(y));
  uint8_t* lo = pv.lo->texel(tv.level, layer, uint32_t(x), uint32_t(y));
  uint8_t* hi = pv.hi->texel(tv.level, layer, uint32_t(x), uint32_t(y));
  uint16_t& cls = pv.cls(tex, tv.level, layer, uint32_t(x), uint32_t(y));
  const uint16_t dstCls = cls;
  const FragInterval f = fragInterval(o, a, p, false);
  uint16_t classes = u.classes;
  int wlo[4], whi[4];
  if (!blend.enabled) {
    for (int c = 0; c < n; ++c) {
      double l = f.lo[c] - f.tol[c], h = f.hi[c] + f.tol[c];
      if (u.dontCare) l = 0.0, h = 1.0;
      unormRange(l, h, wlo[c], whi[c]);
      int tl, th;
      unormRange(f.lo[c], f.hi[c], tl, th);
      if (tl != wlo[c] || th != whi[c]) classes |= kOutputRounding;
    }
  } else {
    // Corners of (src colour, src alpha, dst colour, dst alpha) in [lo, hi]: blending is monotone in
    // each of them separately, so its range over the box is attained at a corner.
    double sLo[4], sHi[4], dLo[4] = {0, 0, 0, 1}, dHi[4] = {0, 0, 0, 1};
    for (int c = 0; c < 4; ++c) {
      sLo[c] = u.dontCare ? 0.0 : f.lo[c] - f.tol[c];
      sHi[c] = u.dontCare ? 1.0 : f.hi[c] + f.tol[c];
    }
    for (int c = 0; c < n; ++c) dLo[c] = lo[c] / 255.0, dHi[c] = hi[c] / 255.0;
    double bmin[4], bmax[4];
    for (int c = 0; c < 4; ++c) bmin[c] = 1e300, bmax[c] = -1e300;
    for (int corner = 0; corner < 16; ++corner) {
      float src[4];
      double dst[4], out[4];
      for (int c = 0; c < 4; ++c) {
        const bool alpha = c == 3;
        src[c] = float(((corner >> (alpha ? 1 : 0)) & 1) ? sHi[c] : sLo[c]);
        dst[c] = ((corner >> (alpha ? 3 : 2)) & 1) ? dHi[c] : dLo[c];
      }
      detail::blend(blend, true, src, dst, out);
      for (int c = 0; c < 4; ++c) bmin[c] = std::min(bmin[c], out[c]), bmax[c] = std::max(bmax[c], out[c]);
    }
    for (int c = 0; c < n; ++c) {
      // GL's blending precision is free. An 8-bit blender (llvmpipe: lp_build_mul_norm) quantizes the
      // source and both factors to 8 bits and rounds both products: at most 5 half-LSB errors, so
      // the exact result may move by 2.5 LSB before the final rounding (docs/crosscheck.md).
      unormRange(bmin[c] - tolerance::kBlendUnorm, bmax[c] + tolerance::kBlendUnorm, wlo[c], whi[c]);
    }
    classes |= kBlendPrecision | dstCls;
  }
  if (u.keepValue) {
    uint32_t bits[4];
    std::memcpy(bits, o[2].color[a][p].u, sizeof bits);
    writeFragment(tex.desc.format, val, bits, blend);
  }
  bool exact = true;
  for (int c = 0; c < n; ++c) {
    int l = wlo[c], h = whi[c];
    if (u.ambiguous) l = std::min<int>(l, lo[c]), h = std::max<int>(h, hi[c]);
    else if (!u.keepValue) l = lo[c], h = hi[c];
    l = std::min<int>(l, val[c]), h = std::max<int>(h, val[c]);  // the oracle's own value is always legal
    lo[c] = uint8_t(l), hi[c] = uint8_t(h);
    exact = exact && l == val[c] && h == val[c];
  }
  if (u.ambiguous) classes |= dstCls;
  if (!u.keepValue && !u.ambiguous) classes = dstCls;
  cls = exact ? 0 : classes;
}

void updateFloat(TextureData& tex, const TargetView& tv, uint32_t layer, int32_t x, int32_t y, const QuadOut (&o)[3],
                 int a, int p, const BlendState& blend, const PixelUpdate& u) {
  const int n = tex.desc.format == Format::RGBA32F ? 4 : 2;
  Provenance& pv = *tex.prov;
  uint8_t* val = tex.texel(tv.level, layer, uint32_t(x), uint32_t(y));
  uint8_t* lob = pv.lo->texel(tv.level, layer, uint32_t(x), uint32_t(y));
  uint8_t* hib = pv.hi->texel(tv.level, layer, uint32_t(x), uint32_t(y));
  uint16_t& cls = pv.cls(tex, tv.level, layer, uint32_t(x), uint32_t(y));
  float lo[4], hi[4], v[4];
  std::memcpy(lo, lob, size_t(n) * 4);
  std::memcpy(hi, hib, size_t(n) * 4);
  const FragInterval f = fragInterval(o, a, p, false);
  uint16_t classes = u.classes;
  double wlo[4], whi[4];
  for (int c = 0; c < n; ++c) {
    wlo[c] = u.dontCare ? -std::numeric_limits<double>::infinity() : f.lo[c] - f.tol[c];
    whi[c] = u.dontCare ? std::numeric_limits<double>::infinity() : f.hi[c] + f.tol[c];
    if (blend.enabled) {
      // Blended float targets are not bounded here (no built-in scene blends into one): any value is
      // accepted and the pixel is classed, so the gap is visible in every report.
      classes |= kBlendPrecision | cls;
      wlo[c] = -std::numeric_limits<double>::infinity();
      whi[c] = std::numeric_limits<double>::infinity();
    }
  }
  if (u.keepValue) {
    uint32_t bits[4];
    std::memcpy(bits, o[2].color[a][p].u, sizeof bits);
    writeFragment(tex.desc.format, val, bits, blend);
  }
  std::memcpy(v, val, size_t(n) * 4);
  bool exact = true;
  for (int c = 0; c < n; ++c) {
    double l = wlo[c], h = whi[c];
    if (u.ambiguous) l = std::min<double>(l, lo[c]), h = std::max<double>(h, hi[c]);
    else if (!u.keepValue) l = lo[c], h = hi[c];
    l = std::min<double>(l, v[c]), h = std::max<double>(h, v[c]);
    lo[c] = float(l), hi[c] = float(h);
    if (double(lo[c]) > l) lo[c] = std::nextafter(lo[c], -std::numeric_limits<float>::infinity());
    if (double(hi[c]) < h) hi[c] = std::nextafter(hi[c], std::numeric_limits<float>::infinity());
    exact = exact && lo[c] == v[c] && hi[c] == v[c];
  }
  std::memcpy(lob, lo, size_t(n) * 4);
  std::memcpy(hib, hi, size_t(n) * 4);
  if (u.ambiguous) classes |= cls;
  if (!u.keepValue && !u.ambiguous) classes = cls;
  cls = exact ? 0 : classes;
}

void updateUint(TextureData& tex, const TargetView& tv, uint32_t layer, int32_t x, int32_t y, const QuadOut (&o)[3],
                int a, int p, const PixelUpdate& u) {
  Provenance& pv = *tex.prov;
  uint8_t* val = tex.texel(tv.level, layer, uint32_t(x), uint32_t(y));
  uint8_t* lob = pv.lo->texel(tv.level, layer, uint32_t(x), uint32_t(y));
  uint8_t* hib = pv.hi->texel(tv.level, layer, uint32_t(x), uint32_t(y));
  uint16_t& cls = pv.cls(tex, tv.level, layer, uint32_t(x), uint32_t(y));
  uint32_t lo, hi, v;
  std::memcpy(&lo, lob, 4);
  std::memcpy(&hi, hib, 4);
  const FragInterval f = fragInterval(o, a, p, true);
  uint32_t wlo = u.dontCare ? 0u : uint32_t(f.lo[0]), whi = u.dontCare ? 0xffffffffu : uint32_t(f.hi[0]);
  if (u.keepValue) std::memcpy(val, o[2].color[a][p].u, 4);
  std::memcpy(&v, val, 4);
  uint16_t classes = u.classes;
  if (u.ambiguous) wlo = std::min(wlo, lo), whi = std::max(whi, hi), classes |= cls;
  else if (!u.keepValue) wlo = lo, whi = hi, classes = cls;
  wlo = std::min(wlo, v), whi = std::max(whi, v);
  std::memcpy(lob, &wlo, 4);
  std::memcpy(hib, &whi, 4);
  cls = (wlo == v && whi == v) ? 0 : classes;
}

}  // namespace

void rasterizeTriangleProvenance(const Scene& scene, const TriSetup& t, const TileRect& tile, PipelineStats& stats) {
  const DrawState& ds = *scene.states[t.drawState];
  const TargetView& tv = scene.target;
  const int32_t x0 = std::max(t.minX, tile.x0), x1 = std::min(t.maxX, tile.x1);
  const int32_t y0 = std::max(t.minY, tile.y0), y1 = std::min(t.maxY, tile.y1);
  if (x0 > x1 || y0 > y1) return;

  double margin[3];
  for (int i = 0; i < 3; ++i) {
    const double len = std::sqrt(double(t.a[i]) * double(t.a[i]) + double(t.b[i]) * double(t.b[i]));
    margin[i] = (t.clipped ? tolerance::kClipMarginSub : tolerance::kEdgeMarginSub) * len;
  }
  // Depth gradient per pixel from the plane z = sum(E_i z_i) / 2A.
  const double area = double(t.area2);
  double dzdx = 0.0, dzdy = 0.0;
  for (int i = 0; i < 3; ++i) dzdx += double(t.a[i]) * t.z[i], dzdy += double(t.b[i]) * t.z[i];
  dzdx = dzdx / area * double(kSubpixelOne), dzdy = dzdy / area * double(kSubpixelOne);
  const double tolZ = tolerance::kDepthAbs + (std::fabs(dzdx) + std::fabs(dzdy)) * tolerance::kSamplePosPx;
  const uint16_t tieClass = t.clipped ? kClipEdge : kEdgeTie;
  const bool depthTest = ds.depth.test && tv.depth;
  const bool depthWrite = depthTest && ds.depth.write;

  ShadeProvenance& sp = shadeProvenance();
  Quad quad;
  QuadOut outs[3];  // lower bound, upper bound, value
  for (int32_t qy = y0 & ~1; qy <= y1; qy += 2) {
    for (int32_t qx = x0 & ~1; qx <= x1; qx += 2) {
      int64_t e[4][3];
      uint8_t cov = 0, tie = 0;
      for (int p = 0; p < 4; ++p) {
        const int32_t px = qx + (p & 1), py = qy + (p >> 1);
        bool covered = true, nearEdge = false, nearMiss = true;
        for (int i = 0; i < 3; ++i) {
          e[p][i] = t.a[i] * ((int64_t(px) << kSubpixelBits) + kSubpixelHalf) +
                    t.b[i] * ((int64_t(py) << kSubpixelBits) + kSubpixelHalf) + t.c[i];
          covered = covered && e[p][i] - t.bias[i] >= 0;
          nearEdge = nearEdge || std::fabs(double(e[p][i])) <= margin[i];
          nearMiss = nearMiss && double(e[p][i]) >= -margin[i];
        }
        if (px < x0 || px > x1 || py < y0 || py > y1) continue;
        cov |= uint8_t(covered) << p;
        tie |= uint8_t((covered && nearEdge) || (!covered && nearMiss)) << p;
      }
      if (!(cov | tie)) continue;

      float z[4];
      quad.x = qx, quad.y = qy, quad.coverage = cov;
      for (int p = 0; p < 4; ++p) z[p] = interpolatePixel(t, ds.varyings, e[p], quad.var[p]);

      uint8_t pass = cov | tie, nearDepth = 0;
      if (depthTest) {
        for (int p = 0; p < 4; ++p) {
          if (!((cov | tie) >> p & 1)) continue;
          const float stored = loadDepth(*tv.depth, tv.level, t.layer, qx + (p & 1), qy + (p >> 1));
          if (!depthPasses(ds.depth.func, z[p], stored)) pass &= uint8_t(~(1u << p));
          // GL's invariance rule (Appendix A) makes EQUAL exact for identical input, so an exact
          // equality under EQUAL / NOTEQUAL is not a near tie.
          const bool invariant = (ds.depth.func == CompareFunc::Equal || ds.depth.func == CompareFunc::NotEqual) &&
                                 z[p] == stored;
          if (!invariant &&
              std::fabs(double(z[p]) - stored) <= tolZ + std::fabs(double(stored)) * tolerance::kInterpRel)
            nearDepth |= uint8_t(1u << p);
        }
      }
      const uint8_t valueWrite = cov & pass;
      const uint8_t ambiguous = (tie & (pass | nearDepth)) | (cov & nearDepth);
      stats.fragments_depth_failed += uint64_t(std::popcount(uint32_t(cov & ~pass)));
      if (!(valueWrite | ambiguous)) continue;

      QuadBatch batch{&quad, nullptr, 1, {}, t.primitiveId, t.layer, t.frontFacing};
      std::memcpy(batch.flat, t.flat, sizeof batch.flat);
      sp.active = true;
      sp.resetPixels();
      const SampleBound bounds[3] = {SampleBound::Lo, SampleBound::Hi, SampleBound::Value};
      for (int r = 0; r < 3; ++r) {
        sp.bound = bounds[r];
        outs[r].discard = 0;
        batch.out = &outs[r];
        ds.program->shadeQuads(batch, ds.ctx);
      }
      sp.active = false;
      sp.bound = SampleBound::Value;

      stats.quads_shaded += 1;
      stats.fragments_shaded += uint64_t(std::popcount(uint32_t(valueWrite)));
      stats.helper_invocations += uint64_t(4 - std::popcount(uint32_t(valueWrite)));
      for (int p = 0; p < 4; ++p) {
        const bool keep = (valueWrite >> p & 1) && !(outs[2].discard >> p & 1);
        const bool amb = ambiguous >> p & 1;
        if (!keep && !amb) continue;
        const int32_t x = qx + (p & 1), y = qy + (p >> 1);
        if (keep && depthWrite) storeDepth(*tv.depth, tv.level, t.layer, x, y, z[p]);
        PixelUpdate u;
        u.keepValue = keep;
        u.ambiguous = amb;
        u.dontCare = sp.dontCare[size_t(p)];
        u.classes = uint16_t(sp.classes[size_t(p)] | (u.dontCare ? kOobFetch : 0) | ((tie >> p & 1) ? tieClass : 0) |
                             ((nearDepth >> p & 1) ? kDepthNearEqual : 0));
        for (int a = 0; a < ds.colorOutputs; ++a) {
          TextureData* c = tv.color[size_t(a)];
          if (!c || !c->prov) continue;
          switch (c->desc.format) {
            case Format::RGBA8:
            case Format::R8: updateUnorm(*c, tv, t.layer, x, y, outs, a, p, ds.blend, u); break;
            case Format::RG32F:
            case Format::RGBA32F: updateFloat(*c, tv, t.layer, x, y, outs, a, p, ds.blend, u); break;
            case Format::R32UI: updateUint(*c, tv, t.layer, x, y, outs, a, p, u); break;
            default: break;
          }
        }
        if (keep) ++stats.pixels_written;
      }
    }
  }
}

}  // namespace tessera::detail
