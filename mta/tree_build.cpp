#include "mta/tree_build.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "mta/packing.h"
#include "mta/split.h"
#include "base/error.h"

namespace tessera::mta {

uint32_t Tree::depth() const {
  uint32_t d = 0;
  for (const Node& n : nodes) d = std::max(d, n.level + 1);
  return d;
}

double toRoot(double local, uint32_t cell, uint32_t level) { return (double(cell) + local) / double(uint64_t(1) << level); }

std::pair<double, double> entryTexel(const AtlasEntry& e, double u, double v) {
  const double sw = e.source.width(), sh = e.source.height();
  if (!e.rotated)
    return {e.x + (sw > 0.0 ? (u - e.source.u0) / sw * e.w : 0.5 * e.w),
            e.y + (sh > 0.0 ? (v - e.source.v0) / sh * e.h : 0.5 * e.h)};
  return {e.x + (sh > 0.0 ? (e.source.v1 - v) / sh * e.w : 0.5 * e.w),
          e.y + (sw > 0.0 ? (u - e.source.u0) / sw * e.h : 0.5 * e.h)};
}

double toLocal(double root, uint32_t level) {
  const double x = root * double(uint64_t(1) << level);
  return x - std::floor(x);
}

bool layoutAtlas(const Scene& s, const Geometry& g, std::span<const uint32_t> tris, const std::vector<TexelSize>& sizes,
                 const BuildParams& p, std::vector<AtlasEntry>& entries, double& coverage, double* capFactor) {
  if (capFactor) *capFactor = 1.0;
  const SceneLayer& L = g.layers[0];
  std::vector<std::pair<int32_t, uint32_t>> byTex;  // (texture, triangle): sorted, a total order
  byTex.reserve(tris.size());
  for (uint32_t t : tris)
    if (L.texture[t] >= 0) byTex.push_back({L.texture[t], t});
  std::sort(byTex.begin(), byTex.end());
  entries.clear();
  std::vector<PackRect> rects;
  for (size_t i = 0; i < byTex.size();) {
    const int32_t tex = byTex[i].first;
    TexelSize need{0.0, 0.0, true, false};
    TexRect rect;
    for (; i < byTex.size() && byTex[i].first == tex; ++i) {
      const uint32_t t = byTex[i].second;
      const TexelSize& ts = sizes[t];
      const SceneTexture& st = s.textures[tex];
      const auto sh = repeatShift(&L.uv[t * 3], st.wrapS, st.wrapT);
      for (int k = 0; k < 3; ++k)
        rect.add(glm::vec2{float(double(L.uv[t * 3 + k].x) - sh.first), float(double(L.uv[t * 3 + k].y) - sh.second)});
      if (ts.ignored || ts.constant) continue;
      need.constant = false;
      need.w = std::max(need.w, ts.w);
      need.h = std::max(need.h, ts.h);
    }
    const SceneImage& img = s.images[s.textures[tex].image];
    const AreaRequirement r = requiredArea(need, rect, img.width, img.height, p.border);
    // How far the image's own size caps the need: the atlas area meets τ only from this factor times
    // d_min on (the originals do not either, closer), which the parents' minDistance must respect.
    if (capFactor && !need.constant)
      *capFactor = std::max(*capFactor, std::max(need.w / double(img.width), need.h / double(img.height)));
    entries.push_back(AtlasEntry{tex, r.source, 0, 0, r.w, r.h});
    rects.push_back(PackRect{r.w, r.h});
  }
  const PackResult pr = packAtlas(rects, p.atlasSize);
  if (!pr.ok) return false;
  for (size_t i = 0; i < entries.size(); ++i) {
    AtlasEntry& e = entries[i];
    e.x = pr.placements[i].x, e.y = pr.placements[i].y;
    if (pr.placements[i].rotated) e.rotated = true, std::swap(e.w, e.h);
  }
  coverage = pr.coverage();
  return true;
}

namespace {

struct BuildNode {
  std::vector<uint32_t> tris;
  std::vector<AtlasEntry> entries;
  double coverage = 0.0;
  double capFactor = 1.0;  // leaves: see layoutAtlas
  std::array<std::unique_ptr<BuildNode>, 4> children;
  bool leaf = true;
};

struct Ctx {
  const Scene& s;
  const Geometry& g;
  const BuildParams& p;
  const std::vector<TexelSize>& sizes;
};

void buildRecursive(const Ctx& c, BuildNode& n, uint32_t level) {
  if (layoutAtlas(c.s, c.g, n.tris, c.sizes, c.p, n.entries, n.coverage, &n.capFactor)) return;
  if (n.tris.size() < 2)
    throw Error("mta: triangle " + std::to_string(c.g.source[n.tris[0]]) +
                " does not fit an atlas on its own (critical-triangle handling missed it)");
  if (level >= 60) throw Error("mta: the tree exceeds 60 levels");
  n.leaf = false;
  auto groups = splitTriangles(c.g, n.tris);
  n.tris.clear();
  n.tris.shrink_to_fit();
  for (int q = 0; q < 4; ++q)
    if (!groups[q].empty()) {
      n.children[q] = std::make_unique<BuildNode>();
      n.children[q]->tris = std::move(groups[q]);
    }
  tbb::parallel_for(0, 4, [&](int q) {
    if (n.children[q]) buildRecursive(c, *n.children[q], level + 1);
  });
}

struct Flattener {
  const Scene& scene;
  const Geometry& in;
  const BuildParams& p;
  double dMin;
  Tree& tree;

