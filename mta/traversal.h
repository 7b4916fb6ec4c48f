// The two per-frame traversals of the atlas tree: the usage traversal of the memory manager (thesis
// §4.6) and the rendering traversal (§4.4, Figure 26, with the refinementPossible change of Figure 30).
//
// Implements:
// - the distance test "d >= N.minDistance" with minDistance rescaled from the build's screen width,
//   field of view and τ to the frame's (f_proj, §4.5.2, is linear in each), and d the distance from the
//   eye to N.bounds, made conservative by default (DistanceBound, docs/mta-render.md). The thesis's
//   estimate assumes a segment seen on the view axis; off axis a perspective projection magnifies by up
//   to 1/cos²θ, so d is multiplied by cos²θ_max: with PerNode, θ_max is the largest angle from the view
//   axis over the node's box clipped to the frustum (its projected bounding rectangle clipped to the
//   window); with FrameCorner, the frustum's corner ray for every node. Both keep the τ guarantee at
//   every pixel; PerNode refines fewer nodes near the view axis;
// - usage categories per block (Needed: every atlas on the rendering path and the originals of refined
//   leaves; Culled: the atlas of a culled child of a refined node with a visible sibling; Parent needed:
//   the children's atlases / the leaf's originals of a node drawn with its atlas), the priority key
//   (usage, distance, level) per block;
// - the draw plan: which node atlases and which original textures draw which triangle ranges, for the
//   atlas tree and for the comparison runs of the thesis's §4.7.2 (original textures for every visible
//   leaf; one dummy texture for everything).
// Does not implement: bind budgets (bind_budget.h), loading (residency.h), the order draws are recorded in (draw_order.h: planFrame
// emits them leaf by leaf, untextured ones last), command recording (frame_recorder.h).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "mta/camera.h"
#include "mta/paging_file.h"
#include "mta/residency.h"
#include "mta/runtime_geometry.h"

