#include "mta/traversal.h"

#include <algorithm>

#include "base/error.h"

namespace tessera::mta {

const char* renderModeName(RenderMode m) {
  switch (m) {
    case RenderMode::AtlasTree: return "atlas_tree";
    case RenderMode::Original: return "original";
    case RenderMode::Dummy: return "dummy";
  }
  return "?";
}

const char* distanceBoundName(DistanceBound b) {
  switch (b) {
    case DistanceBound::PerNode: return "node";
    case DistanceBound::FrameCorner: return "corner";
    case DistanceBound::Thesis: return "thesis";
  }
  return "?";
}

DistanceBound parseDistanceBound(const std::string& text, const std::string& what) {
  for (DistanceBound b : {DistanceBound::PerNode, DistanceBound::FrameCorner, DistanceBound::Thesis})
    if (text == distanceBoundName(b)) return b;
  throw Error(what + " '" + text + "': expected node, corner or thesis");
}

BlockIndex buildBlockIndex(const MtaMeta& meta, LayerMask drawnLayers) {
  BlockIndex bi;
  const LayerMask fileLayers = meta.layerCount >= 32 ? ~LayerMask(0) : (LayerMask(1) << meta.layerCount) - 1;
  bi.layers = drawnLayers & fileLayers;
  if (bi.layers == 0)
    throw Error("block index: the renderer draws none of the file's " + std::to_string(meta.layerCount) + " layers");
  std::vector<uint32_t> drawn;
  for (uint32_t l = 0; l < meta.layerCount; ++l)
    if (bi.layers >> l & 1) drawn.push_back(l);
  bi.atlasPerNode = uint32_t(drawn.size());
  for (size_t ti = 0; ti < meta.trees.size(); ++ti) {
    const Tree& t = meta.trees[ti];
    BlockIndex::PerTree pt;
    const size_t n = t.nodes.size();
    // What the index and the walkers below rely on, checked although PagingFile's validator guarantees
    // it: every block, texture and image index in range, and child indices that only ever increase, so
    // that the recursive walks stay in the table and end (their depth is the tree's, at most
    // kMaxNodeLevel + 1).
    auto broken = [&](size_t node, const std::string& why) {
      throw Error("block index: internal error: tree " + std::to_string(ti) + " node " + std::to_string(node) + ": " +
                  why + " (PagingFile's validator refuses such a file)");
    };
    if (t.atlasBlocks.size() != n * meta.layerCount) broken(0, "the atlas block table does not match the node count");
    if (t.geometry.layers.size() != meta.layerCount) broken(0, "the geometry does not have every layer");
    pt.atlasFirst.resize(n);
    pt.originalFirst.assign(n, 0);
    pt.originalCount.assign(n, 0);
    std::vector<uint32_t> images, blocks;
    for (size_t i = 0; i < n; ++i) {
      const Node& node = t.nodes[i];
      for (int32_t c : node.children)
        if (c != -1 && (c <= int64_t(i) || uint64_t(c) >= n))
          broken(i, "child index " + std::to_string(c) + " out of range");
      if (node.level > kMaxNodeLevel) broken(i, "deeper than the format allows");
      pt.atlasFirst[i] = uint32_t(pt.atlas.size());
      for (uint32_t l : drawn) {
        pt.atlas.push_back(t.atlasBlocks[i * meta.layerCount + l]);
        if (pt.atlas.back() >= meta.blocks.size()) broken(i, "atlas block out of range");
      }
      if (!node.leaf()) continue;
      // The images the leaf's drawn layers use (the validator makes the leaf's image list the union over
      // every layer; a layer nothing draws must not pull its images in).
      images.clear();
      for (uint32_t l : drawn) {
        const std::vector<int32_t>& tex = t.geometry.layers[l].texture;
        if (uint64_t(node.firstTriangle) + node.triangleCount > tex.size()) broken(i, "triangle range out of range");
        for (uint32_t k = node.firstTriangle; k < node.firstTriangle + node.triangleCount; ++k) {
          if (tex[k] < 0) continue;
          if (uint64_t(tex[k]) >= meta.textures.size()) broken(i, "texture " + std::to_string(tex[k]) + " out of range");
          images.push_back(meta.textures[uint32_t(tex[k])].image);
        }
      }
      std::sort(images.begin(), images.end());
      images.erase(std::unique(images.begin(), images.end()), images.end());
      blocks.clear();
      for (uint32_t image : images) {
        if (image >= meta.images.size()) broken(i, "image " + std::to_string(image) + " out of range");
        const ImageRecord& img = meta.images[image];
        if (uint64_t(img.firstPiece) + img.pieceCount > meta.pieces.size()) broken(i, "image pieces out of range");
        for (uint32_t p = 0; p < img.pieceCount; ++p) {
          blocks.push_back(meta.pieces[img.firstPiece + p].block);
          if (blocks.back() >= meta.blocks.size()) broken(i, "piece block out of range");
        }
      }
      std::sort(blocks.begin(), blocks.end());
      blocks.erase(std::unique(blocks.begin(), blocks.end()), blocks.end());
      pt.originalFirst[i] = uint32_t(pt.original.size());
      pt.originalCount[i] = uint32_t(blocks.size());
      pt.original.insert(pt.original.end(), blocks.begin(), blocks.end());
    }
    bi.trees.push_back(std::move(pt));
  }
  return bi;
}

ViewContext makeViewContext(const MtaMeta& meta, const ViewParams& view) {
  if (view.width == 0 || view.height == 0) throw Error("view: the frame size must be at least 1 x 1");
  validate(view.camera, "view");
  ViewContext c;
  c.frustum = frustumOf(view.camera, view.width, view.height);
  c.eye = view.camera.eye;
  const double tx = view.camera.tanHalfFovX;
  const double ty = tx * double(view.height) / double(view.width);
  // cos²θ of the frustum's corner ray: 1 / (1 + tan²x + tan²y). A point at distance r and angle θ from
  // the view axis has depth r·cosθ, and the projection's largest singular value there is f / (r·cos²θ).
  c.bound = view.bound;
  c.distanceFactor = view.bound == DistanceBound::Thesis ? 1.0 : 1.0 / (1.0 + tx * tx + ty * ty);
  c.view = viewMatrixD(view.camera);
  c.tanX = tx;
  c.tanY = ty;
  const double tauBuild = meta.params.tau, tauFrame = view.tau > 0.0 ? view.tau : meta.params.tau;
  c.minDistanceScale = (double(view.width) / double(meta.params.screenWidth)) * (meta.params.tanHalfFov / tx) * (tauBuild / tauFrame);
  return c;
}

double distanceFactor(const ViewContext& ctx, const std::array<float, 6>& b) {
  if (ctx.bound != DistanceBound::PerNode) return ctx.distanceFactor;
  // The magnification at a point r from the eye, θ off the view axis, is f / (r·cos²θ) (traversal.h), so
  // min over the box of r·cos²θ >= d · min cos²θ: θ's maximum over the box clipped to the frustum is a
  // sound factor. tan²θ = (x/z)² + (y/z)² in camera space is convex in the window coordinates (x/z, y/z),
  // and the box (in front of the eye) projects inside the rectangle of its corners' projections: its
  // maximum over that rectangle clipped to the window lies at a corner of the clipped rectangle.
  double minX = 0.0, maxX = 0.0, minY = 0.0, maxY = 0.0;
  for (int k = 0; k < 8; ++k) {
    const double x = b[(k & 1) ? 3 : 0], y = b[(k & 2) ? 4 : 1], z = b[(k & 4) ? 5 : 2];
    const glm::dmat4& m = ctx.view;
    const double cx = ((m[0][0] * x + m[1][0] * y) + m[2][0] * z) + m[3][0];
    const double cy = ((m[0][1] * x + m[1][1] * y) + m[2][1] * z) + m[3][1];
    const double depth = -(((m[0][2] * x + m[1][2] * y) + m[2][2] * z) + m[3][2]);
    // A corner on or behind the eye plane: the projection is unbounded, the frustum's corner ray bounds θ.
    if (!(depth > 0.0)) return ctx.distanceFactor;
    const double px = cx / depth, py = cy / depth;
    if (k == 0 || px < minX) minX = px;
    if (k == 0 || px > maxX) maxX = px;
    if (k == 0 || py < minY) minY = py;
    if (k == 0 || py > maxY) maxY = py;
  }
  const double x0 = std::max(minX, -ctx.tanX), x1 = std::min(maxX, ctx.tanX);
  const double y0 = std::max(minY, -ctx.tanY), y1 = std::min(maxY, ctx.tanY);
  // Outside the window (a box the conservative cull kept): nothing of it is drawn; any sound factor will do.
  if (!(x0 <= x1) || !(y0 <= y1)) return ctx.distanceFactor;
  const double tx2 = std::max(x0 * x0, x1 * x1), ty2 = std::max(y0 * y0, y1 * y1);
  return std::max(1.0 / (1.0 + (tx2 + ty2)), ctx.distanceFactor);
}

namespace {

struct Walker {
  const MtaMeta& meta;
  const BlockIndex& index;
  const ViewContext& ctx;

