#include "mta/layer_maps.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "base/error.h"
#include "mta/size_estimation.h"

namespace tessera::mta {

namespace {

// Leaf-local atlas texel position of vertex k of triangle t in area e, as the build computes it
// (mta/build.cpp localTexel: layer-0 texcoords shifted into the area's repeat).
std::pair<double, double> atlasTexel(const Scene& s, const Tree& tree, const AtlasEntry& e, uint32_t t, int k) {
  const glm::vec2* uvs = &tree.geometry.layers[0].uv[size_t(t) * 3];
  const auto shift = repeatShift(uvs, s.textures[e.texture].wrapS, s.textures[e.texture].wrapT);
  return entryTexel(e, float(double(uvs[k].x) - shift.first), float(double(uvs[k].y) - shift.second));
}

// The distance from a to b in texels of an image `size` wide along this axis, modulo the wrap period.
double texelDistance(double a, double b, uint32_t size, model::Wrap w) {
  double d = std::fabs(a - b);
  const double period = w == model::Wrap::Repeat ? 1.0 : w == model::Wrap::MirroredRepeat ? 2.0 : 0.0;
  if (period > 0.0) {
    d = std::fmod(d, period);
    d = std::min(d, period - d);
  }
  return d * double(size);
}

struct Map {  // uv = (u0 + ux·x + uy·y, v0 + vx·x + vy·y) over leaf-local atlas texel positions
  double u0, ux, uy, v0, vx, vy;
};

// The reference triangle's map (build.cpp renderLeaf's); false when its atlas triangle is degenerate.
bool mapOf(const Scene& s, const Tree& tree, const AtlasEntry& e, uint32_t t, const SceneLayer& L, Map& m) {
  const auto p0 = atlasTexel(s, tree, e, t, 0), p1 = atlasTexel(s, tree, e, t, 1), p2 = atlasTexel(s, tree, e, t, 2);
  const double ax = p1.first - p0.first, ay = p1.second - p0.second, bx = p2.first - p0.first, by = p2.second - p0.second;
  const double det = ax * by - bx * ay;
  if (!(std::fabs(det) > 1e-9)) return false;
  const glm::vec2* uv = &L.uv[size_t(t) * 3];
  const double du1 = double(uv[1].x) - uv[0].x, dv1 = double(uv[1].y) - uv[0].y;
  const double du2 = double(uv[2].x) - uv[0].x, dv2 = double(uv[2].y) - uv[0].y;
  m.ux = (du1 * by - du2 * ay) / det, m.uy = (du2 * ax - du1 * bx) / det;
  m.vx = (dv1 * by - dv2 * ay) / det, m.vy = (dv2 * ax - dv1 * bx) / det;
  m.u0 = uv[0].x - m.ux * p0.first - m.uy * p0.second;
  m.v0 = uv[0].y - m.vx * p0.first - m.vy * p0.second;
  return true;
}

std::string describe(const Scene& s, const Tree& tree, uint32_t t) {
  const uint32_t src = tree.geometry.source[t];
  return s.describeTriangle ? s.describeTriangle(src) : "input triangle " + std::to_string(src);
}

}  // namespace

void checkLayerMaps(const Scene& s, const Tree& tree) {
  const Geometry& g = tree.geometry;
  for (size_t layer = 1; layer < g.layers.size(); ++layer) {
    const SceneLayer& L = g.layers[layer];
    for (const Node& n : tree.nodes) {
      if (!n.leaf()) continue;
      for (const AtlasEntry& e : n.entries) {
        // The reference, as renderLeaf picks it.
        uint32_t ref = UINT32_MAX;
        Map m{};
        for (uint32_t t = n.firstTriangle; t < n.firstTriangle + n.triangleCount && ref == UINT32_MAX; ++t)
          if (g.layers[0].texture[t] == e.texture && L.texture[t] >= 0 && mapOf(s, tree, e, t, L, m)) ref = t;
        auto refuse = [&](uint32_t t, const std::string& how) {
          const SceneImage& base = s.images[s.textures[e.texture].image];
          throw Error("mta build: " + s.name + ": layer " + std::to_string(layer) + " cannot share layer 0's atlas: " +
                      describe(s, tree, ref) + " and " + describe(s, tree, t) + " use base texture '" + base.name +
                      "' in one atlas area, but " + how +
                      ". The build fills an area's layer " + std::to_string(layer) +
                      " through one triangle's map (thesis §5.1.3), so the second would be drawn with the first's "
                      "texels: give every triangle of a base texture the same layer-" + std::to_string(layer) +
                      " texture on the same texcoord set, or a base texture per triangle (docs/mta-build.md step 9)");
        };
        if (ref == UINT32_MAX) continue;  // no layer-i texture in this area: it stays white, as every triangle's is
        const SceneTexture& rt = s.textures[uint32_t(L.texture[ref])];
        const SceneImage& img = s.images[rt.image];
        for (uint32_t t = n.firstTriangle; t < n.firstTriangle + n.triangleCount; ++t) {
          if (g.layers[0].texture[t] != e.texture || t == ref) continue;
          if (L.texture[t] < 0) refuse(t, "the second has no layer-" + std::to_string(layer) + " texture");
          const SceneTexture& tt = s.textures[uint32_t(L.texture[t])];
          if (tt.image != rt.image || tt.wrapS != rt.wrapS || tt.wrapT != rt.wrapT)
            refuse(t, "their layer-" + std::to_string(layer) + " textures differ ('" + img.name + "' and '" +
                          s.images[tt.image].name + "', or their wrap modes)");
          for (int k = 0; k < 3; ++k) {
            const auto [x, y] = atlasTexel(s, tree, e, t, k);
            const glm::vec2 uv = L.uv[size_t(t) * 3 + k];
            const double du = texelDistance(m.u0 + m.ux * x + m.uy * y, uv.x, img.width, rt.wrapS);
            const double dv = texelDistance(m.v0 + m.vx * x + m.vy * y, uv.y, img.height, rt.wrapT);
            if (du > 1.0 / 256.0 || dv > 1.0 / 256.0) {
              char buf[160];
              std::snprintf(buf, sizeof buf, "vertex %d of the second lies %.3g texels (s) and %.3g texels (t) of '%s' away from where the first's map puts it", k, du, dv, img.name.c_str());
              refuse(t, buf);
            }
          }
        }
      }
    }
  }
}

}  // namespace tessera::mta
