// Render-to-texture-atlas on the oracle: STD, RTT and RTTA frames of synthetic berlin cities with
// --objects node, at the paper's object counts (Table 1: 5, 21, 269, 580; berlin with N = #Obj - 1
// buildings, docs/model-import.md), so the crossover the paper reports (RTTA behind RTT at few objects,
// ahead at many) can be looked for on a CPU rasterizer. The frame is recorded once outside the timed
// loop; the loop times CpuBackend::execute (uploads included). Cities are generated once into a
// temporary directory with 64² facades. RTT allocates one viewport-sized layer per visible object, so
// the size is 256x256 (580 layers of 256² are 0.6 GB of targets).
// Run: build/bench_rtta [--benchmark_filter=BM_Rtta/rtta]
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <memory>

#include "batching/input_batches.h"
#include "model/city_gen.h"
#include "model/model.h"
#include "model/object_groups.h"
#include "mta/camera.h"
#include "mta/camera_path.h"
#include "raster/cpu_backend.h"
#include "rtta/rtta_record.h"

using namespace tessera;

namespace {

const rtta::RttaScene& berlin(uint32_t objects) {
  static std::map<uint32_t, std::unique_ptr<rtta::RttaScene>> cache;
  auto& slot = cache[objects];
  if (!slot) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("tessera_bench_rtta_" + std::to_string(objects));
    model::CityOptions o;
    o.buildings = objects - 1;
    o.textureSize = 64;
    o.outDir = dir.string();
    o.progress = false;
    const model::CitySummary cs = model::generateCity(o);
    const model::Model m = model::loadModel(cs.gltf);
    const std::vector<model::ObjectGroup> groups = model::groupObjects(m, model::ObjectGrouping::Node);
    std::vector<uint32_t> objectOf(m.meshes.size());
    std::vector<std::string> names;
    for (uint32_t g = 0; g < groups.size(); ++g) {
      names.push_back(groups[g].name);
      for (uint32_t mesh : groups[g].meshes) objectOf[mesh] = g;
    }
    slot = std::make_unique<rtta::RttaScene>(rtta::makeRttaScene(batching::prepareInput(m), objectOf, names));
    std::filesystem::remove_all(dir);
  }
  return *slot;
}

void rttaFrame(benchmark::State& state, rtta::Mode mode) {
  const uint32_t objects = uint32_t(state.range(0));
  const rtta::RttaScene& s = berlin(objects);
  const mta::CameraPath p = mta::builtinPath("orbit", s.tab.bounds, 24);
  rtta::RttaView v;
  v.width = v.height = 256;
  v.mvp = mta::viewProjection(p.frames[8], v.width, v.height);
  v.eye = p.frames[8].eye;
  rtta::RttaOptions o;
  o.mode = mode;
  o.params.cull = false;  // the paper's Table 1 runs had no view-frustum culling
  const rtta::RttaFrame f = rtta::recordRttaFrame(s, v, o);
  CpuBackend b(RenderOptions{int(state.range(1))});
  for (auto _ : state) b.execute(f.list, "rtta");
  state.counters["objects"] = double(s.objectNames.size());
  state.counters["layers"] = double(f.atlas.layers);
}

void registerAll() {
  for (auto [name, mode] : {std::pair{"BM_Rtta/std", rtta::Mode::Std}, std::pair{"BM_Rtta/rtt", rtta::Mode::Rtt},
                            std::pair{"BM_Rtta/rtta", rtta::Mode::Rtta}})
    benchmark::RegisterBenchmark(name, rttaFrame, mode)
        ->ArgsProduct({{5, 21, 269, 580}, {1, 2}})
        ->ArgNames({"objects", "threads"})
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
}

const int kRegistered = (registerAll(), 0);

}  // namespace
