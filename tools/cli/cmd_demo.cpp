// `tessera demo`: the main job on built-in defaults. Renders every built-in scene, writes its images
// and stats, re-renders it on one thread to show the bytes do not depend on the thread count, and
// writes report.json plus an index.html to look at.
#include <tbb/info.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "gl/gl_backend.h"
#include "tools/cli/commands.h"
#include "tools/cli/repo_paths.h"
#include "verify/crosscheck.h"
#include "verify/crosscheck_report.h"
#include "verify/html_escape.h"
#include "tools/cli/frame_job.h"
#include "tools/cli/gl_options.h"
#include "tools/cli/mta_demo.h"
#include "tools/cli/rtta_demo.h"
#include "tools/cli/suite_demo.h"
#include "tools/cli/tab_demo.h"
#include "tools/cli/options.h"
#include "tools/cli/output_directory.h"
#include "tools/scenes/scenes.h"

namespace tessera::cli {

namespace {

struct DemoArgs {
  std::string outDir = "out/demo";
  int threads = 0;
  bool checkThreads = true;
  bool gl = true;
  bool mta = true;
  bool tab = true;
  bool rtta = true;
  bool suite = true;
  std::string railway = "data/railway.glb";
  ResourceLimits limits;  // the scenes' frames (the atlas tree's frames are small and keep the default)
  gl::GlOptions glOptions;  // --gl-driver, --gl-version, --egl-platform
};

void runDemo(const DemoArgs& a) {
  namespace fs = std::filesystem;
  prepareOutputDirectory(a.outDir, "-o");
  const int threads = a.threads > 0 ? a.threads : int(tbb::info::default_concurrency());
  nlohmann::json report;
  report["threads"] = threads;
  nlohmann::json scenesJson = nlohmann::json::array();
  std::string rows;
  bool allAgree = true, allExplained = true;
  std::unique_ptr<gl::GlBackend> glb;
  if (a.gl) {
    try {
      gl::GlOptions go = a.glOptions;
      go.limits = a.limits;
      glb = gl::GlBackend::create(go);
      report["gl_info"] = glb->info().toJson();
    } catch (const Error& e) {
      std::fprintf(stderr, "demo: no GL cross-check: %s\n", e.what());
      report["gl_error"] = e.what();
    }
  }
  const auto& all = scenes::all();
  for (size_t i = 0; i < all.size(); ++i) {
    const scenes::SceneInfo& s = all[i];
    const std::string name(s.name);
    std::fprintf(stderr, "[%zu/%zu] %-16s ", i + 1, all.size(), name.c_str());
    const CommandList list = scenes::build(s.name, s.width, s.height);
    FrameJob job;
    job.name = name;
    job.threads = threads;
    job.imagePath = a.outDir + "/" + name + ".png";
    job.statsPath = a.outDir + "/" + name + ".json";
    job.recordPath = a.outDir + "/" + name + ".tframe";
    job.limits = a.limits;
    nlohmann::json stats = runFrame(list, job);
    nlohmann::json entry = {{"scene", name},
                            {"rule", std::string(s.rule)},
                            {"stats", name + ".json"},
                            {"frame", name + ".tframe"},
                            {"image_sha256", stats["image_sha256"]},
                            {"oracle_ms", stats["timing"]["oracle_ms"]},
                            {"draw_calls", stats["counters"]["draw_calls"]},
                            {"texture_state_changes", stats["counters"]["texture_state_changes"]},
                            {"triangles_binned", stats["pipeline"]["triangles_binned"]}};
    if (a.checkThreads && threads != 1) {
      FrameJob one;
      one.name = name;
      one.threads = 1;
      one.limits = a.limits;
      const nlohmann::json single = runFrame(list, one);
      bool agree = true;
      for (size_t k = 0; k < stats["images"].size(); ++k)
        agree = agree && single["images"][k]["image_sha256"] == stats["images"][k]["image_sha256"];
      entry["bit_identical_1_vs_n_threads"] = agree;
      entry["oracle_ms_1_thread"] = single["timing"]["oracle_ms"];
      allAgree = allAgree && agree;
    }
    std::string crossCell = "<td>-</td>";
    std::string glNote;
    if (glb) {
      verify::CrosscheckOptions co;
      co.threads = threads;
      co.limits = a.limits;
      // Known GL deviations (docs/expectations.md), as `tessera crosscheck` reads them by default.
      static const std::optional<verify::ExpectationSet> expectations = [] {
        const std::string path = repoPath("tests/expectations/gl-deviations.json");
        return std::filesystem::exists(path) ? std::optional(verify::loadExpectations(path)) : std::nullopt;
      }();
      if (expectations) co.expectations = &*expectations;
      const verify::CrosscheckResult cr = verify::crosscheck(list, name, co, glb.get());
      const std::string dir = a.outDir + "/crosscheck/" + name;
      verify::writeCrosscheckReport(cr, dir);
      const bool countersEqual = cr.json["counters"]["equal"].get<bool>();
      entry["crosscheck"] = {{"exact_match_percent", cr.json["exact_match_percent"]},
                             {"unexplained", cr.json["unexplained"]},
                             {"expected_deviation", cr.json["expected_deviation"]},
                             {"counters_equal", countersEqual},
                             {"report", "crosscheck/" + name + "/index.html"}};
      allExplained = allExplained && cr.passed;
      crossCell = fmt::format("<td><a href='crosscheck/{}/index.html'>{:.2f}% exact, {} unexplained</a>{}</td>", name,
                              cr.json["exact_match_percent"].get<double>(), cr.json["unexplained"].dump(),
                              countersEqual ? "" : " <b>counters differ</b>");
      glNote = fmt::format("  GL: {:.2f}% exact, {} unexplained", cr.json["exact_match_percent"].get<double>(),
                           cr.json["unexplained"].dump());
    }
    std::fprintf(stderr, "%8.1f ms  %s%s\n", stats["timing"]["oracle_ms"].get<double>(),
                 std::string(stats["image_sha256"]).substr(0, 16).c_str(), glNote.c_str());
    std::string imgs;
    for (const auto& img : stats["images"]) {
      const std::string file = fs::path(img["file"].get<std::string>()).filename().string();
      if (file.ends_with(".png"))
        imgs += fmt::format("<img src=\"{}\" title=\"{}\">", file, verify::escapeHtml(file));
      else
        imgs += fmt::format("<a href=\"{}\">{}</a> ", file, verify::escapeHtml(file));
    }
    rows += fmt::format(
        "<tr><td><b>{}</b><br><small>{}</small></td><td>{}</td><td>{}</td><td>{}</td><td>{:.1f}</td>"
        "<td><code>{}</code></td>{}</tr>\n",
        verify::escapeHtml(name), verify::escapeHtml(std::string(s.rule)), imgs, stats["counters"]["draw_calls"].dump(),
        stats["counters"]["texture_state_changes"].dump(), stats["timing"]["oracle_ms"].get<double>(),
        std::string(stats["image_sha256"]).substr(0, 16), crossCell);
    scenesJson.push_back(entry);
  }
  report["scenes"] = scenesJson;
  std::string mtaHtml;
  if (a.mta) {
    const MtaDemoResult m = runMtaDemo(a.outDir, a.railway, threads);
    report["atlas_tree"] = m.report;
    mtaHtml = m.html;
  }
  if (a.tab) {
    const TabDemoResult t = runTabDemo(a.outDir, a.railway, threads);
    report["texture_array_batching"] = t.report;
    mtaHtml += t.html;
  }
  if (a.rtta) {
    const RttaDemoResult r = runRttaDemo(a.outDir, a.railway, threads);
    report["render_to_texture_atlas"] = r.report;
    mtaHtml += r.html;
  }
  bool suitePassed = true;
  if (a.suite) {
    const SuiteDemoResult sd = runSuiteDemo(a.outDir, repoPath("suites/smoke.json"));
    report["suite"] = sd.report;
    mtaHtml += sd.html;
    suitePassed = sd.allPassOrExpected;
  }
  report["bit_identical_1_vs_n_threads"] = allAgree;
  if (glb) report["gl_every_pixel_explained"] = allExplained;
  writeTextFile(a.outDir + "/report.json", report.dump(2) + "\n");
  const std::string html = fmt::format(
      "<!doctype html><meta charset=utf-8><title>Tessera demo</title>"
      "<style>body{{font-family:sans-serif}}img{{image-rendering:pixelated;width:256px;margin:2px;"
      "border:1px solid #888}}img.plot{{width:440px}}td{{vertical-align:top;padding:4px}}</style>"
      "<h1>Tessera demo: built-in scenes on the oracle</h1><p>{} threads; bytes identical at 1 thread: {}</p>"
      "<table border=1 cellspacing=0><tr><th>scene</th><th>images</th><th>draw calls</th>"
      "<th>texture state changes</th><th>ms</th><th>image sha256</th><th>oracle vs GL (llvmpipe)</th></tr>\n{}</table>\n{}",
      threads, allAgree ? "yes" : "NO", rows, mtaHtml);
  writeTextFile(a.outDir + "/index.html", html);
  std::fprintf(stderr, "wrote %s/report.json and %s/index.html\n", a.outDir.c_str(), a.outDir.c_str());
  std::printf("%s\n", report.dump(2).c_str());
  if (glb && !allExplained) throw Error("demo: GL produced pixels the oracle cannot explain; see the crosscheck reports");
  if (!suitePassed) throw Error("demo: the smoke suite's CPU cases did not all pass; see " + a.outDir + "/suite/index.html");
  if (!allAgree) throw Error("demo: some scene rendered different bytes at 1 thread than at " + std::to_string(threads));
}

}  // namespace

void addDemoCommand(CLI::App& app) {
  auto a = std::make_shared<DemoArgs>();
  auto* demo = app.add_subcommand("demo", "Render every built-in scene with its counters; write images, "
                                          "stats, report.json and index.html");
  demo->add_option("-o,--output", a->outDir, "Output directory")->capture_default_str();
  addThreadsOption(demo, a->threads, "Worker threads");
  addMemoryBudgetOption(demo, a->limits);
  demo->add_flag("!--no-thread-check", a->checkThreads, "Skip the 1-thread re-render that checks bit-identity");
  demo->add_flag("!--no-gl", a->gl, "Skip the oracle-vs-OpenGL cross-check of every scene");
  addGlBackendOptions(demo, a->glOptions);
  demo->add_flag("!--no-mta", a->mta, "Skip the atlas tree on railway.glb (build, render over the thesis path, runs, texel)");
  demo->add_flag("!--no-tab", a->tab, "Skip texture-array batching on railway.glb (build, render baseline and batched, compare)");
  demo->add_flag("!--no-rtta", a->rtta, "Skip render-to-texture-atlas (STD / RTT / RTTA on the five-object scene and railway.glb)");
  demo->add_flag("!--no-suite", a->suite, "Skip the corpus run (the CPU cases of suites/smoke.json in child processes, 43 cases, under a minute)");
  demo->add_option("--railway", a->railway, "railway.glb, the real scene of the atlas tree and TAB demos (data/README.md)")->capture_default_str();
  demo->callback([a] {
    a->railway = repoPath(a->railway);  // found from the clone's root or beside the build folder
    runDemo(*a);
  });
}

}  // namespace tessera::cli
