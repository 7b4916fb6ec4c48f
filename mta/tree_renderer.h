// Rendering an atlas tree paging file frame by frame on the oracle: the memory manager, the traversals
// and the recorder put together (thesis §4.4, §4.6), plus the comparison runs of §4.7.2.
//
// Implements: per frame, in this order: the usage traversal and the memory manager's update (loading
// within the budget happens before the frame is drawn, so frame 0 already has what the budget allowed),
// the rendering traversal over what is in memory, the draws grouped by texture (draw_order.h, unless
// RendererOptions::groupBinds is off), recording, and execution on the CPU oracle; the
// frame's statistics (counters from the recorded list, residency, timings) as JSON with plain keys.
// Does not implement: camera paths (camera_path.h), files and plots (tools/cli/cmd_mta_render.cpp).
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "mta/draw_order.h"
#include "mta/frame_recorder.h"
#include "mta/paging_file.h"
#include "mta/residency.h"
#include "mta/runtime_geometry.h"
#include "mta/traversal.h"
#include "raster/counters.h"

namespace tessera {
class CpuBackend;
}

namespace tessera::mta {

struct RendererOptions {
  RenderMode mode = RenderMode::AtlasTree;
  ResidencyOptions residency;     // AtlasTree mode only
  uint32_t width = 1024, height = 768;
  double tau = 0.0;               // 0 = the build's τ
  DistanceBound bound = DistanceBound::PerNode;  // see traversal.h
  // Record the draws grouped by texture (draw_order.h): each texture bound once a frame. false keeps
  // planFrame's leaf-by-leaf order (`--no-group-binds`), for comparison. Every mode, the comparison runs too.
  bool groupBinds = true;
  // AtlasTree mode: at most this many texture binds a frame (bind_budget.h), by drawing refined nodes
  // with their resident atlases; 0 = no cap (the thesis). Needs groupBinds, which it counts on.
  uint32_t maxBinds = 0;
  int threads = 0;                // oracle threads; the bytes never depend on it
  // The oracle's per-frame memory check (limits.frameBytes, `--memory-budget`): a frame of run 1 uploads
  // every visible leaf's original textures decoded, which on berlin 10,000 is 6.1 GiB.
  ResourceLimits limits;
};

struct FrameResult {
  uint32_t frame = 0;
  FramePlan plan;
  FrameCounters counters;
  ResidencyFrameStats residency;  // AtlasTree mode
  uint64_t bytesResident = 0, blocksResident = 0, capacityBytes = 0;
  // RAM of the decoded RGBA8 mip chains the texture cache holds after recording the frame (texture_cache.h):
  // the chains of the textures drawn, kept while their blocks stay resident. Capacity and bytesResident
  // count paging-file bytes, as the thesis's k does; this is what drawing from them costs on top.
  uint64_t decodedBytesResident = 0;
  double updateMs = 0.0, recordMs = 0.0, renderMs = 0.0;
  std::vector<uint8_t> image;     // RGBA8, rows bottom first (GL order), width x height
  std::vector<BoundTexture> drawTexture;
};

class TreeRenderer {
 public:
  TreeRenderer(const PagingFile& file, RendererOptions options);
  ~TreeRenderer();
  TreeRenderer(const TreeRenderer&) = delete;
  TreeRenderer& operator=(const TreeRenderer&) = delete;

  // Renders the next frame of a sequence (the memory manager carries over between calls).
  FrameResult renderFrame(const Camera& camera);
  // The id frame of the last rendered frame's plan (same draws, "object_id", R32UI triangle indices),
  // executed; returns attachment 0, rows bottom first.
  std::vector<uint32_t> triangleIds(const Camera& camera, const FramePlan& plan);

  const RuntimeGeometry& geometry() const { return geometry_; }
  const PagingFile& file() const { return file_; }
  const RendererOptions& options() const { return options_; }
  const Residency* residency() const { return residency_.get(); }
  // The command list of the last frame recorded (renderFrame or triangleIds), e.g. to write as a .tframe.
  const CommandList& lastList() const { return recorded_.list; }
  ViewParams view(const Camera& camera) const;

 private:
  std::vector<uint8_t> presentedLevel0() const;
  const PagingFile& file_;
  RendererOptions options_;
  RuntimeGeometry geometry_;
  BlockIndex index_;
  std::unique_ptr<Residency> residency_;
  std::unique_ptr<TextureCache> textures_;
  std::unique_ptr<CpuBackend> backend_;
  // Every frame is recorded into this one, so its upload blob (every resident atlas) keeps its
  // storage from frame to frame (CommandList::clear).
  RecordedFrame recorded_;
  uint32_t frame_ = 0;
};

nlohmann::json toJson(const FrameResult& r, RenderMode mode);

}  // namespace tessera::mta