  int32_t visit(BuildNode& b, int32_t parent, uint32_t level, uint32_t cellX, uint32_t cellY) {
    const int32_t id = int32_t(tree.nodes.size());
    tree.nodes.emplace_back();
    {
      Node& n = tree.nodes.back();
      n.parent = parent;
      n.level = level;
      n.cellX = cellX;
      n.cellY = cellY;
      n.firstTriangle = uint32_t(tree.geometry.triangleCount());
    }
    if (b.leaf) {
      appendLeaf(b, id);
    } else {
      double cov = 0.0, minD = 0.0;
      for (int q = 0; q < 4; ++q) {
        if (!b.children[q]) continue;
        // A leaf whose need was capped by an image's size meets τ only from d_min · capFactor on.
        const double childTauDistance = b.children[q]->leaf ? dMin * b.children[q]->capFactor : 0.0;
        const int32_t child = visit(*b.children[q], id, level + 1, cellX * 2 + (q & 1), cellY * 2 + (q >> 1));
        tree.nodes[id].children[q] = child;
        cov += tree.nodes[child].coverage;
        minD = std::max(minD, std::max(double(tree.nodes[child].minDistance), childTauDistance));
        b.children[q].reset();
      }
      tree.nodes[id].coverage = float(cov / 4.0);
      tree.nodes[id].minDistance = float(2.0 * minD);
    }
    Node& n = tree.nodes[id];
    n.triangleCount = uint32_t(tree.geometry.triangleCount()) - n.firstTriangle;
    std::array<float, 6> bb{1e30f, 1e30f, 1e30f, -1e30f, -1e30f, -1e30f};
    for (size_t i = size_t(n.firstTriangle) * 3; i < size_t(n.firstTriangle + n.triangleCount) * 3; ++i) {
      const glm::vec3& v = tree.geometry.positions[i];
      bb[0] = std::min(bb[0], v.x), bb[1] = std::min(bb[1], v.y), bb[2] = std::min(bb[2], v.z);
      bb[3] = std::max(bb[3], v.x), bb[4] = std::max(bb[4], v.y), bb[5] = std::max(bb[5], v.z);
    }
    n.bounds = bb;
    return id;
  }

  void appendLeaf(BuildNode& b, int32_t id) {
    Node& n = tree.nodes[id];
    n.minDistance = float(dMin);
    n.coverage = float(b.coverage);
    n.entries = std::move(b.entries);
    const double A = p.atlasSize;
    Geometry& out = tree.geometry;
    for (uint32_t t : b.tris) {
      for (int k = 0; k < 3; ++k) out.positions.push_back(in.positions[t * 3 + k]);
      out.source.push_back(in.source[t]);
      out.alpha.push_back(in.alpha[t]);
      for (size_t l = 0; l < in.layers.size(); ++l) {
        out.layers[l].texture.push_back(in.layers[l].texture[t]);
        for (int k = 0; k < 3; ++k) out.layers[l].uv.push_back(in.layers[l].uv[t * 3 + k]);
      }
      const int32_t tex = in.layers[0].texture[t];
      const AtlasEntry* e = nullptr;
      for (const AtlasEntry& x : n.entries)
        if (x.texture == tex) e = &x;
      std::pair<double, double> shift{0.0, 0.0};
      if (e) shift = repeatShift(&in.layers[0].uv[t * 3], scene.textures[tex].wrapS, scene.textures[tex].wrapT);
      for (int k = 0; k < 3; ++k) {
        double s = 0.5, tt = 0.5;  // untextured: the cell centre (never sampled; texture is -1)
        if (e) {
          const glm::vec2& uv = in.layers[0].uv[t * 3 + k];
          const double u = float(double(uv.x) - shift.first), v = float(double(uv.y) - shift.second);
          const auto [px, py] = entryTexel(*e, u, v);
          s = px / A;
          tt = py / A;
        }
        tree.atlasUV.push_back(glm::vec2{float(toRoot(s, n.cellX, n.level)), float(toRoot(tt, n.cellY, n.level))});
      }
    }
  }
};

}  // namespace

Tree buildTree(const Scene& s, const Geometry& g, std::span<const uint32_t> tris, uint8_t alpha, const BuildParams& p,
               double dMin) {
  Tree tree;
  tree.alpha = alpha;
  tree.geometry.layers.resize(g.layers.size());
  if (tris.empty()) return tree;
  const double fProj = projectionFactor(p, dMin);
  std::vector<TexelSize> sizes(g.triangleCount());
  tbb::parallel_for(size_t(0), tris.size(), [&](size_t i) {
    const uint32_t t = tris[i];
    sizes[t] = triangleTexelSize(&g.positions[t * 3], &g.layers[0].uv[t * 3], fProj);
  });
  BuildNode root;
  root.tris.assign(tris.begin(), tris.end());
  const Ctx ctx{s, g, p, sizes};
  buildRecursive(ctx, root, 0);
  Flattener f{s, g, p, dMin, tree};
  f.visit(root, -1, 0, 0, 0);
  return tree;
}

}  // namespace tessera::mta
