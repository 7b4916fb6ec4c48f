// Texture-array batching on the oracle: the same railway.glb frame unbatched (one draw per mesh, a bind
// per texture change) and batched (Algorithm 2: two geometry batches), at 1 and 2 threads, so that the
// cost of the counted reductions on a CPU rasterizer is measured rather than assumed. The frame is
// recorded once outside the timed loop; the loop times CpuBackend::execute (uploads included).
// Run: build/bench_tab [--benchmark_filter=BM_Tab] ; TESSERA_RAILWAY overrides data/railway.glb.
#include <benchmark/benchmark.h>

#include <cstdlib>

#include "batching/batcher.h"
#include "batching/input_batches.h"
#include "batching/tab_record.h"
#include "model/model.h"
#include "mta/camera.h"
#include "mta/camera_path.h"
#include "raster/cpu_backend.h"

using namespace tessera;

namespace {

const batching::TabScene& railway() {
  static const batching::TabScene s = [] {
    const char* env = std::getenv("TESSERA_RAILWAY");
    batching::TabScene t = batching::prepareInput(model::loadModel(env ? env : TESSERA_SOURCE_DIR "/data/railway.glb"));
    batching::runAlgorithm1(t, batching::TabParams{});
    return t;
  }();
  return s;
}

void tabFrame(benchmark::State& state, batching::Variant variant, uint32_t w, uint32_t h) {
  const batching::TabScene& s = railway();
  const mta::CameraPath p = mta::builtinPath("orbit", s.bounds, 24);
  batching::TabView v;
  v.mvp = mta::viewProjection(p.frames[8], w, h);
  v.eye = p.frames[8].eye;
  v.width = w, v.height = h;
  const CommandList list = batching::recordTabFrame(s, variant, v);
  CpuBackend b(RenderOptions{int(state.range(0))});
  uint64_t fragments = 0;
  for (auto _ : state) {
    b.execute(list, "tab");
    fragments += b.stats().fragments_shaded;
  }
  state.SetItemsProcessed(int64_t(fragments));
}

void registerAll() {
  for (auto [name, variant] : {std::pair{"BM_Tab/baseline", batching::Variant::Baseline}, std::pair{"BM_Tab/batched", batching::Variant::Batched}}) {
    benchmark::RegisterBenchmark((std::string(name) + "/640x480").c_str(), tabFrame, variant, 640u, 480u)
        ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
    benchmark::RegisterBenchmark((std::string(name) + "/1280x720").c_str(), tabFrame, variant, 1280u, 720u)
        ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
  }
}

const int kRegistered = (registerAll(), 0);

}  // namespace