  bool culled(const Node& n) const { return outsideFrustum(ctx.frustum, n.bounds); }
  double distance(const Node& n) const { return distanceToBox(ctx.eye, n.bounds); }
  bool atlasSufficient(const Node& n, double d) const {
    return d * distanceFactor(ctx, n.bounds) >= double(n.minDistance) * ctx.minDistanceScale;
  }
};

void mark(std::vector<BlockPriority>& pr, uint32_t block, Usage u, double d, uint32_t level) {
  const BlockPriority candidate{u, d, level};
  // A block in several roles (an original block shared by leaves) takes its most pressing one.
  if (morePressing(candidate, block, pr[block], block)) pr[block] = candidate;
}

void markAtlas(const Walker& w, std::vector<BlockPriority>& pr, size_t tree, uint32_t node, Usage u, double d) {
  const auto& pt = w.index.trees[tree];
  const uint32_t level = w.meta.trees[tree].nodes[node].level;
  for (uint32_t l = 0; l < w.index.atlasPerNode; ++l) mark(pr, pt.atlas[pt.atlasFirst[node] + l], u, d, level);
}

void markOriginals(const Walker& w, std::vector<BlockPriority>& pr, size_t tree, uint32_t node, Usage u, double d) {
  const auto& pt = w.index.trees[tree];
  const uint32_t level = w.meta.trees[tree].nodes[node].level + 1;  // just below the leaf's own atlas
  for (uint32_t k = 0; k < pt.originalCount[node]; ++k) mark(pr, pt.original[pt.originalFirst[node] + k], u, d, level);
}

// Simulates rendering with every block in memory (§4.6: "a separate tree traversal that simulates the
// rendering process assuming that all nodes are currently in memory").
void usageVisit(const Walker& w, std::vector<BlockPriority>& pr, size_t tree, uint32_t n) {
  const Node& node = w.meta.trees[tree].nodes[n];
  const double d = w.distance(node);
  markAtlas(w, pr, tree, n, Usage::Needed, d);
  if (w.atlasSufficient(node, d)) {
    // Prefetch the next refinement step.
    if (node.leaf()) markOriginals(w, pr, tree, n, Usage::ParentNeeded, d);
    else
      for (int32_t c : node.children)
        if (c >= 0) markAtlas(w, pr, tree, uint32_t(c), Usage::ParentNeeded, w.distance(w.meta.trees[tree].nodes[uint32_t(c)]));
    return;
  }
  if (node.leaf()) {
    markOriginals(w, pr, tree, n, Usage::Needed, d);
    return;
  }
  bool anyVisible = false;
  for (int32_t c : node.children)
    if (c >= 0 && !w.culled(w.meta.trees[tree].nodes[uint32_t(c)])) {
      anyVisible = true;
      usageVisit(w, pr, tree, uint32_t(c));
    }
  if (!anyVisible) return;
  for (int32_t c : node.children)
    if (c >= 0 && w.culled(w.meta.trees[tree].nodes[uint32_t(c)]))
      markAtlas(w, pr, tree, uint32_t(c), Usage::Culled, w.distance(w.meta.trees[tree].nodes[uint32_t(c)]));
}

struct Planner {
  const Walker& w;
  const RuntimeGeometry& g;
  const std::function<bool(uint32_t)>& resident;
  FramePlan& plan;
  std::span<const NodeRef> forced;  // sorted
  std::vector<PlannedDraw> white;  // untextured triangles, drawn last with the white texture

