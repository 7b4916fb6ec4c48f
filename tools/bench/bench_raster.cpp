// Oracle frame time per built-in scene, at 1 and 2 threads, and the city block at 1280x720.
// Run: build/bench_raster [--benchmark_filter=city] ; items/s = shaded fragments per second.
#include <benchmark/benchmark.h>

#include "raster/cpu_backend.h"
#include "tools/scenes/scenes.h"

using namespace tessera;

static void renderScene(benchmark::State& state, std::string_view name, int w, int h) {
  const CommandList list = scenes::build(name, w, h);
  uint64_t fragments = 0;
  for (auto _ : state) {
    CpuBackend b(RenderOptions{int(state.range(0))});
    b.execute(list, name);
    fragments += b.stats().fragments_shaded;
    benchmark::DoNotOptimize(b.stats().pixels_written);
  }
  state.SetItemsProcessed(int64_t(fragments));
}

static void registerAll() {
  for (const scenes::SceneInfo& s : scenes::all())
    benchmark::RegisterBenchmark(std::string(s.name).c_str(), renderScene, s.name, s.width, s.height)
        ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
  benchmark::RegisterBenchmark("city_block_720p", renderScene, "city_block", 1280, 720)
      ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
}

static const int kRegistered = (registerAll(), 0);
