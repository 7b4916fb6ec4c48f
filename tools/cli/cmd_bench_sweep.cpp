// `tessera bench sweep [--quick] -o DIR`: the oracle and llvmpipe (default and strict) on the sweep's
// workloads at each thread count; writes sweep.json, sweep.png and index.html (docs/bench.md).
#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>
#include <tuple>

#include "base/atomic_file.h"
#include "base/error.h"
#include "raster/image_io.h"
#include "raster/simd_targets.h"
#include "tools/cli/bench_sweep.h"
#include "tools/cli/gl_options.h"
#include "tools/cli/output_directory.h"
#include "tools/cli/sweep_plot.h"
#include "verify/html_escape.h"

namespace tessera::cli {

namespace fs = std::filesystem;

namespace {

struct SweepArgs {
  std::string out;
  bool quick = false, noStrict = false;
  int repeat = 0;            // 0: 5, or 3 with --quick
  std::vector<int> threads;  // empty: 1 and 2, or 1 with --quick
  gl::GlOptions gl;          // --gl-driver, --gl-version, --egl-platform
};

// Linear interpolation between order statistics (p in [0, 1]).
double quantile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double at = p * double(v.size() - 1);
  const size_t i = size_t(at);
  if (i + 1 >= v.size()) return v.back();
  return v[i] + (v[i + 1] - v[i]) * (at - double(i));
}

// Runs `tessera bench sweep-worker` for one thread count and llvmpipe mode in its own process, and
// returns its JSON.
nlohmann::json runChild(const SweepArgs& a, const fs::path& tmp, int threads, bool strict, int repeat) {
  const fs::path out = tmp / fmt::format("worker_t{}_{}.json", threads, strict ? "strict" : "default");
  std::vector<std::string> args = {
      "tessera", "bench",     "sweep-worker", "--threads", std::to_string(threads), "--repeat", std::to_string(repeat),
      "--out",   out.string()};
  if (strict)
    args.push_back("--strict");
  else
    args.push_back("--stages");  // the stage times come from the default child's oracle only
  if (a.quick) args.push_back("--quick");
  if (!a.gl.driver.empty()) args.insert(args.end(), {"--gl-driver", a.gl.driver});
  if (a.gl.glVersion != 0) args.insert(args.end(), {"--gl-version", std::to_string(a.gl.glVersion)});
  if (!a.gl.eglPlatform.empty()) args.insert(args.end(), {"--egl-platform", a.gl.eglPlatform});
  std::vector<char*> argv;
  for (std::string& s : args) argv.push_back(s.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) throw Error("bench sweep: fork failed");
  if (pid == 0) {
    execv("/proc/self/exe", argv.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw Error("bench sweep: waitpid failed");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !fs::exists(out))
    throw Error(fmt::format("bench sweep: the worker for {} thread(s), {} failed (status {})", threads,
                            strict ? "llvmpipe strict" : "llvmpipe", WIFEXITED(status) ? WEXITSTATUS(status) : -1));
  std::ifstream in(out);
  return nlohmann::json::parse(in);
}

struct Stat {
  double median = 0, p10 = 0, p90 = 0, cpu = 0;
};
Stat stat(const nlohmann::json& ms, const nlohmann::json& cpu) {
  const auto v = ms.get<std::vector<double>>(), c = cpu.get<std::vector<double>>();
  return {quantile(v, 0.5), quantile(v, 0.1), quantile(v, 0.9), quantile(c, 0.5)};
}

// Least squares ms = a + b x over the points; {b in ns per unit of x, a in ms}. Fewer than two distinct
// x: no fit.
std::optional<std::pair<double, double>> fit(const std::vector<double>& x, const std::vector<double>& y) {
  const size_t n = x.size();
  if (n < 2) return std::nullopt;
  double mx = 0, my = 0;
  for (size_t i = 0; i < n; ++i) mx += x[i], my += y[i];
  mx /= double(n), my /= double(n);
  double sxx = 0, sxy = 0;
  for (size_t i = 0; i < n; ++i) sxx += (x[i] - mx) * (x[i] - mx), sxy += (x[i] - mx) * (y[i] - my);
  if (!(sxx > 0)) return std::nullopt;
  const double b = sxy / sxx;
  return std::make_pair(b * 1e6, my - b * mx);
}

std::string fmtMs(double v) {
  return v >= 100 ? fmt::format("{:.0f}", v) : v >= 10 ? fmt::format("{:.1f}", v) : fmt::format("{:.2f}", v);
}

const char* const kRenderers[] = {"oracle", "llvmpipe", "llvmpipe_strict"};

void runSweep(const SweepArgs& a) {
  prepareOutputDirectory(a.out, "-o");
  if (!fs::is_empty(a.out))
    throw Error(a.out +
                ": the directory is not empty (-o names the output directory; bench sweep writes into an "
                "empty or new one)");
  const std::vector<SweepPoint> plan = sweepPlan(a.quick);
  const int repeat = a.repeat > 0 ? a.repeat : (a.quick ? 3 : 5);
  const std::vector<int> threads =
      !a.threads.empty() ? a.threads : (a.quick ? std::vector<int>{1} : std::vector<int>{1, 2});
  std::string tmpl = (fs::temp_directory_path() / "tessera-sweep-XXXXXX").string();
  if (!mkdtemp(tmpl.data())) throw Error("bench sweep: cannot create a temporary directory under " + tmpl);
  const fs::path tmp = tmpl;
  std::fprintf(stderr, "bench sweep: %zu points x %zu thread counts x %s, %d timed runs each (+1 warm-up)\n",
               plan.size(), threads.size(), a.noStrict ? "oracle + llvmpipe" : "oracle + llvmpipe + llvmpipe strict",
               repeat);
  // workers[t][strict]
  std::map<std::pair<int, bool>, nlohmann::json> workers;
  try {
    for (int t : threads)
      for (bool strict : {false, true}) {
        if (strict && a.noStrict) continue;
        workers[{t, strict}] = runChild(a, tmp, t, strict, repeat);
      }
  } catch (...) {
    std::error_code ec;
    fs::remove_all(tmp, ec);
    throw;
  }
  std::error_code ec;
  fs::remove_all(tmp, ec);

  nlohmann::json points = nlohmann::json::array(), stages = nlohmann::json::array();
  // Per (plan index, threads, renderer): the median, for the fits and the plot.
  std::map<std::tuple<size_t, int, int>, double> med;
  std::map<std::tuple<size_t, int, int>, double> ratioOf;
  for (size_t i = 0; i < plan.size(); ++i) {
    const SweepPoint& p = plan[i];
    for (int t : threads) {
      const nlohmann::json& dp = workers.at({t, false})["points"][i];
      const auto base = [&](const char* renderer) {
        nlohmann::json j = {{"workload", p.workload},
                            {"variant", p.variant},
                            {"width", p.width},
                            {"height", p.height},
                            {"pixels", int64_t(p.width) * p.height}};
        if (p.workload == "tiny_tris") j["triangles"] = p.triangles;
        j["threads"] = t;
        j["renderer"] = renderer;
        return j;
      };
      const Stat o = stat(dp["oracle_ms"], dp["oracle_cpu_ms"]);
      for (int r = 0; r < 3; ++r) {
        if (r == 2 && a.noStrict) continue;
        const nlohmann::json& src = r == 2 ? workers.at({t, true})["points"][i] : dp;
        nlohmann::json j = base(kRenderers[r]);
        const Stat s = r == 0 ? o : stat(src["gl_ms"], src["gl_cpu_ms"]);
        j["median_ms"] = s.median, j["p10_ms"] = s.p10, j["p90_ms"] = s.p90, j["cpu_ms"] = s.cpu;
        j["runs_ms"] = r == 0 ? src["oracle_ms"] : src["gl_ms"];
        if (r > 0) {
          // The oracle's runs interleaved with these GL runs in the same process (for strict, its own child).
          const Stat paired = stat(src["oracle_ms"], src["oracle_cpu_ms"]);
          j["oracle_paired_median_ms"] = paired.median;
          j["ratio"] = paired.median > 0 ? s.median / paired.median : 0.0;
          ratioOf[{i, t, r}] = j["ratio"].get<double>();
        }
        med[{i, t, r}] = s.median;
        points.push_back(std::move(j));
      }
      if (dp.contains("stages")) {
        nlohmann::json s = base("oracle");
        s.erase("renderer");
        s.update(dp["stages"]);
        stages.push_back(std::move(s));
      }
    }
  }

  // Fits and plot panels per (workload, variant) in plan order, then threads, then renderer.
  std::vector<std::pair<std::string, std::string>> groups;
  for (const SweepPoint& p : plan)
    if (std::find(groups.begin(), groups.end(), std::make_pair(p.workload, p.variant)) == groups.end())
      groups.emplace_back(p.workload, p.variant);
  nlohmann::json fits = nlohmann::json::array();
  std::vector<PlotPanel> panels;
  const verify::Rgba colors[3] = {{30, 90, 200, 255}, {225, 110, 20, 255}, {40, 150, 60, 255}};
  for (const auto& [wl, var] : groups) {
    const bool tris = wl == "tiny_tris";
    for (int t : threads) {
      PlotPanel panel;
      panel.title = fmt::format("{} {}, {} thread{}", wl, var, t, t == 1 ? "" : "s");
      panel.xLabel = tris ? "triangles (1280x720)" : fmt::format("pixels ({} layers)", 4);
      for (int r = 0; r < 3; ++r) {
        if (r == 2 && a.noStrict) continue;
        PlotLine line{kRenderers[r], colors[r], {}, {}, {}};
        for (size_t i = 0; i < plan.size(); ++i) {
          if (plan[i].workload != wl || plan[i].variant != var) continue;
          line.x.push_back(plan[i].x());
          line.ms.push_back(med.at({i, t, r}));
          line.notes.push_back(r == 0 ? "" : fmt::format("{:.2f}", ratioOf.at({i, t, r})));
        }
        const auto f = fit(line.x, line.ms);
        nlohmann::json fj = {
            {"workload", wl}, {"variant", var}, {"threads", t}, {"renderer", kRenderers[r]}, {"points", line.x.size()}};
        fj[tris ? "ns_per_triangle" : "ns_per_pixel"] = f ? nlohmann::json(f->first) : nlohmann::json(nullptr);
        fj["intercept_ms"] = f ? nlohmann::json(f->second) : nlohmann::json(nullptr);
        fits.push_back(std::move(fj));
        panel.lines.push_back(std::move(line));
      }
      panels.push_back(std::move(panel));
    }
  }

  // Thread scaling: the 1-thread median over the n-thread median, per point and renderer (the goal
  // is >= 1.85 at 2 threads).
  nlohmann::json scaling = nlohmann::json::array();
  if (std::find(threads.begin(), threads.end(), 1) != threads.end())
    for (size_t i = 0; i < plan.size(); ++i)
      for (int t : threads) {
        if (t == 1) continue;
        for (int r = 0; r < 3; ++r) {
          if (r == 2 && a.noStrict) continue;
          const double one = med.at({i, 1, r}), n = med.at({i, t, r});
          nlohmann::json sj = {{"workload", plan[i].workload},
                               {"variant", plan[i].variant},
                               {"width", plan[i].width},
                               {"height", plan[i].height}};
          if (plan[i].workload == "tiny_tris") sj["triangles"] = plan[i].triangles;
          sj["renderer"] = kRenderers[r];
          sj["threads"] = t;
          sj["speedup_vs_1_thread"] = n > 0 ? one / n : 0.0;
          scaling.push_back(std::move(sj));
        }
      }

  const nlohmann::json& anyWorker = workers.begin()->second;
  nlohmann::json j = {
      {"quick", a.quick},
      {"repeat", repeat},
      {"threads", threads},
      {"hardware_threads", std::thread::hardware_concurrency()},
      // The workers inherit the default: the best compiled SIMD target this CPU runs (raster/simd_targets.h).
      {"simd_target", simd::activeTarget()},
      {"timing",
       "frame only: the draws and clears through the last tile (oracle, StageTimes::frameMs) or through glFinish "
       "(GL, GlBackend::lastFrameTimes); validation and resource commands excluded; median, p10, p90 of the timed "
       "runs after one warm-up; the renderers interleaved run by run in one process per thread count and llvmpipe "
       "mode; cpu_ms = getrusage user + system of the process over the frame (median)"},
      {"ratio_meaning",
       "llvmpipe median / the median of the oracle runs interleaved with it: above 1, the oracle is faster"},
      {"fit_meaning",
       "least squares ms = intercept_ms + slope * x over the points of a line; x = pixels of the target "
       "(fill_layers draws 4 full-screen layers) or triangles"},
      {"gl_info", anyWorker["gl_info"]},
      {"points", points},
      {"fits", fits},
      {"stages", stages},
      {"scaling", scaling}};
  writeFileAtomically(a.out + "/sweep.json", j.dump(2));
  const verify::RgbaCanvas canvas = drawSweepPlot(panels);
  writePngRGBA8(a.out + "/sweep.png", canvas.width(), canvas.height(), canvas.data());

  // index.html: the table of points, the fits, the stage times and the plot.
  using verify::escapeHtml;
  std::string h =
      "<!doctype html><meta charset=utf-8><title>tessera bench sweep</title>\n<style>body{font-family:sans-serif}"
      "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}"
      "th{background:#eee}</style>\n<h1>tessera bench sweep</h1>\n";
  h += fmt::format(
      "<p>{} timed runs per point after one warm-up; times in ms (median [p10, p90]); cpu = process CPU "
      "time over the frame (median); ratio = llvmpipe / oracle (above 1: the oracle is faster). {} "
      "hardware threads. See docs/bench.md for what is timed.</p>\n",
      repeat, std::thread::hardware_concurrency());
  h += "<table><tr><th>workload</th><th>variant</th><th>size</th><th>triangles</th><th>threads</th><th>renderer</th>"
       "<th>median</th><th>p10</th><th>p90</th><th>cpu</th><th>ratio</th></tr>\n";
  for (const nlohmann::json& p : points)
    h += fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{}x{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>"
        "<td>{}</td><td>{}</td><td>{}</td></tr>\n",
        escapeHtml(p["workload"].get<std::string>()), escapeHtml(p["variant"].get<std::string>()),
        p["width"].get<int>(), p["height"].get<int>(),
        p.contains("triangles") ? std::to_string(p["triangles"].get<int>()) : "", p["threads"].get<int>(),
        escapeHtml(p["renderer"].get<std::string>()), fmtMs(p["median_ms"].get<double>()),
        fmtMs(p["p10_ms"].get<double>()), fmtMs(p["p90_ms"].get<double>()), fmtMs(p["cpu_ms"].get<double>()),
        p.contains("ratio") ? fmt::format("{:.2f}", p["ratio"].get<double>()) : "");
  h += "</table>\n<h2>Fits</h2>\n<table><tr><th>workload</th><th>variant</th><th>threads</th><th>renderer</th>"
       "<th>ns per pixel / triangle</th><th>intercept ms</th></tr>\n";
  for (const nlohmann::json& f : fits) {
    const nlohmann::json& s = f.contains("ns_per_pixel") ? f["ns_per_pixel"] : f["ns_per_triangle"];
    h += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                     escapeHtml(f["workload"].get<std::string>()), escapeHtml(f["variant"].get<std::string>()),
                     f["threads"].get<int>(), escapeHtml(f["renderer"].get<std::string>()),
                     s.is_null() ? "-" : fmt::format("{:.2f}", s.get<double>()),
                     f["intercept_ms"].is_null() ? "-" : fmt::format("{:.2f}", f["intercept_ms"].get<double>()));
  }
  h += "</table>\n<h2>Oracle stage times</h2>\n<p>CPU ms summed over worker threads, from a separate run with "
       "RenderOptions::stageTimes (raster/stage_times.h); frame = that run's wall time.</p>\n<table><tr><th>workload"
       "</th><th>variant</th><th>size</th><th>triangles</th><th>threads</th><th>frame</th><th>vertex</th><th>clip</th>"
       "<th>setup</th><th>bin</th><th>rast</th><th>shade</th><th>sample</th><th>fragops</th></tr>\n";
  for (const nlohmann::json& s : stages) {
    h += fmt::format("<tr><td>{}</td><td>{}</td><td>{}x{}</td><td>{}</td><td>{}</td>",
                     escapeHtml(s["workload"].get<std::string>()), escapeHtml(s["variant"].get<std::string>()),
                     s["width"].get<int>(), s["height"].get<int>(),
                     s.contains("triangles") ? std::to_string(s["triangles"].get<int>()) : "", s["threads"].get<int>());
    for (const char* k :
         {"frame_ms", "vertex_ms", "clip_ms", "setup_ms", "bin_ms", "rast_ms", "shade_ms", "sample_ms", "fragops_ms"})
      h += "<td>" + fmtMs(s[k].get<double>()) + "</td>";
    h += "</tr>\n";
  }
  h += "</table>\n<h2>Plot</h2>\n<p>Log-log; the number at each llvmpipe point is its ratio.</p>\n"
       "<img src=\"sweep.png\" alt=\"frame ms against pixels and triangles\">\n";
  writeFileAtomically(a.out + "/index.html", h);
  std::printf("%s\n", (a.out + "/sweep.json").c_str());
}

}  // namespace

