#include "mta/size_estimation.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace tessera::mta {

namespace {

constexpr double kTexDegenerate = 1e-3;

// In double; glm::length is sqrt((x·x + y·y) + z·z), sqrt correctly rounded.
glm::dvec3 sub(const glm::vec3& a, const glm::vec3& b) { return glm::dvec3(a) - glm::dvec3(b); }

}  // namespace

TexelSize triangleTexelSize(const glm::vec3 v[3], const glm::vec2 t[3], double fProj) {
  TexelSize r;
  const glm::dvec3 e1 = sub(v[1], v[0]), e2 = sub(v[2], v[0]);
  const glm::dvec3 c = glm::cross(e1, e2);
  const double l1 = glm::length(e1), l2 = glm::length(e2);
  if (!(glm::length(c) > 1e-12 * l1 * l2) || l1 == 0.0 || l2 == 0.0) {
    r.ignored = true;
    return r;
  }
  // Texture-space edges, translated so that t0 = 0.
  const double a1 = double(t[1].x) - t[0].x, b1 = double(t[1].y) - t[0].y;
  const double a2 = double(t[2].x) - t[0].x, b2 = double(t[2].y) - t[0].y;
  const double te[3] = {std::sqrt(a1 * a1 + b1 * b1), std::sqrt(a2 * a2 + b2 * b2),
                        std::sqrt((a2 - a1) * (a2 - a1) + (b2 - b1) * (b2 - b1))};
  const double tmax = std::max(te[0], std::max(te[1], te[2]));
  if (tmax == 0.0) {
    r.constant = true;
    r.w = r.h = 1.0;
    return r;
  }
  const double det = a1 * b2 - a2 * b1;
  // Nearly collinear texcoords (doubled area below 1e-3 of the longest edge squared) count as
  // degenerate: Tex_T^-1 would stretch a sliver of texture across the triangle and demand up to 10^6
  // texels for a strip that holds almost no content (railway.glb has such triangles).
  if (std::fabs(det) <= kTexDegenerate * tmax * tmax) {
    // Collinear texcoords: the stretch of the longest texture edge (first longest on ties: 01, 02, 12).
    int k = 0;
    for (int i = 1; i < 3; ++i)
      if (te[i] > te[k]) k = i;
    static constexpr int kEdge[3][2] = {{0, 1}, {0, 2}, {1, 2}};
    const double world = glm::length(sub(v[kEdge[k][1]], v[kEdge[k][0]]));
    r.w = r.h = world / te[k] * fProj;
    return r;
  }
  // Tex_T^-1((1,0)) = (b2, -b1) / det; Tex_T^-1((0,1)) = (-a2, a1) / det; P_T(a, b) = a·e1 + b·e2.
  const double sa = b2 / det, sb = -b1 / det, ta = -a2 / det, tb = a1 / det;
  const glm::dvec3 s = sa * e1 + sb * e2, tw = ta * e1 + tb * e2;
  r.w = glm::length(s) * fProj;
  r.h = glm::length(tw) * fProj;
  return r;
}

void TexRect::add(const glm::vec2& t) {
  u0 = std::min(u0, double(t.x));
  u1 = std::max(u1, double(t.x));
  v0 = std::min(v0, double(t.y));
  v1 = std::max(v1, double(t.y));
}

AreaRequirement requiredArea(const TexelSize& size, const TexRect& atex, uint32_t imageW, uint32_t imageH,
                             uint32_t border, double* uncappedW, double* uncappedH) {
  AreaRequirement r;
  auto inner = [](double perRepeat, double cap, double extent, double* uncapped) -> uint32_t {
    const double raw = perRepeat * extent;
    if (uncapped) *uncapped = raw;
    const double x = std::min(perRepeat, cap) * extent;
    if (!(x > 1.0)) return 1;
    return uint32_t(std::min(std::ceil(x), kMaxInnerExtent));
  };
  if (size.constant) {
    r.innerW = r.innerH = 1;
    if (uncappedW) *uncappedW = 1.0;
    if (uncappedH) *uncappedH = 1.0;
  } else {
    r.innerW = inner(size.w, imageW, atex.width(), uncappedW);
    r.innerH = inner(size.h, imageH, atex.height(), uncappedH);
  }
  r.w = r.innerW + 2 * border;
  r.h = r.innerH + 2 * border;
  // Scale A_tex about its centre so that the inner texels keep their density and the border gets the
  // neighbouring texture content (§4.5.2).
  const double cu = 0.5 * (atex.u0 + atex.u1), cv = 0.5 * (atex.v0 + atex.v1);
  const double hu = 0.5 * atex.width() * double(r.w) / double(r.innerW);
  const double hv = 0.5 * atex.height() * double(r.h) / double(r.innerH);
  r.source = TexRect{cu - hu, cv - hv, cu + hu, cv + hv};
  return r;
}

std::pair<double, double> repeatShift(const glm::vec2 t[3], model::Wrap wrapS, model::Wrap wrapT) {
  auto shift = [](double lo, model::Wrap w) {
    if (w == model::Wrap::ClampToEdge || !(std::fabs(lo) < 4.0e15)) return 0.0;
    const double period = w == model::Wrap::MirroredRepeat ? 2.0 : 1.0;
    return period * std::floor(lo / period);
  };
  const double u = std::min(double(t[0].x), std::min(double(t[1].x), double(t[2].x)));
  const double v = std::min(double(t[0].y), std::min(double(t[1].y), double(t[2].y)));
  return {shift(u, wrapS), shift(v, wrapT)};
}

}  // namespace tessera::mta
