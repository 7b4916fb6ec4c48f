// A per-frame cap on texture binds for the atlas tree's rendering traversal.
//
// Implements: planFrameWithinBinds(), which plans a frame as planFrame() does and, while its grouped
// draws would bind more than `maxBinds` textures (draw_order.h textureKeyCount: nodes drawn with their
// atlas + distinct original texture pairs + the white texture), draws one more refined node with its
// own resident atlas instead of its children or original textures, and plans again.
//
// The thesis keeps binds low by the tree's structure alone (§4.7.2: "in the range of 60" atlases on its
// 300-frame Berlin path); it has no cap. A cap trades the τ guarantee for a bound on binds, so it is off
// unless asked for (`--max-binds`), and every node it coarsens is counted (FramePlan::coarsenedForBinds)
// together with how far its texels fall short (worstBindRatio; `tessera texel` counts the pixels).
//
// Which node: the refined node whose distance test failed by the least, the largest
// ratio = d · factor / (minDistance · scale), so that the pixels given up are magnified the least; ties
// go to the lower (tree, node). Coarsening a node removes everything below it from the frame, so the
// candidates are those of the latest plan. The choice depends on the plan alone: the same frame, the
// same nodes, at any thread count.
//
// Does not implement: the memory manager's view. usagePriorities() still requests what the frame would
// draw without a cap, so lifting the cap never waits for loads, and a node is only coarsened to an
// atlas that is resident. When no candidate is left (every node drawn is a resident atlas already, or
// its atlas is not resident), the frame stays over the cap and says so (binds > maxBinds in its counts).
#pragma once

#include "mta/traversal.h"

namespace tessera::mta {

// maxBinds 0: no cap (exactly planFrame). Other modes than AtlasTree ignore the cap.
FramePlan planFrameWithinBinds(const MtaMeta& meta, const RuntimeGeometry& geometry, const BlockIndex& index,
                               const ViewContext& ctx, RenderMode mode, const std::function<bool(uint32_t)>& resident,
                               uint32_t maxBinds);

}  // namespace tessera::mta
