// Double-precision point queries on one window-space triangle: the reference the visibility check
// judges mismatching pixels with (docs/visibility.md "Bounds").
//
// Implements: inside test, distance from a point to the triangle's boundary (its three segments),
// the depth of the triangle's plane at the point, and the length of the plane's depth gradient.
// Does not implement: any fill rule (points on an edge are at distance 0, which every bound covers).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "verify/visibility_scene.h"

namespace tessera::verify {

struct PointQuery {
  bool inside = false;          // strictly inside (either winding)
  double boundaryDistance = 0;  // px
  double depth = 0;             // plane depth at the point (min vertex depth for a degenerate triangle)
  double gradient = 0;          // |grad z| per px; +inf for a degenerate triangle
};

inline double segmentDistance(double px, double py, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0.0 ? ((px - ax) * dx + (py - ay) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const double ex = ax + t * dx - px, ey = ay + t * dy - py;
  return std::sqrt(ex * ex + ey * ey);
}

inline PointQuery queryPoint(const WindowTriangle& t, double px, double py) {
  PointQuery q;
  q.boundaryDistance = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    q.boundaryDistance = std::min(q.boundaryDistance, segmentDistance(px, py, t.x[i], t.y[i], t.x[j], t.y[j]));
  }
  const double area2 = (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - (t.x[2] - t.x[0]) * (t.y[1] - t.y[0]);
  if (area2 == 0.0) {
    q.depth = std::min({t.z[0], t.z[1], t.z[2]});
    q.gradient = std::numeric_limits<double>::infinity();
    return q;
  }
  // Edge function i is opposite vertex i; divided by the doubled area it is barycentric i.
  double b[3], gx = 0, gy = 0;
  bool inside = true;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    const double ex = t.x[k] - t.x[j], ey = t.y[k] - t.y[j];
    const double e = ex * (py - t.y[j]) - ey * (px - t.x[j]);
    b[i] = e / area2;
    inside = inside && b[i] > 0.0;
    gx += t.z[i] * (-ey) / area2;
    gy += t.z[i] * ex / area2;
  }
  q.inside = inside;
  q.depth = b[0] * t.z[0] + b[1] * t.z[1] + b[2] * t.z[2];
  q.gradient = std::sqrt(gx * gx + gy * gy);
  return q;
}

}  // namespace tessera::verify
