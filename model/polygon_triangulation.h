// Triangulation of one polygon given by its corners in order (the polygons of AC3D surfaces).
//
// Implements: ear clipping on the polygon's projection onto the coordinate plane its Newell normal is
// most aligned with, oriented so that the polygon turns counter-clockwise there, computed in double with
// no transcendental function, so the result is the same on every machine. A quad is split along the
// diagonal from its first reflex corner (corner 0 when it is convex). A larger polygon is clipped ear by
// ear, the search starting at corner 0 with the last corner as its predecessor, so a convex n-gon becomes
// the fan around its last corner. For simple polygons these are the triangles Assimp 5.2's Triangulate
// step made, which AC3D files went through before the project parsed AC3D itself (docs/model-import.md).
// Only corners that are not strictly convex are tested against a candidate ear (for a simple polygon no
// other corner can lie inside one), so a convex polygon costs time linear in its corners. Like Assimp,
// a candidate is rejected for a corner strictly inside it; when a corner touches a clipped diagonal that
// can make a triangle turn the wrong way and overlap the others (an L-shaped hexagon does), so a result
// with such a triangle is discarded and the polygon clipped again, a corner on a candidate's boundary
// rejecting it too.
// Does not implement: holes, repair of self-intersecting or strongly non-planar polygons, or removal of
// zero-area triangles (collinear corners count as convex, as in Assimp). When no ear is left, or the
// caller's work budget runs out, the corners that remain are fanned around the first of them and the
// result says so: a hostile polygon costs bounded time, never a hang.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

namespace tessera::model::detail {

// Appends 3 * (corners.size() - 2) indices into `corners` to `out`, each triangle turning the same way
// as the corner order (a counter-clockwise polygon gives counter-clockwise triangles).
// `work` is the caller's budget of elementary steps (one candidate ear or one corner tested against
// it); it is decreased by what this polygon used.
// Precondition: corners.size() >= 3. Returns false when the ear clipping had to stop (the polygon is
// not simple, or `work` ran out) and the rest was fanned; true otherwise.
bool triangulatePolygon(std::span<const glm::vec3> corners, std::vector<uint32_t>& out, uint64_t& work);

}  // namespace tessera::model::detail