  bool atlasResident(size_t tree, uint32_t n) const {
    const auto& pt = w.index.trees[tree];
    for (uint32_t l = 0; l < w.index.atlasPerNode; ++l)
      if (!resident(pt.atlas[pt.atlasFirst[n] + l])) return false;
    return true;
  }
  bool originalsResident(size_t tree, uint32_t n) const {
    const auto& pt = w.index.trees[tree];
    for (uint32_t k = 0; k < pt.originalCount[n]; ++k)
      if (!resident(pt.original[pt.originalFirst[n] + k])) return false;
    return true;
  }
  // Figure 30.
  bool refinementPossible(size_t tree, uint32_t n) const {
    const Node& node = w.meta.trees[tree].nodes[n];
    if (node.leaf()) return originalsResident(tree, n);
    for (int32_t c : node.children)
      if (c >= 0 && !atlasResident(tree, uint32_t(c)) && !w.culled(w.meta.trees[tree].nodes[uint32_t(c)])) return false;
    return true;
  }

  static void append(std::vector<PlannedDraw>& out, PlannedDraw d) {
    if (d.count == 0) return;
    PlannedDraw* last = out.empty() ? nullptr : &out.back();
    // Adjacent ranges with the same texture become one draw (§4.8.1).
    if (last && last->source == d.source && last->tree == d.tree && last->node == d.node && last->texture == d.texture &&
        last->texture1 == d.texture1 && last->first + last->count == d.first) {
      last->count += d.count;
      return;
    }
    out.push_back(d);
  }

