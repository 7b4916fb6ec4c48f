// Where the oracle's time goes: wall time of a frame's parts and CPU time per pipeline stage.
//
// Implements: the StageTimes record CpuBackend::stageTimes() returns, and the cheap cycle clock the
// stages use to fill it (rdtsc on x86-64, the steady clock elsewhere, converted to milliseconds with
// the frame's own wall time as reference).
// Does not implement: any effect on rendering. Timing never changes an output byte: the clocks are
// read around stages, never inside a value's computation. Per-stage times are benchmark data; no
// test asserts a time (docs/bench.md).
#pragma once

#include <chrono>
#include <cstdint>

#if defined(__x86_64__) || defined(_M_X64)
#include <x86intrin.h>
#endif

namespace tessera {

struct StageTimes {
  // Wall time, always measured. frameMs is execute() without validation and without the resource
  // commands (CreateTexture, UploadTexture, CreateBuffer, UploadBuffer, CreateSampler,
  // CreateProgram): the draws and clears through the last tile, what a GL benchmark times between
  // its uploads and glFinish.
  double validateMs = 0.0, resourcesMs = 0.0, frameMs = 0.0;
  // CPU time summed over worker threads, only with RenderOptions::stageTimes (else all 0):
  //   vertex: vertex fetch and the vertex stage;      clip: polygon clipping of crossing triangles;
  //   setup: the rest of triangle setup (window transform, snapping, edges, tile lists);
  //   bin: appending set-up triangles to the tile bins (serial);
  //   rast: tile work outside the fragment program and the fragment operations (coverage,
  //         interpolation, early depth, clears);
  //   shade: the fragment program without its texture lookups;  sample: texture lookups;
  //   fragops: late depth, depth and colour writes, blending.
  bool perStage = false;
  double vertexMs = 0.0, clipMs = 0.0, setupMs = 0.0, binMs = 0.0, rastMs = 0.0, shadeMs = 0.0, sampleMs = 0.0,
         fragopsMs = 0.0;
  // Work the fast path found it could skip, always counted (not GL counters: the stats JSON counts what
  // GL does): 8x8 blocks walked by no triangle because the hierarchical Z found all their covered
  // fragments failing the depth test, and those fragments.
  uint64_t hizBlocksSkipped = 0, hizFragmentsSkipped = 0;
  // Provenance mode's lookup shortcuts (raster/sample_interval.cpp): lambda alternatives not looked up
  // (inside a trilinear level pair's weights), and level grids shared by a lookup's plans.
  uint64_t provPlansSkipped = 0, provGridsShared = 0;
  // Scenes rasterized (tile passes over the target): one per render target and per upload that pending
  // work reads, plus one per RenderOptions::sceneTriangles set-up triangles (a flush for memory).
  uint64_t scenes = 0;
};

namespace detail {

// A monotonic tick counter, cheap enough to read around every fragment-program batch.
inline uint64_t stageClock() {
#if defined(__x86_64__) || defined(_M_X64)
  return __rdtsc();
#else
  return uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(
                      std::chrono::steady_clock::now().time_since_epoch())
                      .count());
#endif
}

enum Stage : int { kStageVertex, kStageClip, kStageSetup, kStageBin, kStageTile, kStageShade, kStageSample,
                   kStageFragops, kStageCount };

// Ticks per stage of one thread; kStageTile holds whole tiles, of which shade and fragops are parts,
// and kStageShade whole program calls, of which sample is a part.
struct StageTicks {
  uint64_t t[kStageCount] = {};
};

// sample.cpp: the calling thread adds its texture-lookup ticks to *ticks (nullptr: no timing). Set
// per tile by the rasterizer when stage times are on.
void setSampleTicks(uint64_t* ticks);

}  // namespace detail
}  // namespace tessera
