// Triangle set subdivision of a node (thesis §4.5.3, paper §5.3).
//
// Implements: the area-balanced greedy split: the two axes along which the triangles' bounding box is
// largest (ties: x before y before z), the triangles sorted by their midpoint along the first axis
// (stable, key (coordinate, position in the input)), cut at the k whose prefix area is closest to half
// the total, then each half the same way along the second axis.
// Guarantee: no child is empty: k is restricted to [1, n - 1], and a half of one triangle is not cut
// again. A node with 2 or 3 triangles therefore gets 2 or 3 children.
// Does not implement: the decision to split (tree_build.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "mta/scene.h"

namespace tessera::mta {

// Children by atlas quadrant (§4.5.4): 0 = first half on axis 1 and 2 (bottom-left), 1 = second half
// on axis 1 (bottom-right), 2 = second half on axis 2 (top-left), 3 = top-right. Requires tris.size() >= 2.
std::array<std::vector<uint32_t>, 4> splitTriangles(const Geometry& g, std::span<const uint32_t> tris);

// The two axes (0 = x, 1 = y, 2 = z) of the largest extents of the triangles' bounding box, largest first.
std::array<int, 2> splitAxes(const Geometry& g, std::span<const uint32_t> tris);

// World-space area of triangle t (double).
double triangleArea(const Geometry& g, uint32_t t);

}  // namespace tessera::mta
