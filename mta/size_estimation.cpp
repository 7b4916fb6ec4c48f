#include "mta/size_estimation.h"

#include <algorithm>
#include <cmath>

namespace tessera::mta {

namespace {

constexpr double kTexDegenerate = 1e-3;

struct D3 {
  double x, y, z;
};
D3 sub(const Float3& a, const Float3& b) { return {double(a.x) - b.x, double(a.y) - b.y, double(a.z) - b.z}; }
double len(const D3& a) { return std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z); }

}  // namespace

TexelSize triangleTexelSize(const Float3 v[3], const Float2 t[3], double fProj) {
  TexelSize r;
  const D3 e1 = sub(v[1], v[0]), e2 = sub(v[2], v[0]);
  const D3 c{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
  const double l1 = len(e1), l2 = len(e2);
  if (!(len(c) > 1e-12 * l1 * l2) || l1 == 0.0 || l2 == 0.0) {
    r.ignored = true;
    return r;
  }
  // Texture-space edges, translated so that t0 = 0.
  const double a1 = double(t[1].u) - t[0].u, b1 = double(t[1].v) - t[0].v;
  const double a2 = double(t[2].u) - t[0].u, b2 = double(t[2].v) - t[0].v;
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
    const double world = len(sub(v[kEdge[k][1]], v[kEdge[k][0]]));
    r.w = r.h = world / te[k] * fProj;
    return r;
  }
  // Tex_T^-1((1,0)) = (b2, -b1) / det; Tex_T^-1((0,1)) = (-a2, a1) / det; P_T(a, b) = a·e1 + b·e2.
  const double sa = b2 / det, sb = -b1 / det, ta = -a2 / det, tb = a1 / det;
  const D3 s{sa * e1.x + sb * e2.x, sa * e1.y + sb * e2.y, sa * e1.z + sb * e2.z};
  const D3 tw{ta * e1.x + tb * e2.x, ta * e1.y + tb * e2.y, ta * e1.z + tb * e2.z};
  r.w = len(s) * fProj;
  r.h = len(tw) * fProj;
  return r;
}

void TexRect::add(const Float2& t) {
  u0 = std::min(u0, double(t.u));
  u1 = std::max(u1, double(t.u));
  v0 = std::min(v0, double(t.v));
  v1 = std::max(v1, double(t.v));
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

std::pair<double, double> repeatShift(const Float2 t[3], model::Wrap wrapS, model::Wrap wrapT) {
  auto shift = [](double lo, model::Wrap w) {
    if (w == model::Wrap::ClampToEdge || !(std::fabs(lo) < 4.0e15)) return 0.0;
    const double period = w == model::Wrap::MirroredRepeat ? 2.0 : 1.0;
    return period * std::floor(lo / period);
  };
  const double u = std::min(double(t[0].u), std::min(double(t[1].u), double(t[2].u)));
  const double v = std::min(double(t[0].v), std::min(double(t[1].v), double(t[2].v)));
  return {shift(u, wrapS), shift(v, wrapT)};
}

}  // namespace tessera::mta
