#include "mta/camera.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <string>

#include "base/error.h"

namespace tessera::mta {

namespace {

// v / |v|: GLM's normalize multiplies by an inverse square root and gives other bits. sqrt is correctly
// rounded (IEEE 754), so this is as deterministic as + - * /. glm::dot is (x·x' + y·y') + z·z' and
// glm::cross the usual a.y·b.z - a.z·b.y, ...: the orders this file has always used.
glm::dvec3 normalized(const glm::dvec3& v) { return v / glm::length(v); }

}  // namespace

glm::dmat4 viewMatrixD(const Camera& c) {
  const glm::dvec3 f = normalized(c.target - c.eye);
  const glm::dvec3 s = normalized(glm::cross(f, c.up));
  const glm::dvec3 u = glm::cross(s, f);  // unit: s and f are orthonormal
  glm::dmat4 m(0.0);
  for (int i = 0; i < 3; ++i) {
    m[i][0] = s[i];
    m[i][1] = u[i];
    m[i][2] = -f[i];
  }
  m[3][0] = -glm::dot(s, c.eye);
  m[3][1] = -glm::dot(u, c.eye);
  m[3][2] = glm::dot(f, c.eye);
  m[3][3] = 1.0;
  return m;
}

glm::dmat4 projectionMatrixD(const Camera& c, uint32_t width, uint32_t height) {
  // aspect = w / h, tan(fovY/2) = tan(fovX/2) / aspect: the horizontal angle is the one the thesis's
  // f_proj is defined with (params.h), so it must stay fixed when the window's shape changes.
  const double aspect = double(width) / double(height);
  const double n = c.nearPlane, f = c.farPlane;
  glm::dmat4 m(0.0);
  m[0][0] = 1.0 / c.tanHalfFovX;
  m[1][1] = aspect / c.tanHalfFovX;
  m[2][2] = (f + n) / (n - f);
  m[2][3] = -1.0;
  m[3][2] = 2.0 * f * n / (n - f);
  return m;
}

glm::dmat4 viewProjectionD(const Camera& c, uint32_t width, uint32_t height) {
  return projectionMatrixD(c, width, height) * viewMatrixD(c);
}

glm::mat4 viewMatrix(const Camera& c) { return glm::mat4(viewMatrixD(c)); }
glm::mat4 projectionMatrix(const Camera& c, uint32_t width, uint32_t height) {
  return glm::mat4(projectionMatrixD(c, width, height));
}
glm::mat4 viewProjection(const Camera& c, uint32_t width, uint32_t height) {
  return glm::mat4(viewProjectionD(c, width, height));
}

Frustum frustumOf(const Camera& c, uint32_t width, uint32_t height) {
  // Gribb & Hartmann: a clip-space point is inside iff -w <= x, y, z <= w, i.e. row3 ± row_i >= 0 applied
  // to the world point. Extracted from the double matrix so that culling is not blurred by float rounding.
  const glm::dmat4 m = viewProjectionD(c, width, height);
  auto row = [&](int r) { return glm::dvec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
  const glm::dvec4 r0 = row(0), r1 = row(1), r2 = row(2), r3 = row(3);
  auto plane = [&](const glm::dvec4& a, double sign) {
    const glm::dvec4 q = r3 + sign * a;
    Plane p{q.x, q.y, q.z, q.w};
    const double l = std::sqrt((p.a * p.a + p.b * p.b) + p.c * p.c);
    p.a /= l, p.b /= l, p.c /= l, p.d /= l;
    return p;
  };
  Frustum fr;
  fr.planes = {plane(r0, 1.0), plane(r0, -1.0), plane(r1, 1.0), plane(r1, -1.0), plane(r2, 1.0), plane(r2, -1.0)};
  return fr;
}

bool outsideFrustum(const Frustum& f, const std::array<float, 6>& b) {
  for (const Plane& p : f.planes) {
    // The box corner farthest along the plane normal (the "p-vertex"): if even it is outside, all are.
    const double x = p.a >= 0.0 ? b[3] : b[0];
    const double y = p.b >= 0.0 ? b[4] : b[1];
    const double z = p.c >= 0.0 ? b[5] : b[2];
    if (((p.a * x + p.b * y) + p.c * z) + p.d < 0.0) return true;
  }
  return false;
}

double distanceToBox(const glm::dvec3& eye, const std::array<float, 6>& b) {
  double s = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double lo = b[k], hi = b[k + 3];
    const double d = eye[k] < lo ? lo - eye[k] : eye[k] > hi ? eye[k] - hi : 0.0;
    s += d * d;
  }
  return std::sqrt(s);
}

void validate(const Camera& c, std::string_view where) {
  auto bad = [&](const char* field, const std::string& why) {
    throw Error(std::string(where) + ": camera " + field + ": " + why);
  };
  auto finite3 = [](const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  if (!finite3(c.eye)) bad("eye", "must be finite");
  if (!finite3(c.target)) bad("target", "must be finite");
  if (!finite3(c.up)) bad("up", "must be finite");
  const glm::dvec3 dir = c.target - c.eye;
  const double dd = glm::dot(dir, dir), uu = glm::dot(c.up, c.up);
  if (!(dd > 0.0)) bad("target", "equals the eye (no view direction)");
  if (!std::isfinite(dd)) bad("target", "is too far from the eye");
  if (!(uu > 0.0) || !std::isfinite(uu)) bad("up", "must be a non-zero finite vector");
  // |dir x up|² = |dir|²|up|² sin²θ: reject angles below ~1e-6 rad, where the view's side axis would be
  // mostly rounding noise.
  const glm::dvec3 x = glm::cross(dir, c.up);
  if (!(glm::dot(x, x) > 1e-12 * dd * uu)) bad("up", "is parallel to the view direction");
  if (!std::isfinite(c.tanHalfFovX) || !(c.tanHalfFovX > 0.0)) bad("tan_half_fov", "must be a finite number > 0");
  if (!std::isfinite(c.nearPlane) || !(c.nearPlane > 0.0)) bad("near", "must be a finite number > 0");
  if (!std::isfinite(c.farPlane) || !(c.farPlane > c.nearPlane)) bad("far", "must be finite and greater than near");
}

}  // namespace tessera::mta
