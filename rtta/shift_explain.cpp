#include "rtta/shift_explain.h"

#include <algorithm>
#include <cmath>

#include "raster/limits.h"

namespace tessera::rtta {

namespace {

struct F4 {
  float v[4];
};

// The programs' mulMat4 (raster/programs/common.h): four products summed left to right in float.
F4 transform(const glm::mat4& m, const RttaVertex& p) {
  F4 r;
  for (int i = 0; i < 4; ++i) {
    float acc = m[0][i] * p.x;
    acc = acc + m[1][i] * p.y;
    acc = acc + m[2][i] * p.z;
    acc = acc + m[3][i] * 1.0f;
    r.v[i] = acc;
  }
  return r;
}

// raster/setup.cpp toWindow: divide in double, scale and offset, snap to sub-pixels half to even.
int64_t snap(float c, float w, int32_t origin, int32_t size) {
  const double invW = 1.0 / double(w);
  const double half = 0.5 * size;
  const double win = double(c) * invW * half + (origin + half);
  return int64_t(std::nearbyint(win * double(kSubpixelOne)));
}

}  // namespace

ShiftExplanation explainShift(const RttaScene& scene, std::span<const Record> records, const glm::mat4& mvp,
                              const Rect& vp, const AtlasSize& atlas) {
  ShiftExplanation e;
  e.mask.assign(size_t(vp.w) * size_t(vp.h), 0);
  auto mark = [&](int64_t x0, int64_t y0, int64_t x1, int64_t y1, uint8_t bit) {
    x0 = std::max<int64_t>(x0, vp.x), y0 = std::max<int64_t>(y0, vp.y);
    x1 = std::min<int64_t>(x1, vp.x + vp.w), y1 = std::min<int64_t>(y1, vp.y + vp.h);
    for (int64_t y = y0; y < y1; ++y)
      for (int64_t x = x0; x < x1; ++x) e.mask[size_t(y - vp.y) * size_t(vp.w) + size_t(x - vp.x)] |= bit;
  };
  for (size_t t = 0; t + 2 < scene.vertices.size(); t += 3) {
    const uint32_t id = scene.vertices[t + 2].object;  // the provoking vertex
    if (id >= records.size() || records[id].layer < 0) continue;
    const Record& r = records[id];
    ++e.triangles;
    bool clipped = false, rounded = false, behind = false;
    int64_t lo[2] = {INT64_MAX, INT64_MAX}, hi[2] = {INT64_MIN, INT64_MIN};
    double plo[2] = {INFINITY, INFINITY}, phi[2] = {-INFINITY, -INFINITY};  // projected hull, pixels
    for (int k = 0; k < 3; ++k) {
      const F4 p = transform(mvp, scene.vertices[t + k]);
      const float x = p.v[0], y = p.v[1], z = p.v[2], w = p.v[3];
      // The capture's clip distances (w ± x, w ± y) and GL's z planes.
      if (w + x < 0.0f || w - x < 0.0f || w + y < 0.0f || w - y < 0.0f || w + z < 0.0f || w - z < 0.0f) clipped = true;
      if (!(w > 0.0f)) {
        behind = true;
        continue;
      }
      const double px = (double(x) / w + 1.0) * 0.5 * vp.w + vp.x, py = (double(y) / w + 1.0) * 0.5 * vp.h + vp.y;
      plo[0] = std::min(plo[0], px), plo[1] = std::min(plo[1], py);
      phi[0] = std::max(phi[0], px), phi[1] = std::max(phi[1], py);
      if (clipped) continue;
      const float xd = (r.T.a * x + r.T.b * y) + r.T.tx * w;
      const float yd = (r.T.c * x + r.T.d * y) + r.T.ty * w;
      const int64_t sx = snap(x, w, vp.x, vp.w), sy = snap(y, w, vp.y, vp.h);
      const int64_t ax = snap(xd, w, 0, atlas.width), ay = snap(yd, w, 0, atlas.height);
      const int64_t shiftX = int64_t(r.atlas.x0 - r.viewport.x0) * kSubpixelOne;
      const int64_t shiftY = int64_t(r.atlas.y0 - r.viewport.y0) * kSubpixelOne;
      rounded = rounded || ax != sx + shiftX || ay != sy + shiftY;
      lo[0] = std::min(lo[0], sx), lo[1] = std::min(lo[1], sy);
      hi[0] = std::max(hi[0], sx), hi[1] = std::max(hi[1], sy);
    }
    if (clipped) {
      // Clipping makes new vertices on the triangle's edges: inside the hull of its projected vertices
      // when all are in front of the eye (w > 0), else anywhere in the object's region.
      ++e.clipped;
      if (behind) mark(r.inner.x0, r.inner.y0, r.inner.x1, r.inner.y1, 2);
      else
        mark(int64_t(std::floor(std::max(plo[0], -1e9))) - 1, int64_t(std::floor(std::max(plo[1], -1e9))) - 1,
             int64_t(std::ceil(std::min(phi[0], 1e9))) + 2, int64_t(std::ceil(std::min(phi[1], 1e9))) + 2, 2);
    } else if (rounded) {
      ++e.rounded;
      // Pixels whose centres the triangle's snapped hull can reach, one pixel wider for the snap moves.
      mark(lo[0] / kSubpixelOne - 1, lo[1] / kSubpixelOne - 1, hi[0] / kSubpixelOne + 2, hi[1] / kSubpixelOne + 2, 1);
    }
  }
  return e;
}

}  // namespace tessera::rtta
