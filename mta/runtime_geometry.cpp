#include "mta/runtime_geometry.h"

#include <algorithm>
#include <numeric>
#include <string>

#include "base/error.h"

namespace tessera::mta {

namespace {

// What this file indexes with, checked although PagingFile's validator guarantees it (and more: that the
// leaves partition the triangles): a meta that breaks it is an Error, never a write out of bounds.
[[noreturn]] void broken(size_t tree, const std::string& why) {
  throw Error("runtime geometry: internal error: tree " + std::to_string(tree) + ": " + why +
              " (PagingFile's validator refuses such a file)");
}

}  // namespace

RuntimeGeometry buildRuntimeGeometry(const MtaMeta& meta) {
  RuntimeGeometry g;
  size_t total = 0;
  for (size_t ti = 0; ti < meta.trees.size(); ++ti) {
    const Tree& t = meta.trees[ti];
    const size_t tris = t.geometry.triangleCount();
    if (t.geometry.positions.size() != tris * 3 || t.atlasUV.size() != tris * 3 || t.geometry.layers.empty() ||
        t.geometry.layers[0].texture.size() != tris || t.geometry.layers[0].uv.size() != tris * 3)
      broken(ti, "arrays do not match the triangle count");
    if (meta.layerCount > 1 && (t.geometry.layers.size() < 2 || t.geometry.layers[1].texture.size() != tris ||
                                t.geometry.layers[1].uv.size() != tris * 3))
      broken(ti, "layer 1's arrays do not match the triangle count");
    total += tris;
  }
  if (total > kMaxTriangles) broken(0, "more triangles than 32-bit vertex indices address");
  const bool layered = meta.layerCount > 1;
  g.vertices.resize(total * 3);
  if (layered) g.layered.resize(total * 3);
  g.triangleTree.resize(total);
  g.triangleLeaf.resize(total);
  g.triangleSource.resize(total);
  uint32_t base = 0;
  std::vector<uint32_t> order;
  for (size_t ti = 0; ti < meta.trees.size(); ++ti) {
    const Tree& t = meta.trees[ti];
    const SceneLayer& layer0 = t.geometry.layers[0];
    const SceneLayer* layer1 = layered ? &t.geometry.layers[1] : nullptr;
    // Layer 1's texture of a textured triangle (-1: none, and always without layer 1).
    auto texture1 = [&](uint32_t tri) { return layer1 && layer0.texture[tri] >= 0 ? layer1->texture[tri] : -1; };
    RuntimeTree rt;
    rt.firstTriangle = base;
    rt.leaf.resize(t.nodes.size());
    uint32_t textured = 0;
    for (int32_t tex : layer0.texture) textured += tex >= 0 ? 1 : 0;
    rt.firstUntextured = base + textured;
    uint32_t nextTextured = base, nextUntextured = rt.firstUntextured;
    const uint32_t treeEnd = base + uint32_t(t.geometry.triangleCount());
    // Pre-order node indices visit the leaves depth first, as the file's ranges are laid out.
    for (size_t n = 0; n < t.nodes.size(); ++n) {
      const Node& node = t.nodes[n];
      if (!node.leaf()) continue;
      if (uint64_t(node.firstTriangle) + node.triangleCount > t.geometry.triangleCount())
        broken(ti, "leaf " + std::to_string(n) + "'s triangles run past the vertex array");
      // Stable sort by (layer-0 texture, layer-1 texture), -1 last in each: keeps the file's order inside
      // each run. Without layer 1 the second key is always -1, so the order is that of layer 0 alone.
      order.resize(node.triangleCount);
      std::iota(order.begin(), order.end(), node.firstTriangle);
      std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        const uint32_t ka = uint32_t(layer0.texture[a]), kb = uint32_t(layer0.texture[b]);  // -1 -> max
        if (ka != kb) return ka < kb;
        return uint32_t(texture1(a)) < uint32_t(texture1(b));
      });
      LeafRuns& lr = rt.leaf[n];
      lr.runFirst = uint32_t(g.runs.size());
      lr.texturedFirst = nextTextured;
      lr.untexturedFirst = nextUntextured;
      for (uint32_t k = 0; k < node.triangleCount; ++k) {
        const uint32_t src = order[k];
        const int32_t tex = layer0.texture[src];
        const int32_t tex1 = texture1(src);
        if (tex >= int64_t(meta.textures.size()) || tex1 >= int64_t(meta.textures.size()))
          broken(ti, "texture " + std::to_string(std::max(tex, tex1)) + " out of range");
        if (tex >= 0 ? nextTextured >= rt.firstUntextured : nextUntextured >= treeEnd)
          broken(ti, "leaf " + std::to_string(n) + " overlaps another leaf's triangles");
        const uint32_t dst = tex >= 0 ? nextTextured++ : nextUntextured++;
        if (tex >= 0) {
          if (g.runs.size() == lr.runFirst || g.runs.back().texture != tex || g.runs.back().texture1 != tex1)
            g.runs.push_back(TextureRun{tex, dst, 0, tex1});
          ++g.runs.back().count;
          ++lr.texturedCount;
        } else {
          ++lr.untexturedCount;
        }
        for (int v = 0; v < 3; ++v) {
          RuntimeVertex& rv = g.vertices[size_t(dst) * 3 + v];
          rv.pos = t.geometry.positions[size_t(src) * 3 + v];
          rv.atlasUV = t.atlasUV[size_t(src) * 3 + v];
          rv.origUV = layer0.uv[size_t(src) * 3 + v];
          rv.triangle = dst;
          rv.pad = 0;
          if (layered) {
            LayeredVertex& lv = g.layered[size_t(dst) * 3 + v];
            lv.pos = rv.pos;
            lv.atlasUV0 = lv.atlasUV1 = rv.atlasUV;
            lv.origUV0 = rv.origUV;
            lv.origUV1 = tex1 >= 0 ? layer1->uv[size_t(src) * 3 + v] : glm::vec2(0.0f);
          }
        }
        g.triangleTree[dst] = uint8_t(ti);
        g.triangleLeaf[dst] = uint32_t(n);
        g.triangleSource[dst] = src;
      }
      lr.runCount = uint32_t(g.runs.size()) - lr.runFirst;
    }
    base += uint32_t(t.geometry.triangleCount());
    g.trees.push_back(std::move(rt));
  }
  return g;
}

}  // namespace tessera::mta
