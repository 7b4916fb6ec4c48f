#include "mta/build_plan.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "base/error.h"
#include "mta/critical.h"
#include "mta/layer_maps.h"
#include "mta/tree_build.h"

namespace tessera::mta {

double sceneDiagonal(const Scene& scene) {
  const Geometry& in = scene.geometry;
  if (in.positions.empty()) return 0.0;
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (const glm::vec3& v : in.positions) {
    const double c[3] = {v.x, v.y, v.z};
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
  }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                   (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

double resolveDMin(const Scene& scene, const BuildParams& params) {
  return params.dMin > 0.0 ? params.dMin : sceneDiagonal(scene) / params.dMinDivisor;
}

BuildPlan planBuild(const Scene& scene, const BuildParams& params, const std::function<void(const char*)>& checkpoint) {
  params.validate();
  scene.validate();
  const Geometry& in = scene.geometry;
  if (in.triangleCount() == 0) throw Error("mta: scene '" + scene.name + "' has no triangles");
  const double diag = sceneDiagonal(scene);
  const double dMin = params.dMin > 0.0 ? params.dMin : diag / params.dMinDivisor;
  if (!(dMin > 0.0)) throw Error("mta: scene '" + scene.name + "' has a zero-size bounding box; give --d-min");
  const uint32_t layers = uint32_t(in.layers.size());

  BuildPlan plan;
  MtaMeta& meta = plan.meta;
  meta.params = params;
  meta.params.tanHalfFov = params.effectiveTanHalfFov();
  meta.layerCount = layers;
  meta.encoding = params.encoding;
  meta.textures = scene.textures;
  CriticalReport crit;
  const Geometry g = handleCriticalTriangles(scene, params, dMin, crit);
  meta.stats = BuildStats{in.triangleCount(),
                          g.triangleCount(),
                          crit.criticalAtRequested,
                          crit.criticalAfterRaise,
                          crit.trianglesAdded,
                          crit.maxSplitDepth,
                          dMin,
                          crit.dMinUsed,
                          diag};
  if (checkpoint) checkpoint("after critical-triangle handling");
  for (uint8_t alpha = 0; alpha < 2; ++alpha) {
    std::vector<uint32_t> tris;
    for (uint32_t t = 0; t < g.triangleCount(); ++t)
      if (g.alpha[t] == alpha) tris.push_back(t);
    if (tris.empty()) continue;
    meta.trees.push_back(buildTree(scene, g, tris, alpha, params, crit.dMinUsed));
    checkLayerMaps(scene, meta.trees.back());  // before anything is written (layer_maps.h)
  }
  // Leaf image lists, image channels and first-use order.
  meta.images.resize(scene.images.size());
  std::vector<uint8_t> used(scene.images.size(), 0);
  for (Tree& tree : meta.trees) {
    tree.atlasBlocks.assign(tree.nodes.size() * layers, 0);
    plan.nodes += tree.nodes.size();
    for (Node& n : tree.nodes) {
      if (!n.leaf()) continue;
      ++plan.leaves;
      std::set<uint32_t> imgs;
      for (uint32_t t = n.firstTriangle; t < n.firstTriangle + n.triangleCount; ++t)
        for (uint32_t l = 0; l < layers; ++l)
          if (tree.geometry.layers[l].texture[t] >= 0)
            imgs.insert(scene.textures[tree.geometry.layers[l].texture[t]].image);
      n.imageFirst = uint32_t(tree.leafImages.size());
      n.imageCount = uint32_t(imgs.size());
      for (uint32_t i : imgs) {
        tree.leafImages.push_back(i);
        used[i] = 1;
        meta.images[i].channels = std::max<uint32_t>(meta.images[i].channels, tree.channels());
      }
    }
  }
  for (size_t i = 0; i < scene.images.size(); ++i) {
    meta.images[i].width = scene.images[i].width, meta.images[i].height = scene.images[i].height;
    meta.images[i].name = scene.images[i].name;
    if (!used[i]) meta.images[i].channels = 3;  // unused images are not stored (0 pieces)
  }
  if (checkpoint) checkpoint("after building the tree structure");
  return plan;
}

}  // namespace tessera::mta
