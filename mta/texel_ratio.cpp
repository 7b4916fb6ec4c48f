#include "mta/texel_ratio.h"

#include <cmath>
#include <limits>

#include "raster/sample.h"

namespace tessera::mta {

namespace {

constexpr double kSqrt2 = 1.4142135623730951;

// The analytic scale factor ρ of one texture parameterization at a pixel (texels of level 0 per pixel).
struct Homogeneous {
  double inv[3][3];  // M⁻¹, M = columns (x̃_i, ỹ_i, W_i)
  bool ok = false;
};

Homogeneous setupTriangle(const double clip[3][4], uint32_t width, uint32_t height) {
  Homogeneous h;
  double m[3][3];
  for (int i = 0; i < 3; ++i) {
    m[0][i] = (0.5 * clip[i][0] + 0.5 * clip[i][3]) * width;
    m[1][i] = (0.5 * clip[i][1] + 0.5 * clip[i][3]) * height;
    m[2][i] = clip[i][3];
  }
  const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
  const double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
  const double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
  const double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
  if (!(std::fabs(det) > 0.0) || !std::isfinite(det)) return h;
  const double id = 1.0 / det;
  h.inv[0][0] = c00 * id;
  h.inv[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * id;
  h.inv[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * id;
  h.inv[1][0] = c01 * id;
  h.inv[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * id;
  h.inv[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * id;
  h.inv[2][0] = c02 * id;
  h.inv[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * id;
  h.inv[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * id;
  h.ok = true;
  return h;
}

// a = M⁻ᵀ·u: aᵀ·p̂ is the homogeneous numerator of the attribute at window point p̂.
void numerator(const Homogeneous& h, const double u[3], double a[3]) {
  for (int k = 0; k < 3; ++k) a[k] = u[0] * h.inv[0][k] + u[1] * h.inv[1][k] + u[2] * h.inv[2][k];
}

// The texcoord Jacobian at window point (px, py): texels of level 0 per pixel (s_x, s_y, t_x, t_y).
struct Jacobian {
  double sx = 0, sy = 0, tx = 0, ty = 0;
  bool ok = false;
  // GL's scale factor (GL 4.6 §8.14.1, eq. 8.7): the longer of the two screen-axis columns.
  double rho() const {
    const double rx = std::sqrt(sx * sx + tx * tx), ry = std::sqrt(sy * sy + ty * ty);
    return rx > ry ? rx : ry;
  }
  // Pixels one texel spans along its own s and t edges, the larger of the two: the columns of the
  // inverse Jacobian, ((t_y, -t_x) and (-s_y, s_x)) / det. 1/ρ only sees the screen axes, so a texel
  // stretched along one edge on screen (an oblique surface, a non-uniform texture mapping) can be
  // magnified beyond 1/ρ along that edge; this is what the build's per-texel world size bounds.
  double perAxisPixels() const {
    const double det = sx * ty - sy * tx;
    if (!(std::fabs(det) > 0.0)) return std::numeric_limits<double>::infinity();
    const double ps = std::sqrt(tx * tx + ty * ty) / std::fabs(det), pt = std::sqrt(sx * sx + sy * sy) / std::fabs(det);
    return ps > pt ? ps : pt;
  }
};

Jacobian jacobian(const Homogeneous& h, const double s[3], const double t[3], double px, double py) {
  const double one[3] = {1, 1, 1};
  double a[3], b[3], c[3];
  numerator(h, s, a);
  numerator(h, t, b);
  numerator(h, one, c);
  const double A = a[0] * px + a[1] * py + a[2];
  const double B = b[0] * px + b[1] * py + b[2];
  const double C = c[0] * px + c[1] * py + c[2];
  Jacobian j;
  if (!(std::fabs(C) > 0.0)) return j;
  const double c2 = C * C;
  j.sx = (a[0] * C - A * c[0]) / c2;
  j.sy = (a[1] * C - A * c[1]) / c2;
  j.tx = (b[0] * C - B * c[0]) / c2;
  j.ty = (b[1] * C - B * c[1]) / c2;
  j.ok = true;
  return j;
}

int ratioBin(double r) {
  int bin = 0;
  for (int k = 1; k < kRatioBins; ++k)
    if (r >= ratioBinLower(k)) bin = k;
  return bin;
}

}  // namespace

double ratioBinLower(int bin) {
  if (bin <= 0) return 0.0;
  // 2^((bin - 5) / 2): 0.25 at bin 1, 1 at bin 5, 8 at bin 11; odd exponents through √2 exactly once.
  const int e = bin - 5;
  double v = 1.0;
  for (int i = 0; i < (e >= 0 ? e : -e) / 2; ++i) v = e >= 0 ? v * 2.0 : v * 0.5;
  if (e % 2 != 0) v = e > 0 ? v * kSqrt2 : v / kSqrt2;
  return v;
}

TexelFrame analyzeTexels(const TreeRenderer& renderer, const Camera& camera, const FrameResult& frame,
                         const std::vector<uint32_t>& triangleIds, double tau) {
  const RuntimeGeometry& g = renderer.geometry();
  const MtaMeta& meta = renderer.file().meta();
  const uint32_t W = renderer.options().width, H = renderer.options().height;
  if (triangleIds.size() != size_t(W) * H) throw Error("texel analysis: the id image does not match the frame size");
  TexelFrame out;
  out.width = W;
  out.height = H;
  const size_t n = size_t(W) * H;
  out.ratio.assign(n, std::numeric_limits<float>::quiet_NaN());
  out.ratioBase.assign(n, std::numeric_limits<float>::quiet_NaN());
  out.source.assign(n, 0);
  out.violation.assign(n, 0);
  out.axisRatio.assign(n, std::numeric_limits<float>::quiet_NaN());

  std::vector<int32_t> drawOf(g.triangleCount(), -1);
  for (size_t d = 0; d < frame.plan.draws.size(); ++d)
    for (uint32_t k = 0; k < frame.plan.draws[d].count; ++k) drawOf[frame.plan.draws[d].first + k] = int32_t(d);

  const glm::dmat4 mvp(viewProjection(camera, W, H));  // the float matrix the frame was drawn with
  const double tauLimit = tau * (1.0 + 1e-6);

  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const size_t pix = size_t(y) * W + x;
      const uint32_t tri = triangleIds[pix];
      if (tri == 0xffffffffu || tri >= g.triangleCount() || drawOf[tri] < 0) continue;
      const PlannedDraw& d = frame.plan.draws[size_t(drawOf[tri])];
      const BoundTexture& bt = frame.drawTexture[size_t(drawOf[tri])];
      if (d.source == DrawSource::White || d.source == DrawSource::Untextured) {
        out.source[pix] = 3;
        ++out.pixelsWhite;
        continue;
      }
      double clip[3][4];
      double sa[3], ta[3], so[3], to[3];
      const Tree& tree = meta.trees[g.triangleTree[tri]];
      const int32_t texture = tree.geometry.layers[0].texture[g.triangleSource[tri]];
      const ImageRecord& img = meta.images[meta.textures[uint32_t(texture)].image];
      for (int v = 0; v < 3; ++v) {
        const RuntimeVertex& rv = g.vertices[size_t(tri) * 3 + v];
        // Spelled out: GLM's mvp * vec4 would add (c0·x + c1·y) + (c2·z + c3).
        for (int r = 0; r < 4; ++r)
          clip[v][r] = ((mvp[0][r] * rv.pos.x + mvp[1][r] * rv.pos.y) + mvp[2][r] * rv.pos.z) + mvp[3][r];
        so[v] = double(rv.origUV[0]) * img.width;
        to[v] = double(rv.origUV[1]) * img.height;
        sa[v] = double(rv.atlasUV[0]) * bt.scale * bt.width;
        ta[v] = double(rv.atlasUV[1]) * bt.scale * bt.height;
      }
      const Homogeneous h = setupTriangle(clip, W, H);
      if (!h.ok) continue;
      const double px = x + 0.5, py = y + 0.5;
      const Jacobian jOrig = jacobian(h, so, to, px, py);
      const Jacobian j = d.source == DrawSource::Atlas ? jacobian(h, sa, ta, px, py) : jOrig;
      if (!j.ok) continue;
      const double r0 = j.rho();
      if (!(r0 > 0.0) || !std::isfinite(r0)) continue;
      int e = 0;
      std::frexp(r0, &e);  // r0 = m · 2^e, m in [0.5, 1): floor(log2 r0) = e - 1, exactly
      int level = e - 1;
      if (level < 0) level = 0;
      if (level > int(bt.levels) - 1) level = int(bt.levels) - 1;
      const double base = 1.0 / r0;
      const double ratio = std::ldexp(1.0, level) / r0;
      const double axisBase = j.perAxisPixels();
      const double axisRatio = std::ldexp(axisBase, level);  // a texel of level L spans 2^L texels of level 0
      out.ratio[pix] = float(ratio);
      out.ratioBase[pix] = float(base);
      out.axisRatio[pix] = float(axisRatio);
      ++out.histogram[size_t(ratioBin(ratio))];
      ++out.axisHistogram[size_t(ratioBin(axisRatio))];
      if (d.source == DrawSource::Atlas) {
        out.source[pix] = 1;
        ++out.pixelsAtlas;
        if (base > out.maxAtlasRatioBase) out.maxAtlasRatioBase = base;
        const double origBaseIso = 1.0 / jOrig.rho(), origAxis = jOrig.perAxisPixels();
        if (!(jOrig.rho() > 0.0) || !(origAxis <= origBaseIso * kDegenerateAnisotropy))
          ++out.atlasPixelsDegenerateTexcoords;
        else if (axisBase > out.maxAtlasAxisBase)
          out.maxAtlasAxisBase = axisBase;
        // A violation: the atlas magnifies beyond τ where the original texture would have been finer (the
        // build never stores more texels than the original has).
        if (base > tauLimit) {
          ++out.atlasAboveTau;
          const double origBase = 1.0 / jOrig.rho();
          if (!(base <= origBase * (1.0 + 1e-3))) {
            out.violation[pix] |= kIsotropicViolation;
            ++out.magnificationViolations;
            if (tree.nodes[d.node].leaf()) ++out.violationsInLeafAtlases;
          }
        }
        if (axisBase > tauLimit) {
          ++out.atlasAxisAboveTau;
          if (!(axisBase <= jOrig.perAxisPixels() * (1.0 + 1e-3))) {
            out.violation[pix] |= kPerAxisViolation;
            ++out.perAxisViolations;
          }
        }
      } else {
        out.source[pix] = 2;
        ++out.pixelsOriginal;
      }
    }
  return out;
}

double log2Exact(double v) {
  // log2Fixed (no libm): the same colours and scales on every machine.
  return !(v > 0.0) ? -64.0 : std::isfinite(v) ? double(log2Fixed(v, 16)) / 65536.0 : 64.0;
}

std::array<uint8_t, 4> heatColorLog2(double l, double lt) {
  auto mix = [](std::array<double, 3> a, std::array<double, 3> b, double f) {
    f = f < 0.0 ? 0.0 : f > 1.0 ? 1.0 : f;
    std::array<uint8_t, 4> c{0, 0, 0, 255};
    for (int k = 0; k < 3; ++k) c[size_t(k)] = uint8_t(a[size_t(k)] + (b[size_t(k)] - a[size_t(k)]) * f + 0.5);
    return c;
  };
  // Linear in log2(ratio) within each band, so that the colour bar's scale is logarithmic.
  if (l <= 0.0) return mix({20, 40, 160}, {0, 200, 80}, (l + 2.0) / 2.0);          // 1/4 .. 1: minified
  if (l <= lt) return mix({0, 200, 80}, {240, 220, 0}, lt > 0.0 ? l / lt : 1.0);   // 1 .. τ
  return mix({250, 140, 0}, {200, 0, 0}, (l - lt) / 2.0);                          // τ .. 4τ and beyond
}

std::array<uint8_t, 4> heatColor(double ratio, double tau) {
  return heatColorLog2(log2Exact(ratio), log2Exact(tau * (1.0 + 1e-6)));
}

std::vector<uint8_t> heatMap(const TexelFrame& t, double tau, bool perAxis) {
  std::vector<uint8_t> px(size_t(t.width) * t.height * 4);
  const uint8_t bit = perAxis ? kPerAxisViolation : kIsotropicViolation;
  const std::vector<float>& value = perAxis ? t.axisRatio : t.ratio;
  for (uint32_t y = 0; y < t.height; ++y)
    for (uint32_t x = 0; x < t.width; ++x) {
      const size_t src = size_t(y) * t.width + x;
      uint8_t* o = px.data() + (size_t(t.height - 1 - y) * t.width + x) * 4;  // top row first
      std::array<uint8_t, 4> c = kHeatBackground;
      if (t.source[src] == 3) c = kHeatWhiteTexture;
      else if (t.violation[src] & bit) c = kHeatViolation;
      else if (t.source[src] != 0 && std::isfinite(value[src])) c = heatColor(value[src], tau);
      for (int k = 0; k < 4; ++k) o[k] = c[size_t(k)];
    }
  return px;
}

nlohmann::json toJson(const TexelFrame& t) {
  nlohmann::json hist = nlohmann::json::array();
  nlohmann::json axisHist = nlohmann::json::array();
  for (int b = 0; b < kRatioBins; ++b) {
    hist.push_back({{"ratio_at_least", ratioBinLower(b)}, {"pixels", t.histogram[size_t(b)]}});
    axisHist.push_back({{"ratio_at_least", ratioBinLower(b)}, {"pixels", t.axisHistogram[size_t(b)]}});
  }
  return {{"magnification_violations", t.magnificationViolations},
          {"violations_in_leaf_atlases", t.violationsInLeafAtlases},
          {"pixels_atlas", t.pixelsAtlas},
          {"pixels_original", t.pixelsOriginal},
          {"pixels_white", t.pixelsWhite},
          {"atlas_pixels_above_tau", t.atlasAboveTau},
          {"max_atlas_ratio_level0", t.maxAtlasRatioBase},
          {"per_axis_magnification_violations", t.perAxisViolations},
          {"atlas_pixels_above_tau_per_axis", t.atlasAxisAboveTau},
          {"max_atlas_per_axis_level0", t.maxAtlasAxisBase},
          {"atlas_pixels_degenerate_texcoords", t.atlasPixelsDegenerateTexcoords},
          {"histogram", hist},
          {"per_axis_histogram", axisHist}};
}

}  // namespace tessera::mta
