// The bind cap (bind_budget.h): off, it is planFrame; on, it meets the cap by drawing the refined nodes
// that miss the distance test by the least with their atlases, draws the same triangles, counts what it
// gave up, and the frame's binds follow.
#include <gtest/gtest.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "mta/bind_budget.h"
#include "mta/draw_order.h"
#include "mta/texel_ratio.h"
#include "mta/tree_renderer.h"
#include "mta_test_scene.h"
#include "wall_tree_file.h"

namespace tessera::mta {
namespace {

using testing::fixture;

// From far away to close up along the 12 x 12 wall, so that frames range from the root alone to dozens
// of leaves with their 144 original textures.
std::vector<ViewParams> budgetViews() {
  std::vector<ViewParams> out;
  for (int i = 0; i < 12; ++i) {
    ViewParams v;
    v.width = 128;
    v.height = 96;
    const double z = i < 6 ? 36.0 - 6.0 * i : 1.5, x = i < 6 ? 6.0 : 1.0 + 2.0 * (i - 6);
    v.camera.eye = {x, 6.0, z};
    v.camera.target = {x, 6.0, 0.0};
    v.camera.tanHalfFovX = fixture().tree->meta().params.tanHalfFov;
    v.camera.nearPlane = 0.05;
    v.camera.farPlane = 200.0;
    out.push_back(v);
  }
  return out;
}

struct Planned {
  RuntimeGeometry geometry = buildRuntimeGeometry(fixture().tree->meta());
  BlockIndex index = buildBlockIndex(fixture().tree->meta(), kRecordedLayers);
  std::function<bool(uint32_t)> resident = [](uint32_t) { return true; };

