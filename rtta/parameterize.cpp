#include "rtta/parameterize.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>

#include "base/error.h"
#include "raster/limits.h"

namespace tessera::rtta {

const char* culledName(Culled c) {
  switch (c) {
    case Culled::No: return "no";
    case Culled::Empty: return "empty";
    case Culled::Frustum: return "frustum";
    case Culled::OffScreen: return "off-screen";
  }
  return "?";
}

namespace {

using Clip = std::array<double, 4>;  // x, y, z, w

// vpm * (p, 1) in double: exact products of float entries and double coordinates up to one rounding
// each, far below the float error bound the margins allow for.
Clip transform(const glm::mat4& m, const glm::dvec3& p) {
  Clip c{};
  for (int k = 0; k < 4; ++k)
    c[k] = double(m[0][k]) * p.x + double(m[1][k]) * p.y + double(m[2][k]) * p.z + double(m[3][k]);
  return c;
}

// Per clip component k, the bound on |float(vpm v) - vpm v| over every vertex v of the box: γ_4 times
// Σ_j |m_kj| max|v_j| (the program's float transform, parameterize.h).
Clip errorBound(const glm::mat4& m, const Box3& b) {
  const glm::dvec3 mag = glm::max(glm::abs(b.lo), glm::abs(b.hi));
  Clip e{};
  for (int k = 0; k < 4; ++k)
    e[k] = kTransformGamma * (std::fabs(double(m[0][k])) * mag.x + std::fabs(double(m[1][k])) * mag.y +
                              std::fabs(double(m[2][k])) * mag.z + std::fabs(double(m[3][k])));
  return e;
}

std::array<glm::dvec3, 8> cornersOf(const Box3& b) {
  std::array<glm::dvec3, 8> c;
  for (int i = 0; i < 8; ++i) c[i] = {(i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z};
  return c;
}

// The six planes as signed distances that are >= 0 inside: w + x, w - x, w + y, w - y, w + z, w - z.
double planeDistance(const Clip& c, int plane) {
  const int axis = plane / 2;
  return plane % 2 == 0 ? c[3] + c[axis] : c[3] - c[axis];
}
double planeError(const Clip& e, int plane) { return e[3] + e[plane / 2]; }

bool frustumCulled(const std::array<Clip, 8>& clip, const Clip& err) {
  for (int plane = 0; plane < 6; ++plane) {
    const double margin = planeError(err, plane);
    bool allOut = true;
    for (const Clip& c : clip) allOut = allOut && planeDistance(c, plane) < -margin;
    if (allOut) return true;
  }
  return false;
}

// The 12 edges of a box as pairs of corner indices (corners differ in one bit).
constexpr std::array<std::array<int, 2>, 12> kEdges{{{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                                     {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}}};

struct NdcBound {
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  bool whole = false;  // fall back to the whole viewport
};

// The NDC bound of the box clipped at the near plane, each point widened by its error bound.
NdcBound projectedBound(const std::array<Clip, 8>& clip, const Clip& err, bool& nearClipped) {
  NdcBound b;
  auto add = [&](const Clip& c, double errScale) {
    const double ew = errScale * err[3];
    if (!(c[3] - ew > 0.0)) {
      b.whole = true;
      return;
    }
    for (int k = 0; k < 2; ++k) {
      const double ndc = c[k] / c[3];
      const double e = (errScale * err[k] + std::fabs(ndc) * ew) / (c[3] - ew);
      b.lo[k] = std::min(b.lo[k], ndc - e);
      b.hi[k] = std::max(b.hi[k], ndc + e);
    }
  };
  nearClipped = false;
  for (const Clip& c : clip)
    if (c[2] + c[3] >= 0.0) add(c, 1.0);
    else nearClipped = true;
  if (nearClipped) {
    for (const auto& [i, j] : kEdges) {
      const double di = clip[i][2] + clip[i][3], dj = clip[j][2] + clip[j][3];
      if ((di < 0.0) == (dj < 0.0)) continue;
      const double t = di / (di - dj);  // the crossing, from corner i
      Clip p;
      for (int k = 0; k < 4; ++k) p[k] = clip[i][k] + t * (clip[j][k] - clip[i][k]);
      // GL clips the triangles, not the box: its clipped vertices carry the interpolation's rounding
      // on top of the vertices' own, so these points get twice the bound.
      add(p, 2.0);
    }
  }
  if (b.lo[0] > b.hi[0]) b.whole = true;  // nothing in front of the near plane survived the margins
  return b;
}

}  // namespace

PixelRect borderedRegion(const PixelRect& inner, int32_t border) {
  auto floorEven = [](int32_t v) { return v - (v & 1); };  // two's complement: also right for negatives
  auto ceilEven = [](int32_t v) { return v + (v & 1); };
  return {floorEven(inner.x0 - border), floorEven(inner.y0 - border), ceilEven(inner.x1 + border), ceilEven(inner.y1 + border)};
}

std::vector<Record> parameterize(std::span<const Box3> objects, const glm::mat4& vpm, const Rect& vp,
                                 const ParamOptions& options) {
  if (options.border < 0 || options.border > 64)
    throw Error(fmt::format("border {}: expected a whole number of pixels in [0, 64]", options.border));
  if (vp.w <= 0 || vp.h <= 0 || vp.w > kMaxTextureSize || vp.h > kMaxTextureSize)
    throw Error(fmt::format("viewport {}x{}: expected 1..{} pixels on each side", vp.w, vp.h, kMaxTextureSize));
  if (objects.size() >= (size_t(1) << 24))
    throw Error(fmt::format("{} objects: object ids must stay below 2^24 (16777216)", objects.size()));
  // Half a sub-pixel: how far snapping may move a vertex (raster/limits.h).
  const double snap = 0.5 / double(kSubpixelOne);
  std::vector<Record> out(objects.size());
  for (size_t i = 0; i < objects.size(); ++i) {
    Record& r = out[i];
    r.id = uint32_t(i);
    r.world = objects[i];
    if (r.world.empty()) {
      r.culled = Culled::Empty;
      continue;
    }
    const auto corners = cornersOf(r.world);
    std::array<Clip, 8> clip;
    for (int k = 0; k < 8; ++k) clip[k] = transform(vpm, corners[k]);
    const Clip err = errorBound(vpm, r.world);
    if (options.cull && frustumCulled(clip, err)) {
      r.culled = Culled::Frustum;
      continue;
    }
    const NdcBound b = projectedBound(clip, err, r.nearClipped);
    PixelRect inner{vp.x, vp.y, vp.x + vp.w, vp.y + vp.h};
    if (b.whole) {
      r.wholeViewport = true;
    } else {
      const double lo[2] = {std::max(b.lo[0], -1.0), std::max(b.lo[1], -1.0)};
      const double hi[2] = {std::min(b.hi[0], 1.0), std::min(b.hi[1], 1.0)};
      if (lo[0] > hi[0] || lo[1] > hi[1]) {
        r.culled = Culled::OffScreen;
        continue;
      }
      // Window coordinates (GL 4.6 §13.8.1), widened by the snap, rounded outward.
      auto toPixel = [](double ndc, int32_t origin, int32_t size) { return (ndc + 1.0) * 0.5 * double(size) + origin; };
      inner.x0 = std::max(vp.x, int32_t(std::floor(toPixel(lo[0], vp.x, vp.w) - snap)));
      inner.y0 = std::max(vp.y, int32_t(std::floor(toPixel(lo[1], vp.y, vp.h) - snap)));
      inner.x1 = std::min(vp.x + vp.w, int32_t(std::ceil(toPixel(hi[0], vp.x, vp.w) + snap)));
      inner.y1 = std::min(vp.y + vp.h, int32_t(std::ceil(toPixel(hi[1], vp.y, vp.h) + snap)));
      if (inner.empty()) {
        r.culled = Culled::OffScreen;
        continue;
      }
    }
    r.inner = inner;
    r.viewport = borderedRegion(inner, options.border);
  }
  return out;
}

}  // namespace tessera::rtta
