// The camera of the atlas tree renderer (Buchholz's thesis §4.4, §4.6): a look-at pinhole camera with a
// horizontal field of view, its GL matrices, its view frustum, and the two geometric tests that the
// traversal asks of it (is a node's box outside the frustum, how far is the box from the eye).
//
// Implements: view / projection / view-projection matrices (glm::dmat4, computed in double; glm::mat4,
// rounded to float once at the end), frustum planes extracted from the double view-projection (Gribb &
// Hartmann), a conservative box-versus-frustum test, the eye-to-box distance and camera validation.
// Does not implement: camera paths and their file format (camera_path.h), the traversal that uses these
// tests (traversal.h).
#pragma once

#include <array>
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <string_view>

namespace tessera::mta {

struct Camera {
  glm::dvec3 eye{0, 0, 0}, target{0, 0, 0}, up{0, 1, 0};  // world space; glTF convention: +y is up
  double tanHalfFovX = 0.5773502691896257;                 // tan(horizontal fov / 2); default 60 degrees
  double nearPlane = 0.1, farPlane = 1000.0;
};

struct Plane {
  double a, b, c, d;  // a*x + b*y + c*z + d >= 0 is inside; (a, b, c) has unit length
};
struct Frustum {
  std::array<Plane, 6> planes;  // left, right, bottom, top, near, far
};

// Column-major 4x4 matrices as GL expects (m[c][r]); viewProjection = projection * view, GLM's product
// in double (each entry ((p0 + p1) + p2) + p3).
// The view matrix is gluLookAt's: the camera looks down -z, +y of the view is the projection of `up`.
// The projection is a symmetric perspective with tan(fovX/2) = tanHalfFovX and aspect = width / height
// (so tan(fovY/2) = tanHalfFovX / aspect), with GL's clip conventions (-w <= z <= w inside).
// The float versions are the double versions rounded once, so that a caller who needs more precision
// (frustum planes, analysis) sees the same transform as the rasterizer, only unrounded.
// Preconditions: validate(camera) passes; width, height >= 1.
glm::dmat4 viewMatrixD(const Camera& c);
glm::dmat4 projectionMatrixD(const Camera& c, uint32_t width, uint32_t height);
glm::dmat4 viewProjectionD(const Camera& c, uint32_t width, uint32_t height);
glm::mat4 viewMatrix(const Camera& c);
glm::mat4 projectionMatrix(const Camera& c, uint32_t width, uint32_t height);
glm::mat4 viewProjection(const Camera& c, uint32_t width, uint32_t height);

// The six clip planes of viewProjectionD (left, right, bottom, top, near, far), normalised so that
// a*x + b*y + c*z + d is the signed Euclidean distance to the plane (positive inside).
Frustum frustumOf(const Camera& c, uint32_t width, uint32_t height);

// Axis-aligned box bounds {minx, miny, minz, maxx, maxy, maxz}.
// True only if the whole box lies on the outside of one plane. Conservative: a box that is outside the
// frustum but straddles two planes near a frustum edge or corner is reported as not outside (it is then
// merely drawn or loaded although invisible, never dropped although visible).
bool outsideFrustum(const Frustum& f, const std::array<float, 6>& bounds);

// Euclidean distance from `eye` to the closest point of the box, 0 if the eye is inside or on it.
double distanceToBox(const glm::dvec3& eye, const std::array<float, 6>& bounds);

// Throws Error("<where>: camera <field>: <reason>") unless every value is finite, eye != target, up is
// not (nearly) parallel to the view direction, 0 < near < far and tanHalfFovX > 0.
void validate(const Camera& c, std::string_view where);

}  // namespace tessera::mta
