// `tessera crosscheck | visibility | compare | bench crosscheck`: the oracle checked against GL,
// against Embree, and images against each other (`bench sweep`: bench_sweep.h).
#include <tbb/info.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "gl/gl_backend.h"
#include "gl/gl_mutation.h"
#include "raster/cpu_backend.h"
#include "raster/serialize.h"
#include "raster/validate.h"
#include "tools/cli/bench_sweep.h"
#include "tools/cli/commands.h"
#include "tools/cli/frame_job.h"
#include "tools/cli/gl_options.h"
#include "tools/cli/options.h"
#include "tools/cli/output_directory.h"
#include "tools/cli/repo_paths.h"
#include "tools/cli/stability_run.h"
#include "tools/scenes/scenes.h"
#include "verify/compare_report.h"
#include "verify/crosscheck.h"
#include "verify/crosscheck_report.h"
#include "verify/expectations.h"
#include "verify/stability.h"
#include "verify/image_compare.h"
#include "verify/visibility.h"

namespace tessera::cli {

namespace {

// A scene name or a .tframe path.
CommandList loadFrame(const std::string& what, const std::string& size) {
  if (scenes::find(what)) {
    const scenes::SceneInfo* s = scenes::find(what);
    int w = s->width, h = s->height;
    if (!size.empty()) std::tie(w, h) = parseSize(size, "--size");
    return scenes::build(what, w, h);
  }
  if (what.ends_with(".tframe")) return readFrame(what);
  return scenes::build(what, 1, 1);  // throws "unknown scene ... (known: ...)"
}

struct CrossArgs {
  std::string frame, size, report, backends = "cpu,gl", mutant;
  int threads = 0;
  bool strict = false, noBisect = false;
  ResourceLimits limits;
  gl::GlOptions gl;  // --gl-driver, --gl-version, --egl-platform
  std::string expectations;  // "" = the repo's tests/expectations/gl-deviations.json when it exists
  bool noExpectations = false, stability = false;
};

constexpr const char* kDefaultExpectations = "tests/expectations/gl-deviations.json";

void runCrosscheck(const CrossArgs& a) {
  if (a.backends != "cpu,cpu" && a.backends != "cpu,gl")
    throw Error("--backends '" + a.backends + "': expected cpu,gl (oracle vs GL) or cpu,cpu (oracle self-check)");
  if (a.stability && a.backends != "cpu,gl") throw Error("--stability re-renders the GL side: it needs --backends cpu,gl");
  if (!a.report.empty()) prepareOutputDirectory(a.report, "--report");
  const CommandList list = loadFrame(a.frame, a.size);
  verify::CrosscheckOptions o;
  o.threads = a.threads;
  o.bisect = !a.noBisect;
  o.limits = a.limits;
  std::unique_ptr<gl::GlBackend> glb;
  if (a.backends == "cpu,cpu") {
    o.selfCheck = true;
  } else {
    gl::GlOptions go = a.gl;
    go.strict = a.strict;
    if (a.threads > 0) go.lpThreads = a.threads;
    go.limits = a.limits;
    if (!a.mutant.empty() && !(go.mutation = gl::findMutation(a.mutant)))
      throw Error("--mutant '" + a.mutant + "': no such mutant (`tessera mutants --list` names them)");
    glb = gl::GlBackend::create(go);
  }
  std::optional<verify::ExpectationSet> expectations;
  if (glb && !a.noExpectations) {
    const std::string path = a.expectations.empty() ? repoPath(kDefaultExpectations) : a.expectations;
    if (!a.expectations.empty() || std::filesystem::exists(path)) expectations = verify::loadExpectations(path);
  }
  if (expectations) o.expectations = &*expectations;
  verify::CrosscheckResult r = verify::crosscheck(list, a.frame, o, glb.get());
  if (a.stability && glb) {
    std::vector<size_t> pixels;
    for (const verify::ImageVerdict& v : r.images) pixels.push_back(v.judgement.pixels);
    r.json["stability"] = runStability(a.frame, a.size, list, pixels, a.limits, a.gl);
    if (!a.report.empty())
      writeTextFile(a.report + "/stability.html", verify::stabilityHtml(r.json["stability"], a.frame));
  }
  if (!a.report.empty()) verify::writeCrosscheckReport(r, a.report);
  std::printf("%s\n", r.json.dump(2).c_str());
  if (!r.passed) throw CLI::RuntimeError(1);
}

struct BenchArgs {
  std::string scene, size;
  int threads = 1, repeat = 5;
  ResourceLimits limits;
  gl::GlOptions gl;  // --gl-driver, --gl-version, --egl-platform
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

void runBench(const BenchArgs& a) {
  const CommandList list = loadFrame(a.scene, a.size);
  // Both sides get the same explicit count; 0 means every core, for both.
  const int threads = a.threads > 0 ? a.threads : int(tbb::info::default_concurrency());
  gl::GlOptions go = a.gl;
  go.lpThreads = threads;
  go.limits = a.limits;
  auto glb = gl::GlBackend::create(go);
  std::vector<double> oracle, llvmpipe, oracleFrame, llvmpipeFrame;
  // One warm-up run each (GL compiles its shaders on first use), then `repeat` timed runs. Each side
  // keeps its backend across the runs, as a renderer of a frame sequence would: a new CpuBackend per
  // run paid for its worker arena and its first-touch pages inside execute(), which made the 2-thread
  // oracle times bimodal (11 or 26 ms for city_block at 320x240). The order alternates by round, so
  // neither side always runs on the caches and clocks the other left behind.
  CpuBackend b(RenderOptions{threads, false, a.limits});
  for (int i = 0; i <= a.repeat; ++i) {
    if (i % 2 == 1) glb->execute(list, a.scene);
    const auto t0 = std::chrono::steady_clock::now();
    b.execute(list, a.scene);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (i % 2 == 0) glb->execute(list, a.scene);
    if (i == 0) continue;
    oracle.push_back(ms);
    llvmpipe.push_back(glb->lastExecuteMs());
    // The frame alone, without validation and resource commands (docs/bench.md).
    oracleFrame.push_back(b.stageTimes().frameMs);
    llvmpipeFrame.push_back(glb->lastFrameTimes().frameMs);
  }
  const double mo = median(oracle), ml = median(llvmpipe), fo = median(oracleFrame), fl = median(llvmpipeFrame);
  const nlohmann::json j = {{"scene", a.scene},
                            {"threads", threads},
                            {"repeat", a.repeat},
                            {"oracle_ms", mo},
                            {"llvmpipe_ms", ml},
                            {"ratio", mo > 0 ? ml / mo : 0.0},
                            {"ratio_meaning", "llvmpipe time / oracle time: above 1 means the oracle is faster"},
                            {"oracle_frame_ms", fo},
                            {"llvmpipe_frame_ms", fl},
                            {"frame_ratio", fo > 0 ? fl / fo : 0.0},
                            {"frame_meaning",
                             "the frame alone, without validation and resource commands (docs/bench.md); "
                             "oracle_ms and llvmpipe_ms time the whole execute()"},
                            {"oracle_runs_ms", oracle},
                            {"llvmpipe_runs_ms", llvmpipe},
                            {"gl_info", glb->info().toJson()}};
  std::printf("%s\n", j.dump(2).c_str());
}

}  // namespace

void addVerifyCommands(CLI::App& app) {
  addGlDumpCommand(app);  // hidden: the child of `crosscheck --stability`
  auto ca = std::make_shared<CrossArgs>();
  auto* cross = app.add_subcommand(
      "crosscheck",
      "Render a frame on the oracle (with per-pixel provenance) and on OpenGL (headless EGL; Mesa llvmpipe here),\n"
      "judge every GL pixel against the interval the GL spec allows, check GL issued exactly the counted calls,\n"
      "and bisect to the first diverging draw on failure. Prints JSON; exit 1 if any pixel is unexplained.");
  cross->add_option("frame", ca->frame, "Scene name or .tframe file")->required();
  cross->add_option("--backends", ca->backends, "cpu,gl (default) or cpu,cpu (oracle self-check)")->capture_default_str();
  cross->add_option("--report", ca->report, "Write report.json, PNGs and index.html (with a pixel inspector) here");
  addSizeOption(cross, ca->size, "Target size WxH for scenes");
  addThreadsOption(cross, ca->threads, "Oracle threads, and LP_NUM_THREADS for llvmpipe when > 0");
  addMemoryBudgetOption(cross, ca->limits);
  cross->add_flag("--strict", ca->strict, "Switch off llvmpipe fast paths that do not change GL semantics");
  cross->add_flag("--no-bisect", ca->noBisect, "Do not bisect to the first diverging draw on failure");
  addGlBackendOptions(cross, ca->gl);
  cross->add_option("--expectations", ca->expectations,
                    std::string("Known GL deviations (docs/expectations.md); default: the repo's ") + kDefaultExpectations);
  cross->add_flag("--no-expectations", ca->noExpectations, "Judge without the expectations file");
  cross->add_flag("--stability", ca->stability,
                  "Also render the GL side in child processes under other conditions (repeat, LP_NUM_THREADS 1 and N,\n"
                  "one CPU, strict) and report any change as GL nondeterministic / fast-path dependent (JSON \"stability\")");
  cross->add_option("--mutant", ca->mutant, "Run GL with this deliberate fault of `tessera mutants` (to see why it is killed)");
  cross->callback([ca] { runCrosscheck(*ca); });

  auto va = std::make_shared<CrossArgs>();
  auto* vis = app.add_subcommand(
      "visibility",
      "Ray-cast every pixel centre with Embree against the frame's post-transform triangles and compare the\n"
      "object / primitive ids with the oracle's R32UI id targets. Prints JSON; exit 1 on any unexplained mismatch.");
  vis->add_option("frame", va->frame, "Scene name or .tframe file (a frame not drawn with object_id is rewritten to it: id = draw index)")
      ->required();
  addSizeOption(vis, va->size, "Target size WxH for scenes");
  addThreadsOption(vis, va->threads, "Threads of the ray casts and the oracle render");
  addMemoryBudgetOption(vis, va->limits);
  vis->callback([va] {
    verify::VisibilityOptions o;
    o.threads = va->threads;
    o.limits = va->limits;
    const CommandList list = loadFrame(va->frame, va->size);
    validateOrThrow(list, va->frame, o.limits);  // names the file (castVisibility says "visibility")
    const verify::VisibilityResult r = verify::castVisibility(list, o);
    std::printf("%s\n", verify::visibilityToJson(r, true).dump(2).c_str());
    if (r.unexplained) throw CLI::RuntimeError(1);
  });

  struct CompareArgs {
    std::string a, b, report;
    verify::CompareOptions o;
    double warn = -1;
  };
  auto cmp = std::make_shared<CompareArgs>();
  auto* compare = app.add_subcommand(
      "compare",
      "Compare two images (PNG, EXR, ...) like idiff: exit 0 pass, 1 warn, 2 fail, 3 size/format mismatch, 4 I/O error.\n"
      "Thresholds are in LSBs for 8-bit images and absolute values for float images; NaN equals only NaN.");
  compare->add_option("a", cmp->a, "Expected image")->required();
  compare->add_option("b", cmp->b, "Actual image")->required();
  const RealRange percent{0.0, 100.0, false, false};
  addRealOption(compare, "--fail", cmp->o.failThreshold, "Per-channel |Δ| above this fails (default 0: exact)",
                kNonNegative);
  addRealOption(compare, "--failpercent", cmp->o.failPercent, "Allow this % of pixels above --fail", percent);
  addRealOption(compare, "--warn", cmp->warn, "Per-channel |Δ| above this warns (default: --fail)", kNonNegative);
  addRealOption(compare, "--warnpercent", cmp->o.warnPercent, "Allow this % of pixels above --warn", percent);
  compare->add_option("--report", cmp->report, "Write report.json, heatmap.png, histogram.png and index.html here");
  compare->callback([cmp] {
    if (cmp->warn >= 0) cmp->o.warnThreshold = cmp->warn;
    if (!cmp->report.empty()) prepareOutputDirectory(cmp->report, "--report");
    const verify::CompareResult r = verify::compareImages(cmp->a, cmp->b, cmp->o);
    if (!cmp->report.empty()) verify::writeCompareReport(r, cmp->report);
    std::printf("%s\n", verify::compareToJson(r).dump(2).c_str());
    if (r.exitCode()) throw CLI::RuntimeError(r.exitCode());
  });

  auto ba = std::make_shared<BenchArgs>();
  auto* bench = app.add_subcommand("bench", "Benchmarks");
  bench->require_subcommand(1);
  auto* bc = bench->add_subcommand(
      "crosscheck", "Time the same frame on the oracle and on llvmpipe with the same thread count; prints JSON with "
                    "ratio = llvmpipe / oracle (above 1: the oracle is faster)");
  bc->add_option("scene", ba->scene, "Scene name or .tframe file")->required();
  addThreadsOption(bc, ba->threads, "Threads for both (oracle workers, LP_NUM_THREADS; default 1)");
  addSizeOption(bc, ba->size, "Target size WxH");
  addMemoryBudgetOption(bc, ba->limits);
  bc->add_option("--repeat", ba->repeat, "Timed runs (median reported)")->check(CLI::Range(1, 1000));
  addGlBackendOptions(bc, ba->gl);
  bc->callback([ba] { runBench(*ba); });
  addBenchSweepCommands(bench);
}

}  // namespace tessera::cli