  void leafRanges(size_t tree, uint32_t leaf, DrawSource src, uint32_t atlasNode) {
    const LeafRuns& lr = g.trees[tree].leaf[leaf];
    ++plan.leavesDrawn;
    plan.trianglesDrawn += lr.texturedCount + lr.untexturedCount;
    if (src == DrawSource::White)
      append(plan.draws, {DrawSource::White, uint8_t(tree), 0, -1, lr.texturedFirst, lr.texturedCount});
    else if (src == DrawSource::Atlas)
      append(plan.draws, {DrawSource::Atlas, uint8_t(tree), atlasNode, -1, lr.texturedFirst, lr.texturedCount});
    else
      for (uint32_t r = 0; r < lr.runCount; ++r) {
        const TextureRun& run = g.runs[lr.runFirst + r];
        append(plan.draws, {DrawSource::Original, uint8_t(tree), leaf, run.texture, run.first, run.count, run.texture1});
      }
    append(white, {DrawSource::Untextured, uint8_t(tree), 0, -1, lr.untexturedFirst, lr.untexturedCount});
  }

  // renderNode (Figure 26): the node's atlas for every visible leaf below it.
  void atlasLeaves(size_t tree, uint32_t n, uint32_t atlasNode) {
    const Node& node = w.meta.trees[tree].nodes[n];
    if (w.culled(node)) return;
    if (node.leaf()) {
      leafRanges(tree, n, DrawSource::Atlas, atlasNode);
      return;
    }
    for (int32_t c : node.children)
      if (c >= 0) atlasLeaves(tree, uint32_t(c), atlasNode);
  }

  void visitTree(size_t tree, uint32_t n) {
    const Node& node = w.meta.trees[tree].nodes[n];
    if (w.culled(node)) return;
    const double d = w.distance(node);
    bool useAtlas = w.atlasSufficient(node, d);
    if (!useAtlas && !refinementPossible(tree, n)) {
      useAtlas = true;
      ++plan.coarserThanNeeded;
    }
    if (!useAtlas && atlasResident(tree, n)) {
      const double ratio = d * distanceFactor(w.ctx, node.bounds) / (double(node.minDistance) * w.ctx.minDistanceScale);
      if (std::binary_search(forced.begin(), forced.end(), NodeRef{uint8_t(tree), n})) {
        useAtlas = true;
        ++plan.coarsenedForBinds;
        plan.worstBindRatio = std::min(plan.worstBindRatio, ratio);
      } else {
        plan.refined.push_back({NodeRef{uint8_t(tree), n}, ratio});
      }
    }
    if (useAtlas) {
      ++plan.atlasNodes;
      atlasLeaves(tree, n, n);
    } else if (node.leaf()) {
      ++plan.originalLeaves;
      leafRanges(tree, n, DrawSource::Original, 0);
    } else {
      for (int32_t c : node.children)
        if (c >= 0) visitTree(tree, uint32_t(c));
    }
  }

  // The comparison runs: every visible leaf, no distance test.
  void visitAll(size_t tree, uint32_t n, DrawSource src) {
    const Node& node = w.meta.trees[tree].nodes[n];
    if (w.culled(node)) return;
    if (node.leaf()) {
      if (src == DrawSource::Original) ++plan.originalLeaves;
      leafRanges(tree, n, src, 0);
      return;
    }
    for (int32_t c : node.children)
      if (c >= 0) visitAll(tree, uint32_t(c), src);
  }
};

}  // namespace

std::vector<BlockPriority> usagePriorities(const MtaMeta& meta, const BlockIndex& index, const ViewContext& ctx) {
  std::vector<BlockPriority> pr(meta.blocks.size());
  const Walker w{meta, index, ctx};
  for (size_t t = 0; t < meta.trees.size(); ++t)
    if (!meta.trees[t].nodes.empty() && !w.culled(meta.trees[t].nodes[0])) usageVisit(w, pr, t, 0);
  return pr;
}

FramePlan planFrame(const MtaMeta& meta, const RuntimeGeometry& geometry, const BlockIndex& index, const ViewContext& ctx,
                    RenderMode mode, const std::function<bool(uint32_t)>& resident,
                    std::span<const NodeRef> drawWithAtlas) {
  FramePlan plan;
  const Walker w{meta, index, ctx};
  Planner p{w, geometry, resident, plan, drawWithAtlas, {}};
  for (size_t t = 0; t < meta.trees.size(); ++t) {
    if (meta.trees[t].nodes.empty()) continue;
    switch (mode) {
      case RenderMode::AtlasTree: p.visitTree(t, 0); break;
      case RenderMode::Original: p.visitAll(t, 0, DrawSource::Original); break;
      case RenderMode::Dummy: p.visitAll(t, 0, DrawSource::White); break;
    }
  }
  for (const PlannedDraw& d : p.white) Planner::append(plan.draws, d);
  return plan;
}

}  // namespace tessera::mta
