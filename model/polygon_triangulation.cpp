#include "model/polygon_triangulation.h"

#include <cmath>
#include <glm/vec2.hpp>

namespace tessera::model::detail {

namespace {

// Twice the signed area of triangle (a, b, c): positive when it turns counter-clockwise.
double orient(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// The corners projected onto the coordinate plane the Newell normal is most aligned with, the two axes
// ordered so that the polygon turns counter-clockwise in the plane. The axis choice (ties included)
// follows Assimp's, so that near-degenerate polygons are projected the same way.
std::vector<glm::dvec2> project(std::span<const glm::vec3> c) {
  const size_t n = c.size();
  glm::dvec3 normal(0.0);
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec3 a(c[i]), b(c[(i + 1) % n]);
    normal.x += (a.y - b.y) * (a.z + b.z);
    normal.y += (a.z - b.z) * (a.x + b.x);
    normal.z += (a.x - b.x) * (a.y + b.y);
  }
  const double ax = std::fabs(normal.x), ay = std::fabs(normal.y), az = std::fabs(normal.z);
  int u = 0, v = 1;  // drop z
  double facing = normal.z;
  if (ax > ay) {
    if (ax > az) u = 1, v = 2, facing = normal.x;  // drop x
  } else if (ay > az) {
    u = 2, v = 0, facing = normal.y;  // drop y
  }
  if (facing < 0.0) std::swap(u, v);
  std::vector<glm::dvec2> p(n);
  for (size_t i = 0; i < n; ++i) p[i] = glm::dvec2(double(c[i][u]), double(c[i][v]));
  return p;
}

void emit(std::vector<uint32_t>& out, size_t a, size_t b, size_t c) {
  out.push_back(uint32_t(a));
  out.push_back(uint32_t(b));
  out.push_back(uint32_t(c));
}

// Ear clipping of the projected polygon `p`, appending triangles to `out`. Candidates are tried in
// corner order from the last clipped ear on (from corner 0, with the last corner before it, at the
// start); two wraps past corner 0 without an ear mean there is none. A candidate is rejected when it is
// reflex or a blocker lies strictly inside it (or, with `touching`, on its boundary). Returns false when
// no ear was found or `work` ran out: the corners left are then fanned around the first of them.
bool earClip(const std::vector<glm::dvec2>& p, const std::vector<size_t>& blockers, bool touching,
             std::vector<uint32_t>& out, uint64_t& work) {
  const size_t n = p.size();
  auto earFree = [&](size_t a, size_t b, size_t c) {
    const double area = orient(p[a], p[b], p[c]);
    if (area < 0.0) return false;  // reflex at b
    if (area == 0.0) return true;  // nothing lies strictly inside a flat triangle
    for (size_t k : blockers) {
      if (work > 0) --work;
      const glm::dvec2& q = p[k];
      if (q == p[a] || q == p[b] || q == p[c]) continue;  // a repeated position is not inside
      const double ab = orient(p[a], p[b], q), bc = orient(p[b], p[c], q), ca = orient(p[c], p[a], q);
      if (touching ? ab >= 0.0 && bc >= 0.0 && ca >= 0.0 : ab > 0.0 && bc > 0.0 && ca > 0.0) return false;
    }
    return true;
  };
  std::vector<char> done(n, 0);
  size_t left = n, prev = n - 1, next = 0;
  bool clean = true;
  while (left > 3) {
    size_t ear = next;
    int wraps = 0;
    bool found = false;
    while (work > 0) {
      --work;
      next = ear + 1;
      for (;; ++next) {
        if (next >= n) next = 0;
        if (!done[next]) break;
      }
      if (next < ear && ++wraps == 2) break;
      if (earFree(prev, ear, next)) {
        found = true;
        break;
      }
      prev = ear;
      ear = next;
    }
    if (!found) {
      clean = false;
      break;
    }
    emit(out, prev, ear, next);
    done[ear] = 1;
    --left;
  }
  // The last three corners (or, when clipping stopped, all that remain) in corner order, fanned.
  std::vector<size_t> rest;
  for (size_t i = 0; i < n; ++i)
    if (!done[i]) rest.push_back(i);
  for (size_t i = 1; i + 1 < rest.size(); ++i) emit(out, rest[0], rest[i], rest[i + 1]);
  return clean;
}

}  // namespace

bool triangulatePolygon(std::span<const glm::vec3> corners, std::vector<uint32_t>& out, uint64_t& work) {
  const size_t n = corners.size();
  if (n == 3) {
    emit(out, 0, 1, 2);
    return true;
  }
  const std::vector<glm::dvec2> p = project(corners);
  if (n == 4) {
    // A simple quad has at most one reflex corner; the diagonal from it is the one inside the quad.
    size_t s = 0;
    for (size_t i = 0; i < 4; ++i)
      if (orient(p[(i + 3) % 4], p[i], p[(i + 1) % 4]) < 0.0) {
        s = i;
        break;
      }
    emit(out, s, (s + 1) % 4, (s + 2) % 4);
    emit(out, s, (s + 2) % 4, (s + 3) % 4);
    return true;
  }

  // Corners that may block an ear: those not strictly convex in the original polygon. Clipping an ear
  // only makes the angles at its neighbours smaller, so this stays a superset of the remaining
  // polygon's reflex corners.
  std::vector<size_t> blockers;
  for (size_t i = 0; i < n; ++i)
    if (orient(p[(i + n - 1) % n], p[i], p[(i + 1) % n]) <= 0.0) blockers.push_back(i);
  const size_t first = out.size();
  bool clean = earClip(p, blockers, false, out, work);
  // Every triangle turning the polygon's way proves the cover exact (the triangles' winding numbers add
  // up to the polygon's, so none can overlap another or leave the outline). Assimp's strict test fails
  // that when a corner touches a clipped diagonal; then the polygon is clipped again, a corner on a
  // candidate's boundary blocking it too.
  for (size_t i = first; i < out.size(); i += 3)
    if (orient(p[out[i]], p[out[i + 1]], p[out[i + 2]]) < 0.0) {
      out.resize(first);
      clean = earClip(p, blockers, true, out, work) && clean;
      break;
    }
  return clean;
}

}  // namespace tessera::model::detail
