// Oracle frame time per built-in scene, at 1 and 2 threads, the city block at 1280x720 and 1920x1080,
// and two `tessera bench sweep` workloads (tiny_tris_100k / tiny_tris_1m: setup-bound;
// fill_layers_720p: fill-bound), so one stage's change can be timed without the whole sweep.
// Run: build/bench_raster [--benchmark_filter=city] ; items/s = shaded fragments per second.
//
// One backend renders the frame once to warm up and then once per iteration, as `tessera bench sweep`
// and a GL benchmark reuse their context. The time of an iteration is the frame only
// (StageTimes::frameMs: the draws and clears through the last tile), as a GL benchmark times between
// its uploads and glFinish. What a frame costs around that is reported as counters, so it is visible
// but not mixed in: backend construction (construct_ms, once), validation (validate_ms) and the
// resource commands (resources_ms) per iteration.
// `--stages` also turns on per-stage CPU times (stage_*_ms counters, raster/stage_times.h); they
// cost a few cycle-counter reads per program batch. `--provenance` renders in provenance mode, the
// mode every cross-check runs (per-pixel intervals, three program runs per quad). `--simd=NAME` runs
// the sampler's SIMD kernel on one target (raster/sample_simd.h: avx3, avx2, sse4, ssse3, scalar) or
// not at all (reference), so one binary times a kernel against the scalar filter it must equal.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <cstring>

#include "base/error.h"
#include "raster/cpu_backend.h"
#include "raster/simd_targets.h"
#include "tools/scenes/scenes.h"
#include "tools/scenes/sweep_scenes.h"

using namespace tessera;

static bool g_stages = false;
static bool g_provenance = false;

static void renderList(benchmark::State& state, const std::string& name, const CommandList& list) {
  uint64_t fragments = 0, hizBlocks = 0, hizFragments = 0, plansSkipped = 0, gridsShared = 0;
  double scenes = 0.0;
  double constructMs = 0, validateMs = 0, resourcesMs = 0;
  StageTimes sum;
  RenderOptions o{int(state.range(0))};
  o.stageTimes = g_stages;
  o.provenance = g_provenance;
  const auto t0 = std::chrono::steady_clock::now();
  CpuBackend b(o);
  constructMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  b.execute(list, name);  // warm-up: the first frame also pays for first-touch pages of the scene's arrays
  for (auto _ : state) {
    b.execute(list, name);
    const StageTimes& st = b.stageTimes();
    state.SetIterationTime(st.frameMs / 1000.0);
    validateMs += st.validateMs, resourcesMs += st.resourcesMs;
    sum.vertexMs += st.vertexMs, sum.clipMs += st.clipMs, sum.setupMs += st.setupMs, sum.binMs += st.binMs;
    sum.rastMs += st.rastMs, sum.shadeMs += st.shadeMs, sum.sampleMs += st.sampleMs, sum.fragopsMs += st.fragopsMs;
    fragments += b.stats().fragments_shaded;
    hizBlocks += st.hizBlocksSkipped, hizFragments += st.hizFragmentsSkipped;
    scenes += double(st.scenes);
    plansSkipped += st.provPlansSkipped, gridsShared += st.provGridsShared;
    benchmark::DoNotOptimize(b.stats().pixels_written);
  }
  state.SetItemsProcessed(int64_t(fragments));
  const auto avg = [&](double v) { return benchmark::Counter(v / double(state.iterations())); };
  state.counters["construct_ms"] = constructMs;  // once per benchmark: the backend renders every iteration
  state.counters["validate_ms"] = avg(validateMs);
  state.counters["resources_ms"] = avg(resourcesMs);
  // Work the hierarchical Z skipped per frame (raster/rast.cpp): blocks and fragments never walked.
  state.counters["hiz_blocks"] = avg(double(hizBlocks));
  state.counters["hiz_fragments"] = avg(double(hizFragments));
  // Tile passes per frame: a frame is rasterized in more than one scene where its set-up triangles
  // exceed the scene bound (raster/cpu_backend.cpp, kSceneTriangles) or an upload needs it.
  state.counters["scenes"] = avg(scenes);
  if (g_provenance) {
    // Provenance mode's lookup shortcuts per frame (raster/sample_interval.cpp): lambda alternatives
    // not looked up, and level grids shared by a lookup's plans.
    state.counters["prov_plans_skipped"] = avg(double(plansSkipped));
    state.counters["prov_grids_shared"] = avg(double(gridsShared));
  }
  if (g_stages) {
    state.counters["stage_vertex_ms"] = avg(sum.vertexMs);
    state.counters["stage_clip_ms"] = avg(sum.clipMs);
    state.counters["stage_setup_ms"] = avg(sum.setupMs);
    state.counters["stage_bin_ms"] = avg(sum.binMs);
    state.counters["stage_rast_ms"] = avg(sum.rastMs);
    state.counters["stage_shade_ms"] = avg(sum.shadeMs);
    state.counters["stage_sample_ms"] = avg(sum.sampleMs);
    state.counters["stage_fragops_ms"] = avg(sum.fragopsMs);
  }
}

static void renderScene(benchmark::State& state, std::string_view name, int w, int h) {
  renderList(state, std::string(name), scenes::build(name, w, h));
}

static void renderTinyTris(benchmark::State& state, int triangles) {
  renderList(state, "tiny_tris", scenes::buildTinyTris(1280, 720, triangles));
}

static void renderFillLayers(benchmark::State& state, int w, int h, std::string_view variant) {
  renderList(state, "fill_layers", scenes::buildFillLayers(w, h, variant));
}

static void registerAll() {
  for (const scenes::SceneInfo& s : scenes::all())
    benchmark::RegisterBenchmark(std::string(s.name).c_str(), renderScene, s.name, s.width, s.height)
        ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseManualTime();
  benchmark::RegisterBenchmark("city_block_720p", renderScene, "city_block", 1280, 720)
      ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseManualTime();
  benchmark::RegisterBenchmark("city_block_1080p", renderScene, "city_block", 1920, 1080)
      ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseManualTime();
  benchmark::RegisterBenchmark("tiny_tris_100k", renderTinyTris, 100000)
      ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseManualTime();
  benchmark::RegisterBenchmark("tiny_tris_1m", renderTinyTris, 1000000)
      ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseManualTime();
  benchmark::RegisterBenchmark("fill_layers_720p", renderFillLayers, 1280, 720, "trilinear")
      ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseManualTime();
  // The sweep's other fill variants: the per-fragment cost without a texture, and with blending.
  benchmark::RegisterBenchmark("fill_flat_720p", renderFillLayers, 1280, 720, "flat_color")
      ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseManualTime();
  benchmark::RegisterBenchmark("fill_blend_720p", renderFillLayers, 1280, 720, "trilinear_blend")
      ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseManualTime();
}

int main(int argc, char** argv) {
  // Our own flag first, so Google Benchmark does not reject it.
  int n = 1;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--stages") == 0) {
      g_stages = true;
    } else if (std::strcmp(argv[i], "--provenance") == 0) {
      g_provenance = true;
    } else if (std::strncmp(argv[i], "--simd=", 7) == 0) {
      try {
        simd::forceTarget(argv[i] + 7);
      } catch (const Error& e) {
        std::fprintf(stderr, "bench_raster: --simd: %s\n", e.what());
        return 2;
      }
    } else {
      argv[n++] = argv[i];
    }
  }
  argc = n;
  registerAll();
  benchmark::AddCustomContext("simd_target", simd::activeTarget());
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