void addBenchSweepCommands(CLI::App* bench) {
  auto a = std::make_shared<SweepArgs>();
  auto* cmd = bench->add_subcommand(
      "sweep",
      "How frame time grows: the oracle and llvmpipe (default, and strict: fast paths off) on the same CommandLists\n"
      "at the same thread count (oracle workers = LP_NUM_THREADS, one child process per thread count and llvmpipe\n"
      "mode). Workloads: fill_layers (4 full-screen textured layers; variants trilinear, flat_color,\n"
      "trilinear_depth, trilinear_blend) at 320x240, 640x480, 1280x720, 1920x1080, and tiny_tris (triangles of\n"
      "1 px area at 1280x720) with 1k, 10k, 100k, 1M triangles. Timed: the frame only, after one warm-up run\n"
      "(uploads and program compilation excluded), the renderers interleaved run by run; wall time median\n"
      "with p10 / p90, and process CPU time. Writes DIR/sweep.json (every point, ratio = llvmpipe / oracle,\n"
      "least-squares ns per pixel and ns per triangle, oracle per-stage times from a separate run),\n"
      "DIR/sweep.png (log-log, ratio at each point) and DIR/index.html; progress on stderr. docs/bench.md.");
  cmd->add_option("-o,--out", a->out, "Output directory (created; must be empty)")->required();
  cmd->add_flag("--quick", a->quick,
                "A small subset (fill_layers trilinear at 320x240 and 640x480, tiny_tris 1k and 10k, 1 thread, "
                "3 runs): seconds, for tests");
  cmd->add_option("--repeat", a->repeat, "Timed runs per point and renderer (default 5; 3 with --quick)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--threads", a->threads, "Thread counts to sweep, e.g. --threads 1,2 (default 1,2; 1 with --quick)")
      ->delimiter(',')
      ->check(CLI::Range(1, kMaxThreads));
  cmd->add_flag("--no-strict", a->noStrict, "Skip llvmpipe with its fast paths off");
  addGlBackendOptions(cmd, a->gl);
  cmd->callback([a] { runSweep(*a); });
  addSweepWorkerCommand(bench);
}

}  // namespace tessera::cli
