// The CPU backend: the oracle. Replays a CommandList bit-reproducibly.
//
// Implements: execution of every command kind of command_list.h with the rules of
// docs/spec-choices.md: vertex fetch and program stages, clipping, setup and 64x64 binning, and
// parallel per-tile rasterization on oneTBB (tiles own their pixels; within a tile primitives run in
// submission order, so the bytes do not depend on the thread count).
// Does not implement: validation beyond validate.h (every list is validated before it runs), GL.
//
// Outputs: after execute(), every resource is readable; the frame's presented images are the colour
// attachments of the render target bound when the list ends (every layer of a layered target).
#pragma once

#include <memory>
#include <string_view>
#include <vector>

#include "base/resource_limits.h"
#include "raster/command_list.h"
#include "raster/lod_probe.h"
#include "raster/pipeline.h"
#include "raster/stage_times.h"
#include "raster/texture.h"

namespace tessera {

struct RenderOptions {
  int threads = 0;          // 0 = all hardware threads
  bool provenance = false;  // also record per-pixel intervals and ambiguity classes (provenance.h)
  ResourceLimits limits;    // execute() refuses a list over limits.frameBytes before allocating (validate.h)
  // Provenance: GL_SUBPIXEL_BITS of the implementation that will be judged against the intervals
  // (tolerance::edgeMarginSub). GL's minimum, 4, when it is not known.
  int otherSubpixelBits = 4;
  // Record, per pixel of each colour attachment 0 rendered to, the LOD of the lookups of the fragment
  // stored there (raster/lod_probe.h; lodMap()). Slower (one quad per program call) but the images,
  // counters and every other output are the same bytes. Ignored in provenance mode.
  bool lodProbe = false;
  // Measure CPU time per pipeline stage (stageTimes()). Costs a few cycle-counter reads per program
  // batch and clipped triangle; every output is the same bytes.
  bool stageTimes = false;
  // The set-up triangles a scene may hold before it is rasterized (a flush for memory; 0: cpu_backend.cpp's
  // choice, kSceneTriangles, or kSingleThreadScene at one thread). Every output is the same bytes for
  // any bound: tests render with a bound of 1, which rasterizes after every draw.
  uint32_t sceneTriangles = 0;
};

// One presented image: attachment `attachment` of the final target at (level, layer).
struct PresentedImage {
  ResourceId texture = kNone;
  uint32_t attachment = 0, level = 0, layer = 0;
};

class CpuBackend {
 public:
  explicit CpuBackend(RenderOptions options = {});
  ~CpuBackend();
  CpuBackend(const CpuBackend&) = delete;
  CpuBackend& operator=(const CpuBackend&) = delete;

  // Validates the list against options.limits (throws Error naming `frameName` and the command index)
  // before anything is allocated, and runs it from GL's initial state: resources and state of an
  // earlier execute() are dropped first.
  void execute(const CommandList& list, std::string_view frameName = "frame");

  const TextureData* texture(ResourceId id) const;
  std::vector<PresentedImage> presented() const;
  const detail::PipelineStats& stats() const;
  // Where the last execute() spent its time (stage_times.h). Wall times always; per-stage CPU times
  // with RenderOptions::stageTimes.
  const StageTimes& stageTimes() const;
  const RenderOptions& options() const;
  // With RenderOptions::lodProbe: the LOD map of presented image `p` (its texture, level and layer);
  // nullptr without the probe or if nothing was rendered to it.
  const LodMap* lodMap(const PresentedImage& p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tessera