namespace tessera::mta {

enum class RenderMode : uint8_t {
  AtlasTree = 0,  // §4.4 with the memory manager
  Original = 1,   // every visible leaf with its original textures (run 1 of §4.7.2)
  Dummy = 2,      // every visible leaf with one white texture (run 2: an upper bound, wrong image)
};
const char* renderModeName(RenderMode m);

// How the distance test accounts for off-axis magnification (see above and docs/mta-render.md).
enum class DistanceBound : uint8_t {
  PerNode = 0,      // d · cos²θ_max over the node's box clipped to the frustum (default)
  FrameCorner = 1,  // d · cos²θ_max of the frustum's corner ray, the same for every node
  Thesis = 2,       // plain d (the thesis; the τ guarantee holds on the view axis only)
};
const char* distanceBoundName(DistanceBound b);
// "node", "corner", "thesis"; throws Error naming `what` otherwise.
DistanceBound parseDistanceBound(const std::string& text, const std::string& what);

struct ViewParams {
  Camera camera;
  uint32_t width = 1024, height = 768;
  double tau = 0.0;  // runtime τ; 0 = the build's
  DistanceBound bound = DistanceBound::PerNode;
};

// Which blocks each node needs for the layers the renderer draws: its atlas blocks (one per drawn layer)
// and, for leaves, the blocks holding pieces of the original images that its triangles' textures of a
// drawn layer use. Blocks of other layers are in no node's lists, so the usage traversal never requests
// them (they stay Unused) and the rendering traversal never waits for them.
struct BlockIndex {
  struct PerTree {
    std::vector<uint32_t> atlasFirst;                 // per node: into atlas (atlasPerNode each)
    std::vector<uint32_t> atlas;
    std::vector<uint32_t> originalFirst, originalCount;  // per node (leaves), into original
    std::vector<uint32_t> original;
  };
  std::vector<PerTree> trees;
  uint32_t atlasPerNode = 1;  // the drawn layers that the file has
  LayerMask layers = 1;       // which ones
};
// drawnLayers: bit l set when the renderer samples layer l (frame_recorder.h kRecordedLayers: layers 0
// and 1); bits of layers the file lacks are ignored. Error if it names none of the file's layers.
// Precondition: `meta` passed PagingFile's validation. Also checks what the walkers of this file index
// with (child indices that only increase, block, texture and image indices in range): a meta that breaks
// it is an Error ("internal error"), never an access out of bounds or an endless walk.
BlockIndex buildBlockIndex(const MtaMeta& meta, LayerMask drawnLayers);

// Per-frame derived view quantities shared by both traversals.
struct ViewContext {
  Frustum frustum;
  glm::dvec3 eye{0, 0, 0};
  DistanceBound bound = DistanceBound::PerNode;
  double distanceFactor = 1.0;    // FrameCorner (and PerNode's fallback): the corner ray's cos²θ; Thesis: 1
  double minDistanceScale = 1.0;  // build -> frame rescaling of minDistance
  glm::dmat4 view{1.0};           // viewMatrixD: camera space, looking down -z
  double tanX = 0.0, tanY = 0.0;  // the window's half extents at depth 1
};
ViewContext makeViewContext(const MtaMeta& meta, const ViewParams& view);
// The factor d is multiplied by in the distance test of a node with these bounds: cos²θ_max of the box
// clipped to the frustum (PerNode; the corner ray's when the box reaches behind the eye plane, where its
// projection is unbounded), the corner ray's (FrameCorner) or 1 (Thesis). Never below the corner ray's.
double distanceFactor(const ViewContext& ctx, const std::array<float, 6>& bounds);

// One entry per paging-file block.
std::vector<BlockPriority> usagePriorities(const MtaMeta& meta, const BlockIndex& index, const ViewContext& ctx);

// White: the dummy run's one texture. Untextured: triangles without a texture (the presets' terrain and
// roofs), drawn with the same 1x1 white texture and a grey tint so that they read as ground.
enum class DrawSource : uint8_t { Atlas, Original, White, Untextured };
struct PlannedDraw {
  DrawSource source = DrawSource::Atlas;
  uint8_t tree = 0;
  uint32_t node = 0;      // Atlas: the node whose atlas is bound; Original: the leaf (the first, once
                          // groupDrawsByTexture merged contiguous ranges of several leaves)
  int32_t texture = -1;   // Original: scene texture (layer 0)
  uint32_t first = 0, count = 0;  // global triangles (runtime_geometry.h)
  int32_t texture1 = -1;  // Original: scene texture of layer 1 (runtime_geometry.h TextureRun), -1 = none
};

// A node of one of the file's trees.
struct NodeRef {
  uint8_t tree = 0;
  uint32_t node = 0;
  friend bool operator==(const NodeRef&, const NodeRef&) = default;
  friend auto operator<=>(const NodeRef&, const NodeRef&) = default;
};

// A node the AtlasTree traversal refined (drawn through its children, or a leaf drawn with its original
// textures) although its own atlas is resident: a node a bind budget may draw with its atlas instead
// (bind_budget.h). ratio = d · factor / (minDistance · scale), below 1 (the distance test failed): drawn
// with its atlas, its texels are magnified up to 1/ratio times more than τ allows.
struct RefinedNode {
  NodeRef ref;
  double ratio = 0.0;
};

struct FramePlan {
  std::vector<PlannedDraw> draws;
  uint32_t atlasNodes = 0;       // nodes drawn with their atlas
  uint32_t originalLeaves = 0;   // leaves drawn with original textures
  uint32_t coarserThanNeeded = 0;  // nodes drawn with their atlas only because refinement was impossible (Figure 30)
  uint32_t coarsenedForBinds = 0;  // nodes drawn with their atlas only because of a bind budget (bind_budget.h)
  double worstBindRatio = 1.0;     // the least RefinedNode::ratio among those (1 when none)
  uint32_t leavesDrawn = 0;
  uint64_t trianglesDrawn = 0;
  std::vector<RefinedNode> refined;  // AtlasTree mode, in traversal order
};

// resident(block): whether a block is in memory (AtlasTree mode; ignored by the other modes).
// drawWithAtlas (AtlasTree mode, sorted): nodes drawn with their resident atlas even where the distance
// test asks for refinement, counted in coarsenedForBinds; bind_budget.h chooses them. Each must be a
// node the traversal reaches with its atlas resident (an earlier plan's RefinedNode); others are ignored.
FramePlan planFrame(const MtaMeta& meta, const RuntimeGeometry& geometry, const BlockIndex& index, const ViewContext& ctx,
                    RenderMode mode, const std::function<bool(uint32_t)>& resident,
                    std::span<const NodeRef> drawWithAtlas = {});

}  // namespace tessera::mta
