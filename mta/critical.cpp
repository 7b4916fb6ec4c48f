#include "mta/critical.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "base/error.h"

namespace tessera::mta {

namespace {

struct Tri {
  glm::vec3 p[3];
  std::vector<glm::vec2> uv;  // 3 per layer
};

AreaRequirement requirementOf(const Scene& s, int32_t tex, const glm::vec3 p[3], const glm::vec2 t[3], double fProj,
                              uint32_t border, double* uw, double* uh) {
  const TexelSize size = triangleTexelSize(p, t, fProj);
  TexRect rect;
  for (int k = 0; k < 3; ++k) rect.add(t[k]);
  const SceneImage& img = s.images[s.textures[tex].image];
  if (size.ignored) {
    if (uw) *uw = 1.0;
    if (uh) *uh = 1.0;
    return requiredArea(TexelSize{1.0, 1.0, true, false}, rect, img.width, img.height, border);
  }
  return requiredArea(size, rect, img.width, img.height, border, uw, uh);
}

// The midpoint in double, rounded to float once.
glm::vec3 mid(const glm::vec3& a, const glm::vec3& b) { return glm::vec3(0.5 * (glm::dvec3(a) + glm::dvec3(b))); }
glm::vec2 mid(const glm::vec2& a, const glm::vec2& b) { return glm::vec2(0.5 * (glm::dvec2(a) + glm::dvec2(b))); }

// Splits `t` until no piece is critical; appends the pieces in order.
void splitRecursive(const Scene& s, int32_t tex, const Tri& t, double fProj, const BuildParams& p, uint32_t depth,
                    std::vector<Tri>& out, uint32_t& maxDepth) {
  const AreaRequirement r = requirementOf(s, tex, t.p, t.uv.data(), fProj, p.border, nullptr, nullptr);
  if (!isCritical(r, p.atlasSize)) {
    out.push_back(t);
    maxDepth = std::max(maxDepth, depth);
    return;
  }
  if (depth >= 40) throw Error("mta: a triangle is still critical after 40 levels of splitting; raise d_min or the atlas size");
  // Longest edge in required texels: (du · w_tex)² + (dv · h_tex)² with the triangle's own per-repeat size.
  const TexelSize ts = triangleTexelSize(t.p, t.uv.data(), fProj);
  const double sw = ts.ignored ? 1.0 : std::min(ts.w, double(s.images[s.textures[tex].image].width));
  const double sh = ts.ignored ? 1.0 : std::min(ts.h, double(s.images[s.textures[tex].image].height));
  int best = 0;
  double bestLen = -1.0;
  for (int e = 0; e < 3; ++e) {
    const glm::vec2 &a = t.uv[e], &b = t.uv[(e + 1) % 3];
    const double du = (double(b.x) - a.x) * sw, dv = (double(b.y) - a.y) * sh;
    const double l = du * du + dv * dv;
    if (l > bestLen) bestLen = l, best = e;
  }
  const int i0 = best, i1 = (best + 1) % 3, i2 = (best + 2) % 3;
  const size_t layers = t.uv.size() / 3;
  Tri a, b;  // (v0, m, v2) and (m, v1, v2) with v0 = i0, v1 = i1: both keep the winding
  a.uv.resize(t.uv.size());
  b.uv.resize(t.uv.size());
  const glm::vec3 mp = mid(t.p[i0], t.p[i1]);
  a.p[0] = t.p[i0], a.p[1] = mp, a.p[2] = t.p[i2];
  b.p[0] = mp, b.p[1] = t.p[i1], b.p[2] = t.p[i2];
  for (size_t l = 0; l < layers; ++l) {
    const glm::vec2* u = &t.uv[l * 3];
    const glm::vec2 mu = mid(u[i0], u[i1]);
    a.uv[l * 3] = u[i0], a.uv[l * 3 + 1] = mu, a.uv[l * 3 + 2] = u[i2];
    b.uv[l * 3] = mu, b.uv[l * 3 + 1] = u[i1], b.uv[l * 3 + 2] = u[i2];
  }
  splitRecursive(s, tex, a, fProj, p, depth + 1, out, maxDepth);
  splitRecursive(s, tex, b, fProj, p, depth + 1, out, maxDepth);
}

}  // namespace

bool isCritical(const AreaRequirement& r, uint32_t atlasSize) { return r.w > atlasSize || r.h > atlasSize; }

AreaRequirement triangleRequirement(const Scene& s, const Geometry& g, uint32_t t, double fProj, uint32_t border,
                                    double* uncappedW, double* uncappedH) {
  const int32_t tex = g.layers[0].texture[t];
  if (tex < 0) return AreaRequirement{};
  return requirementOf(s, tex, &g.positions[t * 3], &g.layers[0].uv[t * 3], fProj, border, uncappedW, uncappedH);
}

Geometry handleCriticalTriangles(const Scene& s, const BuildParams& p, double dMinRequested, CriticalReport& rep) {
  const Geometry& g = s.geometry;
  const uint32_t n = uint32_t(g.triangleCount());
  rep = CriticalReport{};
  rep.triangles = n;
  rep.dMinRequested = dMinRequested;
  std::vector<uint8_t> critical(n);
  std::vector<double> need(n);  // d_min at which the triangle stops being critical (upper bound)
  auto evaluate = [&](double d) {
    const double fProj = projectionFactor(p, d);
    tbb::parallel_for(uint32_t(0), n, [&](uint32_t t) {
      double uw = 0.0, uh = 0.0;
      const AreaRequirement r = triangleRequirement(s, g, t, fProj, p.border, &uw, &uh);
      critical[t] = isCritical(r, p.atlasSize);
      need[t] = critical[t] ? d * std::max(uw, uh) / double(p.atlasSize - 2 * p.border) : 0.0;
    });
    uint64_t c = 0;
    for (uint8_t x : critical) c += x;  // integer sum: order-free
    return c;
  };
  double d = dMinRequested;
  uint64_t count = evaluate(d);
  rep.criticalAtRequested = count;
  uint64_t textured = 0;
  for (uint32_t t = 0; t < n; ++t) textured += g.layers[0].texture[t] >= 0;
  const uint64_t allowed = uint64_t(std::floor(p.criticalThreshold * double(textured)));
  for (int step = 0; count > allowed && step < 8; ++step) {
    std::vector<double> needs;
    for (uint32_t t = 0; t < n; ++t)
      if (critical[t]) needs.push_back(need[t]);
    std::sort(needs.begin(), needs.end());
    d = std::max(d, needs[needs.size() - allowed - 1] * (1.0 + 1e-9));
    count = evaluate(d);
  }
  rep.dMinUsed = d;
  rep.criticalAfterRaise = count;
  if (count == 0) return g;
  const double fProj = projectionFactor(p, d);
  const size_t layers = g.layers.size();
  std::vector<std::vector<Tri>> pieces(n);
  std::vector<uint32_t> depths(n, 0);
  tbb::parallel_for(uint32_t(0), n, [&](uint32_t t) {
    if (!critical[t]) return;
    Tri tri;
    for (int k = 0; k < 3; ++k) tri.p[k] = g.positions[t * 3 + k];
    tri.uv.resize(layers * 3);
    for (size_t l = 0; l < layers; ++l)
      for (int k = 0; k < 3; ++k) tri.uv[l * 3 + k] = g.layers[l].uv[t * 3 + k];
    splitRecursive(s, g.layers[0].texture[t], tri, fProj, p, 0, pieces[t], depths[t]);
  });
  Geometry out;
  out.layers.resize(layers);
  for (uint32_t t = 0; t < n; ++t) {
    auto emit = [&](const glm::vec3* pos, auto uvOf) {
      for (int k = 0; k < 3; ++k) out.positions.push_back(pos[k]);
      out.source.push_back(g.source[t]);
      out.alpha.push_back(g.alpha[t]);
      for (size_t l = 0; l < layers; ++l) {
        out.layers[l].texture.push_back(g.layers[l].texture[t]);
        for (int k = 0; k < 3; ++k) out.layers[l].uv.push_back(uvOf(l, k));
      }
    };
    if (!critical[t]) {
      emit(&g.positions[t * 3], [&](size_t l, int k) { return g.layers[l].uv[t * 3 + k]; });
    } else {
      rep.maxSplitDepth = std::max(rep.maxSplitDepth, depths[t]);
      rep.trianglesAdded += pieces[t].size() - 1;
      for (const Tri& tri : pieces[t]) emit(tri.p, [&](size_t l, int k) { return tri.uv[l * 3 + k]; });
    }
  }
  return out;
}

}  // namespace tessera::mta