  FramePlan plan(const ViewParams& v, uint32_t cap, std::span<const NodeRef> force = {}) const {
    const MtaMeta& m = fixture().tree->meta();
    const ViewContext ctx = makeViewContext(m, v);
    FramePlan p = force.empty() ? planFrameWithinBinds(m, geometry, index, ctx, RenderMode::AtlasTree, resident, cap)
                                : planFrame(m, geometry, index, ctx, RenderMode::AtlasTree, resident, force);
    groupDrawsByTexture(p);
    return p;
  }
};

// Every triangle a plan draws, as sorted (first, count) ranges merged where they touch.
std::vector<std::pair<uint32_t, uint32_t>> triangles(const FramePlan& p) {
  std::vector<std::pair<uint32_t, uint32_t>> r;
  for (const PlannedDraw& d : p.draws) r.push_back({d.first, d.count});
  std::sort(r.begin(), r.end());
  std::vector<std::pair<uint32_t, uint32_t>> merged;
  for (const auto& x : r)
    if (!merged.empty() && merged.back().first + merged.back().second == x.first)
      merged.back().second += x.second;
    else
      merged.push_back(x);
  return merged;
}

TEST(BindBudget, WithoutACapOrWithACapTheFrameMeetsAnywayThePlanIsPlanFramesOwn) {
  const Planned p;
  for (const ViewParams& v : budgetViews()) {
    const FramePlan free = p.plan(v, 0);
    const FramePlan roomy = p.plan(v, textureKeyCount(free));
    EXPECT_EQ(free.coarsenedForBinds, 0u);
    EXPECT_EQ(roomy.coarsenedForBinds, 0u);
    ASSERT_EQ(free.draws.size(), roomy.draws.size());
    for (size_t i = 0; i < free.draws.size(); ++i) {
      EXPECT_EQ(free.draws[i].node, roomy.draws[i].node);
      EXPECT_EQ(free.draws[i].first, roomy.draws[i].first);
      EXPECT_EQ(free.draws[i].count, roomy.draws[i].count);
    }
  }
}

TEST(BindBudget, ACapIsMetByDrawingRefinedNodesWithTheirAtlasesAndTheSameTrianglesAreDrawn) {
  const Planned p;
  uint32_t framesCapped = 0;
  for (const ViewParams& v : budgetViews()) {
    const FramePlan free = p.plan(v, 0);
    const uint32_t keys = textureKeyCount(free);
    for (uint32_t cap : {1u, 2u, 4u, keys / 2, keys - 1}) {
      if (cap == 0 || cap >= keys) continue;
      const FramePlan capped = p.plan(v, cap);
      SCOPED_TRACE("keys " + std::to_string(keys) + ", cap " + std::to_string(cap));
      // Met, unless nothing is left to coarsen: then every node drawn is an atlas (the root's, at worst).
      if (textureKeyCount(capped) > cap) { EXPECT_TRUE(capped.refined.empty()); }
      EXPECT_GT(capped.coarsenedForBinds, 0u);
      EXPECT_LT(capped.worstBindRatio, 1.0);
      EXPECT_GE(capped.worstBindRatio, 0.0);  // 0: the eye inside the node's box
      EXPECT_LE(capped.atlasNodes + capped.originalLeaves, free.atlasNodes + free.originalLeaves);
      EXPECT_EQ(triangles(capped), triangles(free)) << "coarsening draws a node's visible leaves, as refining does";
      EXPECT_EQ(capped.trianglesDrawn, free.trianglesDrawn);
      ++framesCapped;
    }
  }
  EXPECT_GT(framesCapped, 10u) << "the views should need more binds than the caps tried";
}

// When one coarsening is enough, the plan is planFrame's with exactly the refined node of the largest
// ratio drawn with its atlas.
TEST(BindBudget, TheNodeCoarsenedFirstIsTheOneThatMissesTheDistanceTestByTheLeast) {
  const Planned p;
  uint32_t checked = 0;
  for (const ViewParams& v : budgetViews()) {
    const FramePlan free = p.plan(v, 0);
    if (free.refined.empty()) continue;
    const RefinedNode* best = &free.refined.front();
    for (const RefinedNode& r : free.refined)
      if (r.ratio > best->ratio || (r.ratio == best->ratio && r.ref < best->ref)) best = &r;
    for (const RefinedNode& r : free.refined) EXPECT_LT(r.ratio, 1.0);
    const NodeRef first[1] = {best->ref};
    const FramePlan one = p.plan(v, 0, first);
    const uint32_t cap = textureKeyCount(one);
    if (cap >= textureKeyCount(free)) continue;  // coarsening that node saved no bind
    const FramePlan capped = p.plan(v, cap);
    EXPECT_EQ(capped.coarsenedForBinds, 1u);
    EXPECT_EQ(capped.worstBindRatio, best->ratio);
    ASSERT_EQ(capped.draws.size(), one.draws.size());
    for (size_t i = 0; i < one.draws.size(); ++i) {
      EXPECT_EQ(capped.draws[i].node, one.draws[i].node);
      EXPECT_EQ(capped.draws[i].first, one.draws[i].first);
    }
    ++checked;
  }
  EXPECT_GT(checked, 3u);
}

// The frame recorded from a capped plan binds at most the cap on each unit, and gives up the τ guarantee
// only on pixels of the coarsened nodes: the texel analysis sees violations where the uncapped frame has
// none.
TEST(BindBudget, ACappedFrameBindsAtMostTheCapAndItsViolationsAreCounted) {
  const PagingFile& f = *fixture().tree;
  RendererOptions o;
  o.width = 128;
  o.height = 96;
  o.threads = 2;
  o.residency.capacityBytes = uint64_t(1) << 32;
  o.residency.budget.kind = LoadBudget::Kind::Blocks;
  o.residency.budget.perFrame = UINT64_MAX;
  o.residency.maxQueue = UINT32_MAX;
  RendererOptions capped = o;
  capped.maxBinds = 3;
  TreeRenderer free(f, o), cap(f, capped);
  uint64_t coarsened = 0, violations = 0, cappedBinds = 0, freeBinds = 0;
  for (const ViewParams& v : budgetViews()) {
    const FrameResult a = free.renderFrame(v.camera), b = cap.renderFrame(v.camera);
    EXPECT_EQ(a.plan.coarsenedForBinds, 0u);
    // Binds follow the keys; the keys meet the cap unless nothing was left to coarsen.
    EXPECT_LE(b.counters.texture_binds, textureKeyCount(b.plan)) << "frame " << b.frame;
    EXPECT_LE(b.counters.units[1].texture_binds, textureKeyCount(b.plan)) << "frame " << b.frame;
    if (!b.plan.refined.empty()) { EXPECT_LE(textureKeyCount(b.plan), 3u) << "frame " << b.frame; }
    cappedBinds = std::max<uint64_t>(cappedBinds, b.counters.texture_binds);
    freeBinds = std::max<uint64_t>(freeBinds, a.counters.texture_binds);
    const TexelFrame ta = analyzeTexels(free, v.camera, a, free.triangleIds(v.camera, a.plan), f.meta().params.tau);
    const TexelFrame tb = analyzeTexels(cap, v.camera, b, cap.triangleIds(v.camera, b.plan), f.meta().params.tau);
    EXPECT_EQ(ta.magnificationViolations, 0u);
    if (b.plan.coarsenedForBinds == 0) { EXPECT_EQ(tb.magnificationViolations, 0u); }
    coarsened += b.plan.coarsenedForBinds;
    violations += tb.magnificationViolations;
    const nlohmann::json j = toJson(b, RenderMode::AtlasTree);
    EXPECT_EQ(j["nodes_coarsened_for_binds"], b.plan.coarsenedForBinds);
    EXPECT_EQ(j["bind_cap_worst_ratio"].is_null(), b.plan.coarsenedForBinds == 0);
  }
  EXPECT_GT(coarsened, 0u);
  EXPECT_GT(violations, 0u);
  EXPECT_LT(cappedBinds, freeBinds);
}

TEST(BindBudget, ACapOnLeafByLeafDrawsIsRefusedBecauseItCountsGroupedBinds) {
  RendererOptions o;
  o.maxBinds = 8;
  o.groupBinds = false;
  EXPECT_THROW(TreeRenderer(*fixture().tree, o), Error);
}

}  // namespace
}  // namespace tessera::mta
