#include "mta/split.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace tessera::mta {

namespace {

double coord(const glm::vec3& p, int axis) { return p[axis]; }

double midpoint(const Geometry& g, uint32_t t, int axis) {
  return (coord(g.positions[t * 3], axis) + coord(g.positions[t * 3 + 1], axis) + coord(g.positions[t * 3 + 2], axis)) / 3.0;
}

// Splits `tris` (sorted by the midpoint on `axis`) into a prefix and a suffix of balanced area.
std::pair<std::vector<uint32_t>, std::vector<uint32_t>> halve(const Geometry& g, std::vector<uint32_t> tris, int axis) {
  const size_t n = tris.size();
  std::vector<std::pair<double, uint32_t>> keyed(n);
  for (size_t i = 0; i < n; ++i) keyed[i] = {midpoint(g, tris[i], axis), uint32_t(i)};
  std::sort(keyed.begin(), keyed.end());  // (coordinate, input position): a total order
  std::vector<uint32_t> sorted(n);
  for (size_t i = 0; i < n; ++i) sorted[i] = tris[keyed[i].second];
  double total = 0.0;
  for (uint32_t t : sorted) total = total + triangleArea(g, t);
  size_t k = n / 2;
  if (total > 0.0) {
    double prefix = 0.0, best = 1e308;
    for (size_t i = 1; i < n; ++i) {  // k in [1, n-1]: both halves non-empty
      prefix = prefix + triangleArea(g, sorted[i - 1]);
      const double diff = std::fabs(prefix - 0.5 * total);
      if (diff < best) best = diff, k = i;
    }
  }
  std::vector<uint32_t> a(sorted.begin(), sorted.begin() + ptrdiff_t(k)), b(sorted.begin() + ptrdiff_t(k), sorted.end());
  return {std::move(a), std::move(b)};
}

}  // namespace

double triangleArea(const Geometry& g, uint32_t t) {
  const glm::dvec3 a(g.positions[t * 3]);
  const glm::dvec3 e1 = glm::dvec3(g.positions[t * 3 + 1]) - a, e2 = glm::dvec3(g.positions[t * 3 + 2]) - a;
  return 0.5 * glm::length(glm::cross(e1, e2));  // in double; sqrt((x·x + y·y) + z·z), correctly rounded
}

std::array<int, 2> splitAxes(const Geometry& g, std::span<const uint32_t> tris) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (uint32_t t : tris)
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) {
        const double c = coord(g.positions[t * 3 + k], a);
        lo[a] = std::min(lo[a], c);
        hi[a] = std::max(hi[a], c);
      }
  int axes[3] = {0, 1, 2};
  std::stable_sort(axes, axes + 3, [&](int a, int b) { return hi[a] - lo[a] > hi[b] - lo[b]; });
  return {axes[0], axes[1]};
}

std::array<std::vector<uint32_t>, 4> splitTriangles(const Geometry& g, std::span<const uint32_t> tris) {
  const auto axes = splitAxes(g, tris);
  std::array<std::vector<uint32_t>, 4> out;
  auto [first, second] = halve(g, std::vector<uint32_t>(tris.begin(), tris.end()), axes[0]);
  auto place = [&](std::vector<uint32_t> half, int column) {
    if (half.size() < 2) {
      out[column] = std::move(half);
      return;
    }
    auto [bottom, top] = halve(g, std::move(half), axes[1]);
    out[column] = std::move(bottom);
    out[2 + column] = std::move(top);
  };
  place(std::move(first), 0);
  place(std::move(second), 1);
  return out;
}

}  // namespace tessera::mta
