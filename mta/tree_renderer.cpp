#include "mta/tree_renderer.h"

#include <chrono>
#include <cstring>

#include "mta/bind_budget.h"
#include "raster/cpu_backend.h"

namespace tessera::mta {

namespace {
double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

TreeRenderer::TreeRenderer(const PagingFile& file, RendererOptions options)
    : file_(file),
      options_(options),
      geometry_(buildRuntimeGeometry(file.meta())),
      index_(buildBlockIndex(file.meta(), kRecordedLayers)) {
  if (options_.maxBinds != 0 && !options_.groupBinds)
    throw Error("renderer: a bind cap counts the binds of draws grouped by texture; it cannot be used with leaf-by-leaf draws");
  if (options_.width == 0 || options_.height == 0 || options_.width > 16384 || options_.height > 16384)
    throw Error("renderer: frame size " + std::to_string(options_.width) + "x" + std::to_string(options_.height) + " is outside 1..16384");
  // Requests and pins follow what the recorder draws, never an option: blocks of other layers are dead weight.
  options_.residency.drawnLayers = kRecordedLayers;
  if (options_.mode == RenderMode::AtlasTree) residency_ = std::make_unique<Residency>(file_, options_.residency);
  textures_ = std::make_unique<TextureCache>(file_, residency_.get());
  backend_ = std::make_unique<CpuBackend>(RenderOptions{options_.threads, false, options_.limits});
}

TreeRenderer::~TreeRenderer() = default;

// Attachment 0 of the frame just executed (the recorder's target), level 0.
std::vector<uint8_t> TreeRenderer::presentedLevel0() const {
  return backend_->texture(backend_->presented().at(0).texture)->levels[0];
}

ViewParams TreeRenderer::view(const Camera& camera) const {
  ViewParams v;
  v.camera = camera;
  v.width = options_.width;
  v.height = options_.height;
  v.tau = options_.tau;
  v.bound = options_.bound;
  return v;
}

FrameResult TreeRenderer::renderFrame(const Camera& camera) {
  FrameResult r;
  r.frame = frame_++;
  const MtaMeta& meta = file_.meta();
  const ViewParams v = view(camera);
  const ViewContext ctx = makeViewContext(meta, v);

  auto t0 = std::chrono::steady_clock::now();
  std::function<bool(uint32_t)> resident = [](uint32_t) { return true; };
  if (residency_) {
    r.residency = residency_->update(usagePriorities(meta, index_, ctx));
    textures_->prune();
    resident = [this](uint32_t b) { return residency_->resident(b); };
    r.bytesResident = residency_->bytesResident();
    r.blocksResident = residency_->blocksResident();
    r.capacityBytes = residency_->capacity();
  }
  r.plan = planFrameWithinBinds(meta, geometry_, index_, ctx, options_.mode, resident, options_.maxBinds);
  if (options_.groupBinds) groupDrawsByTexture(r.plan);
  r.updateMs = msSince(t0);

  t0 = std::chrono::steady_clock::now();
  RecordParams rp;
  rp.width = options_.width;
  rp.height = options_.height;
  RecordedFrame& rec = recorded_;
  recordFrame(meta, geometry_, r.plan, v, *textures_, rp, rec);
  r.counters = countCommands(rec.list);
  r.drawTexture = rec.drawTexture;
  r.decodedBytesResident = textures_->decodedBytes();
  r.recordMs = msSince(t0);

  t0 = std::chrono::steady_clock::now();
  // The label errors carry: which run and frame (`mta runs` renders three).
  backend_->execute(rec.list, std::string(renderModeName(options_.mode)) + " run, frame " + std::to_string(r.frame));
  r.renderMs = msSince(t0);
  r.image = presentedLevel0();
  return r;
}

std::vector<uint32_t> TreeRenderer::triangleIds(const Camera& camera, const FramePlan& plan) {
  const ViewParams v = view(camera);
  RecordParams rp;
  rp.width = options_.width;
  rp.height = options_.height;
  rp.idFrame = true;
  recordFrame(file_.meta(), geometry_, plan, v, *textures_, rp, recorded_);
  backend_->execute(recorded_.list, "atlas tree id frame");
  const std::vector<uint8_t> bytes = presentedLevel0();
  std::vector<uint32_t> ids(size_t(options_.width) * options_.height);
  std::memcpy(ids.data(), bytes.data(), ids.size() * 4);
  return ids;
}

nlohmann::json toJson(const FrameResult& r, RenderMode mode) {
  nlohmann::json j;
  j["frame"] = r.frame;
  j["mode"] = renderModeName(mode);
  j["texture_binds"] = r.counters.texture_binds;
  j["texture_state_changes"] = r.counters.texture_state_changes;
  j["texture_binds_unit1"] = r.counters.units[1].texture_binds;  // layer 1 (files that have one)
  j["draw_calls"] = r.counters.draw_calls;
  j["state_changes"] = r.counters.state_changes;
  j["triangles_drawn"] = r.plan.trianglesDrawn;
  j["nodes_with_atlas"] = r.plan.atlasNodes;
  j["nodes_with_original_textures"] = r.plan.originalLeaves;
  j["nodes_coarser_than_needed"] = r.plan.coarserThanNeeded;
  j["nodes_coarsened_for_binds"] = r.plan.coarsenedForBinds;
  // null when no node was coarsened: a ratio of 1 would read as "coarsened, at no cost".
  j["bind_cap_worst_ratio"] = r.plan.coarsenedForBinds ? nlohmann::json(r.plan.worstBindRatio) : nlohmann::json(nullptr);
  j["leaves_drawn"] = r.plan.leavesDrawn;
  if (mode == RenderMode::AtlasTree) {
    j["blocks_resident"] = r.blocksResident;
    j["bytes_resident"] = r.bytesResident;
    j["decoded_bytes_resident"] = r.decodedBytesResident;
    j["capacity_bytes"] = r.capacityBytes;
    j["blocks_loaded"] = r.residency.blocksLoaded;
    j["bytes_loaded"] = r.residency.bytesLoaded;
    j["blocks_evicted"] = r.residency.blocksEvicted;
    j["loads_cancelled"] = r.residency.loadsCancelled;
    j["ideal_blocks"] = r.residency.idealBlocks;
    j["ideal_bytes"] = r.residency.idealBytes;
    j["ideal_blocks_cut"] = r.residency.idealBlocksCut;
    j["needed_blocks_missing"] = r.residency.neededMissing;
    j["queue_length"] = r.residency.queueLength;
  }
  j["frame_time_ms"] = r.renderMs;
  j["update_ms"] = r.updateMs;
  j["record_ms"] = r.recordMs;
  return j;
}

}  // namespace tessera::mta
