#include "mta/camera.h"

#include <cmath>
#include <string>

#include "base/error.h"

namespace tessera::mta {

namespace {

using V3 = std::array<double, 3>;

V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const V3& a, const V3& b) { return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2]; }
V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
// sqrt is correctly rounded (IEEE 754), so this is as deterministic as + - * /.
V3 normalized(const V3& v) {
  const double l = std::sqrt(dot(v, v));
  return {v[0] / l, v[1] / l, v[2] / l};
}

std::array<float, 16> toFloat(const std::array<double, 16>& m) {
  std::array<float, 16> r;
  for (int i = 0; i < 16; ++i) r[i] = float(m[i]);
  return r;
}

// Column-major product a * b with a fixed summation order (k = 0..3), so the bits never depend on the
// compiler's choice of association.
std::array<double, 16> multiply(const std::array<double, 16>& a, const std::array<double, 16>& b) {
  std::array<double, 16> r{};
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row)
      r[c * 4 + row] =
          ((a[0 * 4 + row] * b[c * 4 + 0] + a[1 * 4 + row] * b[c * 4 + 1]) + a[2 * 4 + row] * b[c * 4 + 2]) +
          a[3 * 4 + row] * b[c * 4 + 3];
  return r;
}

}  // namespace

std::array<double, 16> viewMatrixD(const Camera& c) {
  const V3 f = normalized(sub(c.target, c.eye));
  const V3 s = normalized(cross(f, c.up));
  const V3 u = cross(s, f);  // unit: s and f are orthonormal
  std::array<double, 16> m{};
  for (int i = 0; i < 3; ++i) {
    m[i * 4 + 0] = s[i];
    m[i * 4 + 1] = u[i];
    m[i * 4 + 2] = -f[i];
  }
  m[12] = -dot(s, c.eye);
  m[13] = -dot(u, c.eye);
  m[14] = dot(f, c.eye);
  m[15] = 1.0;
  return m;
}

std::array<double, 16> projectionMatrixD(const Camera& c, uint32_t width, uint32_t height) {
  // aspect = w / h, tan(fovY/2) = tan(fovX/2) / aspect: the horizontal angle is the one the thesis's
  // f_proj is defined with (params.h), so it must stay fixed when the window's shape changes.
  const double aspect = double(width) / double(height);
  const double n = c.nearPlane, f = c.farPlane;
  std::array<double, 16> m{};
  m[0] = 1.0 / c.tanHalfFovX;
  m[5] = aspect / c.tanHalfFovX;
  m[10] = (f + n) / (n - f);
  m[11] = -1.0;
  m[14] = 2.0 * f * n / (n - f);
  return m;
}

std::array<double, 16> viewProjectionD(const Camera& c, uint32_t width, uint32_t height) {
  return multiply(projectionMatrixD(c, width, height), viewMatrixD(c));
}

std::array<float, 16> viewMatrix(const Camera& c) { return toFloat(viewMatrixD(c)); }
std::array<float, 16> projectionMatrix(const Camera& c, uint32_t width, uint32_t height) {
  return toFloat(projectionMatrixD(c, width, height));
}
std::array<float, 16> viewProjection(const Camera& c, uint32_t width, uint32_t height) {
  return toFloat(viewProjectionD(c, width, height));
}

Frustum frustumOf(const Camera& c, uint32_t width, uint32_t height) {
  // Gribb & Hartmann: a clip-space point is inside iff -w <= x, y, z <= w, i.e. row3 ± row_i >= 0 applied
  // to the world point. Extracted from the double matrix so that culling is not blurred by float rounding.
  const std::array<double, 16> m = viewProjectionD(c, width, height);
  auto row = [&](int r) { return std::array<double, 4>{m[0 + r], m[4 + r], m[8 + r], m[12 + r]}; };
  const auto r0 = row(0), r1 = row(1), r2 = row(2), r3 = row(3);
  auto plane = [&](const std::array<double, 4>& a, double sign) {
    Plane p{r3[0] + sign * a[0], r3[1] + sign * a[1], r3[2] + sign * a[2], r3[3] + sign * a[3]};
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

double distanceToBox(const std::array<double, 3>& eye, const std::array<float, 6>& b) {
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
  auto finite3 = [](const V3& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); };
  if (!finite3(c.eye)) bad("eye", "must be finite");
  if (!finite3(c.target)) bad("target", "must be finite");
  if (!finite3(c.up)) bad("up", "must be finite");
  const V3 dir = sub(c.target, c.eye);
  const double dd = dot(dir, dir), uu = dot(c.up, c.up);
  if (!(dd > 0.0)) bad("target", "equals the eye (no view direction)");
  if (!std::isfinite(dd)) bad("target", "is too far from the eye");
  if (!(uu > 0.0) || !std::isfinite(uu)) bad("up", "must be a non-zero finite vector");
  // |dir x up|² = |dir|²|up|² sin²θ: reject angles below ~1e-6 rad, where the view's side axis would be
  // mostly rounding noise.
  const V3 x = cross(dir, c.up);
  if (!(dot(x, x) > 1e-12 * dd * uu)) bad("up", "is parallel to the view direction");
  if (!std::isfinite(c.tanHalfFovX) || !(c.tanHalfFovX > 0.0)) bad("tan_half_fov", "must be a finite number > 0");
  if (!std::isfinite(c.nearPlane) || !(c.nearPlane > 0.0)) bad("near", "must be a finite number > 0");
  if (!std::isfinite(c.farPlane) || !(c.farPlane > c.nearPlane)) bad("far", "must be finite and greater than near");
}

}  // namespace tessera::mta
