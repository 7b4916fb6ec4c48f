// The child process of `tessera bench sweep`: one thread count, one llvmpipe mode, the whole plan.
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "base/atomic_file.h"
#include "base/cpu_time.h"
#include "gl/gl_backend.h"
#include "raster/cpu_backend.h"
#include "tools/cli/bench_sweep.h"
#include "tools/cli/gl_options.h"
#include "tools/cli/options.h"
#include "tools/scenes/sweep_scenes.h"

namespace tessera::cli {

// The fixed size of the setup-bound sweep: big enough that 1M one-pixel triangles fit side by side.
constexpr int kTrisWidth = 1280, kTrisHeight = 720;

CommandList SweepPoint::build() const {
  if (workload == "tiny_tris") return scenes::buildTinyTris(width, height, triangles);
  return scenes::buildFillLayers(width, height, variant);
}

std::string SweepPoint::label() const {
  if (workload == "tiny_tris") return fmt::format("tiny_tris {} tris", triangles);
  return fmt::format("{} {} {}x{}", workload, variant, width, height);
}

std::vector<SweepPoint> sweepPlan(bool quick) {
  std::vector<SweepPoint> plan;
  const std::vector<std::pair<int, int>> sizes =
      quick ? std::vector<std::pair<int, int>>{{320, 240}, {640, 480}}
            : std::vector<std::pair<int, int>>{{320, 240}, {640, 480}, {1280, 720}, {1920, 1080}};
  const std::vector<std::string> variants = quick ? std::vector<std::string>{"trilinear"} : scenes::fillVariants();
  for (const std::string& v : variants)
    for (const auto& [w, h] : sizes) plan.push_back({"fill_layers", v, w, h, 0});
  const std::vector<int> counts =
      quick ? std::vector<int>{1000, 10000} : std::vector<int>{1000, 10000, 100000, 1000000};
  for (int n : counts) plan.push_back({"tiny_tris", "flat_color", kTrisWidth, kTrisHeight, n});
  return plan;
}

namespace {

struct WorkerArgs {
  int threads = 1, repeat = 5;
  bool strict = false, quick = false, stages = false;
  std::string out;
  gl::GlOptions gl;
};

// One oracle run: the frame's wall time, and the process's CPU time over execute() less validation and
// the resource commands (both run on the calling thread alone, so their wall time is their CPU time).
std::pair<double, double> timeOracle(CpuBackend& b, const CommandList& list, const std::string& name) {
  const double cpu0 = processCpuMs();
  b.execute(list, name);
  const double cpu = processCpuMs() - cpu0;
  const StageTimes& st = b.stageTimes();
  return {st.frameMs, std::max(0.0, cpu - st.validateMs - st.resourcesMs)};
}

void runWorker(const WorkerArgs& a) {
  gl::GlOptions go = a.gl;
  go.lpThreads = a.threads;
  go.strict = a.strict;
  auto glb = gl::GlBackend::create(go);
  const std::string mode = a.strict ? "llvmpipe_strict" : "llvmpipe";
  const std::vector<SweepPoint> plan = sweepPlan(a.quick);
  nlohmann::json points = nlohmann::json::array();
  for (size_t i = 0; i < plan.size(); ++i) {
    const SweepPoint& p = plan[i];
    const std::string name = p.label();
    const CommandList list = p.build();
    auto oracle = std::make_unique<CpuBackend>(RenderOptions{a.threads});
    // Warm-up: GL compiles its programs (and llvmpipe its shader variants) on first use; both sides touch
    // their memory once.
    oracle->execute(list, name);
    glb->execute(list, name);
    nlohmann::json o = {{"index", i}};
    std::vector<double> oms, ocpu, gms, gcpu;
    for (int r = 0; r < a.repeat; ++r) {
      // Interleaved run by run, the first renderer alternating, so a disturbance of the shared machine
      // falls on both sides alike.
      const auto runGl = [&] {
        glb->execute(list, name);
        gms.push_back(glb->lastFrameTimes().frameMs);
        gcpu.push_back(glb->lastFrameTimes().frameCpuMs);
      };
      const auto runOracle = [&] {
        const auto [ms, cpu] = timeOracle(*oracle, list, name);
        oms.push_back(ms);
        ocpu.push_back(cpu);
      };
      if (r % 2 == 0) {
        runOracle();
        runGl();
      } else {
        runGl();
        runOracle();
      }
    }
    o["oracle_ms"] = oms;
    o["oracle_cpu_ms"] = ocpu;
    o["gl_ms"] = gms;
    o["gl_cpu_ms"] = gcpu;
    // The timed backend's last frame goes first: a staged backend next to it would allocate its frame from
    // fresh pages, which the timed runs (after their warm-up) never do.
    oracle.reset();
    if (a.stages) {
      // A separate backend with the stage clocks on, so they never perturb the timed runs above; its
      // first run warms it up like the timed ones', the second is reported.
      RenderOptions so{a.threads};
      so.stageTimes = true;
      CpuBackend staged(so);
      staged.execute(list, name);
      staged.execute(list, name);
      const StageTimes& st = staged.stageTimes();
      o["stages"] = {{"frame_ms", st.frameMs}, {"vertex_ms", st.vertexMs}, {"clip_ms", st.clipMs},
                     {"setup_ms", st.setupMs}, {"bin_ms", st.binMs},       {"rast_ms", st.rastMs},
                     {"shade_ms", st.shadeMs}, {"sample_ms", st.sampleMs}, {"fragops_ms", st.fragopsMs}};
    }
    std::vector<double> so = oms, sg = gms;
    std::sort(so.begin(), so.end());
    std::sort(sg.begin(), sg.end());
    std::fprintf(stderr, "bench sweep: [%d thread%s, %s] %zu/%zu %s: oracle %.2f ms, %s %.2f ms\n", a.threads,
                 a.threads == 1 ? "" : "s", mode.c_str(), i + 1, plan.size(), name.c_str(), so[so.size() / 2],
                 mode.c_str(), sg[sg.size() / 2]);
    points.push_back(std::move(o));
  }
  const nlohmann::json j = {{"threads", a.threads},
                            {"gl_mode", mode},
                            {"repeat", a.repeat},
                            {"gl_info", glb->info().toJson()},
                            {"points", points}};
  writeFileAtomically(a.out, j.dump(1));
}

}  // namespace

void addSweepWorkerCommand(CLI::App* bench) {
  auto a = std::make_shared<WorkerArgs>();
  auto* cmd = bench->add_subcommand("sweep-worker", "Internal: the child process of `bench sweep`");
  cmd->group("");  // hidden from --help: not a user command
  cmd->add_option("--threads", a->threads, "Oracle threads and LP_NUM_THREADS")->check(CLI::Range(1, kMaxThreads));
  cmd->add_option("--repeat", a->repeat, "Timed runs per point")->check(CLI::Range(1, 1000));
  cmd->add_option("--out", a->out, "The JSON file of raw runs")->required();
  cmd->add_flag("--strict", a->strict, "llvmpipe fast paths off");
  cmd->add_flag("--quick", a->quick, "The quick plan");
  cmd->add_flag("--stages", a->stages,
                "Also per point an oracle run with per-stage times (after a warm-up run), in a backend of its own");
  addGlBackendOptions(cmd, a->gl);
  cmd->callback([a] { runWorker(*a); });
}

}  // namespace tessera::cli
