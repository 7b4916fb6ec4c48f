#include "mta/bind_budget.h"

#include <algorithm>
#include <vector>

#include "mta/draw_order.h"

namespace tessera::mta {

FramePlan planFrameWithinBinds(const MtaMeta& meta, const RuntimeGeometry& geometry, const BlockIndex& index,
                               const ViewContext& ctx, RenderMode mode, const std::function<bool(uint32_t)>& resident,
                               uint32_t maxBinds) {
  std::vector<NodeRef> coarsened;  // sorted
  FramePlan plan = planFrame(meta, geometry, index, ctx, mode, resident, coarsened);
  if (maxBinds == 0 || mode != RenderMode::AtlasTree) return plan;
  // Each round coarsens one node that the plan drew through its descendants and never refines it again,
  // so the rounds are at most the file's nodes; the bound makes that a loop condition, not an argument.
  size_t nodes = 0;
  for (const auto& t : meta.trees) nodes += t.nodes.size();
  for (size_t round = 0; round < nodes && textureKeyCount(plan) > maxBinds && !plan.refined.empty(); ++round) {
    const RefinedNode* best = &plan.refined.front();
    for (const RefinedNode& r : plan.refined)
      if (r.ratio > best->ratio || (r.ratio == best->ratio && r.ref < best->ref)) best = &r;
    coarsened.insert(std::upper_bound(coarsened.begin(), coarsened.end(), best->ref), best->ref);
    plan = planFrame(meta, geometry, index, ctx, mode, resident, coarsened);
  }
  return plan;
}

}  // namespace tessera::mta
