// `tessera mta render`, `tessera mta runs` and `tessera texel`: the atlas tree at run time (thesis §4.4,
// §4.6, §4.7) over a camera path, with per-frame JSON, frame images and plots (docs/mta-render.md).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "model/model.h"
#include "mta/build.h"
#include "mta/scene.h"
#include "mta/texel_ratio.h"
#include "raster/image_io.h"
#include "base/image_diff.h"
#include "base/sha256.h"
#include "tools/cli/commands.h"
#include "tools/cli/frame_job.h"
#include "tools/cli/mta_path_run.h"

namespace tessera::cli {

namespace fs = std::filesystem;

namespace {

const verify::Rgba kBlue{40, 90, 200, 255}, kRed{210, 50, 40, 255}, kGreen{30, 150, 60, 255}, kGrey{110, 110, 110, 255},
    kOrange{230, 140, 20, 255}, kPurple{140, 60, 170, 255};

std::vector<double> column(const nlohmann::json& rows, const char* key) {
  std::vector<double> v;
  for (const auto& r : rows) v.push_back(r.contains(key) && !r[key].is_null() ? r[key].get<double>() : NAN);
  return v;
}

bool saveFrame(const PathRunArgs& a, size_t i, size_t n) { return a.saveEvery && (i % a.saveEvery == 0 || i + 1 == n); }

std::string frameName(const char* prefix, size_t i) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%04zu.png", prefix, i);
  return buf;
}

// ---- mta render ----

nlohmann::json runRenderImpl(const PathRunArgs& a) {
  mta::PagingFile file(a.input);
  const mta::CameraPath path = loadPath(a, file.meta());
  const mta::RendererOptions o = rendererOptions(a, mta::RenderMode::AtlasTree);
  fs::create_directories(a.out);
  mta::TreeRenderer renderer(file, o);
  nlohmann::json rows = nlohmann::json::array();
  Progress progress("mta render", path.frames.size(), a.quiet);
  for (size_t i = 0; i < path.frames.size(); ++i) {
    mta::FrameResult r = renderer.renderFrame(path.frames[i]);
    nlohmann::json j = mta::toJson(r, o.mode);
    j["image_sha256"] = sha256Hex(r.image);
    if (saveFrame(a, i, path.frames.size())) {
      const std::string name = frameName("frame", i);
      writeFramePng((fs::path(a.out) / name).string(), o.width, o.height, r.image);
      j["image"] = name;
    }
    rows.push_back(j);
    progress.tick(i + 1, std::to_string(r.counters.texture_state_changes) + " texture changes, " +
                             std::to_string(r.bytesResident >> 20) + " MiB resident");
  }
  const auto [bindMax, bindMean] = maxMean(column(rows, "texture_binds"));
  const auto [chgMax, chgMean] = maxMean(column(rows, "texture_state_changes"));
  const auto [drawMax, drawMean] = maxMean(column(rows, "draw_calls"));
  const auto [atlasMax, atlasMean] = maxMean(column(rows, "nodes_with_atlas"));
  const auto [origMax, origMean] = maxMean(column(rows, "nodes_with_original_textures"));
  const auto [timeMax, timeMean] = maxMean(column(rows, "frame_time_ms"));
  const auto [loadedMax, loadedMean] = maxMean(column(rows, "blocks_loaded"));
  uint64_t framesMissing = 0, loadedTotal = 0;
  for (const auto& r : rows) {
    framesMissing += r["needed_blocks_missing"].get<uint64_t>() > 0 ? 1 : 0;
    loadedTotal += r["blocks_loaded"].get<uint64_t>();
  }
  nlohmann::json summary = {
      {"frames", rows.size()},
      {"texture_binds_max", bindMax},
      {"texture_binds_mean", bindMean},
      {"texture_state_changes_max", chgMax},
      {"texture_state_changes_mean", chgMean},
      {"draw_calls_max", drawMax},
      {"draw_calls_mean", drawMean},
      {"nodes_with_atlas_max", atlasMax},
      {"nodes_with_atlas_mean", atlasMean},
      {"nodes_with_original_textures_max", origMax},
      {"nodes_with_original_textures_mean", origMean},
      {"peak_bytes_resident", renderer.residency()->peakBytesResident()},
      {"capacity_bytes", renderer.residency()->capacity()},
      {"blocks_loaded_total", loadedTotal},
      {"blocks_loaded_max_per_frame", loadedMax},
      {"frames_with_needed_blocks_missing", framesMissing},
      {"frame_time_ms_mean", timeMean},
      {"frame_time_ms_max", timeMax}};
  nlohmann::json doc = {{"options", optionsJson(a, o, path)}, {"summary", summary}, {"frames", rows}};
  writeTextFile((fs::path(a.out) / "frames.json").string(), doc.dump(1) + "\n");

  // Figures 31-32 of the thesis show one series over the path; here every series gets a panel.
  std::vector<verify::RgbaCanvas> panels;
  verify::LineChart c1{"Texture binds and draw calls per frame", "frame", "count",
                       {{"texture_state_changes", column(rows, "texture_state_changes"), kBlue, false, 2},
                        {"draw_calls", column(rows, "draw_calls"), kOrange, true, 1}}};
  panels.push_back(verify::drawLineChart(c1));
  verify::LineChart c2{"Nodes drawn", "frame", "nodes",
                       {{"with atlas", column(rows, "nodes_with_atlas"), kGreen, false, 2},
                        {"with original textures", column(rows, "nodes_with_original_textures"), kPurple, false, 1},
                        {"coarser than needed", column(rows, "nodes_coarser_than_needed"), kRed, true, 1}}};
  panels.push_back(verify::drawLineChart(c2));
  std::vector<double> mib = column(rows, "bytes_resident");
  for (double& v : mib) v /= 1048576.0;
  verify::LineChart c3{"Memory manager", "frame", "MiB resident",
                       {{"bytes resident (MiB)", mib, kBlue, false, 2}}};
  c3.hLines = {double(renderer.residency()->capacity()) / 1048576.0};
  c3.yMin = 0.0;
  c3.yMax = c3.hLines[0] * 1.1;
  panels.push_back(verify::drawLineChart(c3));
  verify::LineChart c4{"Blocks loaded per frame and oracle frame time", "frame", "",
                       {{"blocks loaded", column(rows, "blocks_loaded"), kGrey, false, 1},
                        {"frame time (ms)", column(rows, "frame_time_ms"), kRed, false, 1}}};
  panels.push_back(verify::drawLineChart(c4));
  writeChartPng((fs::path(a.out) / "plot.png").string(), verify::stackCharts(panels));
  return summary;
}

// ---- mta runs: the three runs of §4.7.2 ----

struct ImageError {
  double psnr = INFINITY;  // RGB
  double withinTolerance = 1.0;
};

// The atlas tree's frame `a` against the original textures' frame `b`, both RGBA8: PSNR over R, G and B
// (alpha is not compared) with peak 255, and the share of pixels whose RGB channels all differ by at
// most `tolerance` steps (base/image_diff.h).
ImageError imageError(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int tolerance) {
  ImageDiffRules rules;
  rules.peak = 255.0;
  rules.tolerance = double(tolerance);
  const ImageDiff d = diffPixels(a, b, DiffChannelType::UInt8, 4, rules, 3);
  ImageError e;
  e.psnr = d.psnr();
  e.withinTolerance = double(d.pixelsWithinTolerance) / double(d.pixels);
  return e;
}

nlohmann::json runRunsImpl(const PathRunArgs& a, int tolerance) {
  mta::PagingFile file(a.input);
  const mta::CameraPath path = loadPath(a, file.meta());
  fs::create_directories(a.out);
  const mta::RenderMode modes[3] = {mta::RenderMode::Original, mta::RenderMode::Dummy, mta::RenderMode::AtlasTree};
  std::vector<std::unique_ptr<mta::TreeRenderer>> r;
  for (mta::RenderMode m : modes) r.push_back(std::make_unique<mta::TreeRenderer>(file, rendererOptions(a, m)));
  const uint32_t w = r[0]->options().width, h = r[0]->options().height;
  nlohmann::json rows = nlohmann::json::array();
  Progress progress("mta runs", path.frames.size(), a.quiet);
  for (size_t i = 0; i < path.frames.size(); ++i) {
    nlohmann::json row = {{"frame", i}};
    mta::FrameResult res[3];
    for (int k = 0; k < 3; ++k) {
      res[k] = r[size_t(k)]->renderFrame(path.frames[i]);
      const std::string m = mta::renderModeName(modes[k]);
      row[m] = {{"texture_state_changes", res[k].counters.texture_state_changes},
                {"texture_binds", res[k].counters.texture_binds},
                {"draw_calls", res[k].counters.draw_calls},
                {"frame_time_ms", res[k].renderMs}};
    }
    const ImageError e = imageError(res[2].image, res[0].image, tolerance);
    row["atlas_tree"]["psnr_db"] = std::isfinite(e.psnr) ? nlohmann::json(e.psnr) : nlohmann::json(nullptr);
    row["atlas_tree"]["identical_to_original"] = !std::isfinite(e.psnr);
    row["atlas_tree"]["within_tolerance"] = e.withinTolerance;
    row["atlas_tree"]["needed_blocks_missing"] = res[2].residency.neededMissing;
    if (saveFrame(a, i, path.frames.size())) {
      writeFramePng((fs::path(a.out) / frameName("original", i)).string(), w, h, res[0].image);
      writeFramePng((fs::path(a.out) / frameName("atlas_tree", i)).string(), w, h, res[2].image);
    }
    rows.push_back(row);
    progress.tick(i + 1, "PSNR " + (std::isfinite(e.psnr) ? std::to_string(e.psnr) : std::string("inf")) + " dB");
  }
  auto series = [&](const char* mode, const char* key) {
    std::vector<double> v;
    for (const auto& row : rows) v.push_back(row[mode][key].is_null() ? NAN : row[mode][key].get<double>());
    return v;
  };
  nlohmann::json summary = {{"frames", rows.size()}, {"tolerance_lsb", tolerance}};
  for (mta::RenderMode m : modes) {
    const char* name = mta::renderModeName(m);
    const auto [cMax, cMean] = maxMean(series(name, "texture_state_changes"));
    const auto [dMax, dMean] = maxMean(series(name, "draw_calls"));
    const auto [tMax, tMean] = maxMean(series(name, "frame_time_ms"));
    summary[name] = {{"texture_state_changes_max", cMax}, {"texture_state_changes_mean", cMean}, {"draw_calls_max", dMax},
                     {"draw_calls_mean", dMean}, {"frame_time_ms_max", tMax}, {"frame_time_ms_mean", tMean}};
  }
  std::vector<double> psnr = series("atlas_tree", "psnr_db"), within = series("atlas_tree", "within_tolerance");
  double psnrMin = INFINITY, psnrSum = 0.0, withinMin = 1.0, withinSum = 0.0;
  size_t finite = 0;
  for (size_t i = 0; i < psnr.size(); ++i) {
    if (std::isfinite(psnr[i])) psnrMin = std::min(psnrMin, psnr[i]), psnrSum += psnr[i], ++finite;
    withinMin = std::min(withinMin, within[i]);
    withinSum += within[i];
  }
  summary["atlas_tree"]["psnr_db_min"] = std::isfinite(psnrMin) ? nlohmann::json(psnrMin) : nlohmann::json(nullptr);
  summary["atlas_tree"]["psnr_db_mean_finite"] = finite ? nlohmann::json(psnrSum / double(finite)) : nlohmann::json(nullptr);
  summary["atlas_tree"]["within_tolerance_min"] = withinMin;
  summary["atlas_tree"]["within_tolerance_mean"] = rows.empty() ? 0.0 : withinSum / double(rows.size());
  nlohmann::json doc = {{"options", optionsJson(a, r[2]->options(), path)}, {"summary", summary}, {"frames", rows}};
  writeTextFile((fs::path(a.out) / "runs.json").string(), doc.dump(1) + "\n");

  std::vector<verify::RgbaCanvas> panels;
  panels.push_back(verify::drawLineChart({"Oracle frame time (thesis Figure 32)", "frame", "ms",
                                          {{"original textures", series("original", "frame_time_ms"), kGrey, false, 1},
                                           {"one dummy texture", series("dummy", "frame_time_ms"), kOrange, true, 1},
                                           {"atlas tree", series("atlas_tree", "frame_time_ms"), kBlue, false, 2}}}));
  panels.push_back(verify::drawLineChart({"Texture state changes", "frame", "count",
                                          {{"original textures", series("original", "texture_state_changes"), kGrey, false, 1},
                                           {"one dummy texture", series("dummy", "texture_state_changes"), kOrange, true, 1},
                                           {"atlas tree", series("atlas_tree", "texture_state_changes"), kBlue, false, 2}}}));
  panels.push_back(verify::drawLineChart({"Draw calls", "frame", "count",
                                          {{"original textures", series("original", "draw_calls"), kGrey, false, 1},
                                           {"one dummy texture", series("dummy", "draw_calls"), kOrange, true, 1},
                                           {"atlas tree", series("atlas_tree", "draw_calls"), kBlue, false, 2}}}));
  panels.push_back(verify::drawLineChart({"Atlas tree vs original textures", "frame", "PSNR (dB)",
                                          {{"PSNR (dB)", psnr, kGreen, false, 2}}}));
  writeChartPng((fs::path(a.out) / "runs.png").string(), verify::stackCharts(panels));
  return summary;
}

// ---- texel ----

verify::RgbaCanvas histogramPng(const std::array<uint64_t, mta::kRatioBins>& hist, double tau) {
  const int barW = 56, chartH = 200, left = 20, top = 30;
  verify::RgbaCanvas c(left * 2 + barW * mta::kRatioBins, chartH + top + 50, {255, 255, 255, 255});
  c.text(left, 8, "pixels per texel at the level sampled", {0, 0, 0, 255}, 2);
  uint64_t mx = 1;
  for (uint64_t v : hist) mx = std::max(mx, v);
  for (int b = 0; b < mta::kRatioBins; ++b) {
    const int bh = int(double(chartH) * double(hist[size_t(b)]) / double(mx));
    const double lo = mta::ratioBinLower(b);
    const verify::Rgba col = lo >= tau * 0.999 ? kRed : (lo >= 1.0 ? kOrange : kGreen);
    c.fillRect(left + b * barW + 4, top + chartH - bh, barW - 8, bh, col);
    char label[32];
    std::snprintf(label, sizeof label, b == 0 ? "<0.25" : ">%.3g", lo);
    c.text(left + b * barW + 4, top + chartH + 6, label, {0, 0, 0, 255}, 2);
    std::snprintf(label, sizeof label, "%llu", (unsigned long long)hist[size_t(b)]);
    c.text(left + b * barW + 4, top + chartH + 24, label, {60, 60, 60, 255}, 1);
  }
  return c;
}

nlohmann::json runTexelImpl(PathRunArgs a) {
  fs::create_directories(a.out);
  std::string treePath = a.input;
  if (fs::path(a.input).extension() != ".mta") {
    // A model: build its tree with the default parameters first (kept, so later runs can reuse it).
    treePath = (fs::path(a.out) / "tree.mta").string();
    if (!a.quiet) std::fprintf(stderr, "texel: %s is a model; building its atlas tree into %s\n", a.input.c_str(), treePath.c_str());
    auto model = std::make_shared<const model::Model>(model::loadModel(a.input));
    mta::BuildParams p;
    p.dMin = a.buildDMin;
    p.progress = !a.quiet;
    mta::buildMta(mta::sceneFromModel(model), p, treePath);
  }
  mta::PagingFile file(treePath);
  const mta::CameraPath path = loadPath(a, file.meta());
  const mta::RendererOptions o = rendererOptions(a, mta::RenderMode::AtlasTree);
  const double tau = o.tau > 0.0 ? o.tau : file.meta().params.tau;
  mta::TreeRenderer renderer(file, o);
  nlohmann::json rows = nlohmann::json::array();
  std::array<uint64_t, mta::kRatioBins> hist{};
  uint64_t violations = 0, violationsAllResident = 0, framesAllResident = 0, atlasPixels = 0, abovePixels = 0;
  double maxRatio = 0.0;
  Progress progress("texel", path.frames.size(), a.quiet);
  for (size_t i = 0; i < path.frames.size(); ++i) {
    mta::FrameResult r = renderer.renderFrame(path.frames[i]);
    const std::vector<uint32_t> ids = renderer.triangleIds(path.frames[i], r.plan);
    const mta::TexelFrame t = mta::analyzeTexels(renderer, path.frames[i], r, ids, tau);
    nlohmann::json j = mta::toJson(t);
    j["frame"] = i;
    j["needed_blocks_missing"] = r.residency.neededMissing;
    j["nodes_coarser_than_needed"] = r.plan.coarserThanNeeded;
    rows.push_back(j);
    for (int b = 0; b < mta::kRatioBins; ++b) hist[size_t(b)] += t.histogram[size_t(b)];
    violations += t.magnificationViolations;
    atlasPixels += t.pixelsAtlas;
    abovePixels += t.atlasAboveTau;
    maxRatio = std::max(maxRatio, t.maxAtlasRatioBase);
    if (r.plan.coarserThanNeeded == 0) {
      ++framesAllResident;
      violationsAllResident += t.magnificationViolations;
    }
    if (saveFrame(a, i, path.frames.size())) {
      const std::vector<uint8_t> heat = mta::heatMap(t, tau);
      writePngRGBA8((fs::path(a.out) / frameName("texel", i)).string(), int(t.width), int(t.height), heat.data());
      writeFramePng((fs::path(a.out) / frameName("frame", i)).string(), t.width, t.height, r.image);
    }
    progress.tick(i + 1, std::to_string(t.magnificationViolations) + " violations");
  }
  nlohmann::json histJson = nlohmann::json::array();
  for (int b = 0; b < mta::kRatioBins; ++b) histJson.push_back({{"ratio_at_least", mta::ratioBinLower(b)}, {"pixels", hist[size_t(b)]}});
  nlohmann::json summary = {{"frames", rows.size()},
                            {"tau", tau},
                            {"magnification_violations", violations},
                            {"frames_with_every_needed_block_resident", framesAllResident},
                            {"magnification_violations_when_every_needed_block_resident", violationsAllResident},
                            {"atlas_pixels", atlasPixels},
                            {"atlas_pixels_above_tau_capped_by_original", abovePixels - violations},
                            {"max_atlas_ratio_level0", maxRatio},
                            {"histogram", histJson}};
  nlohmann::json doc = {{"options", optionsJson(a, o, path)}, {"summary", summary}, {"frames", rows}};
  writeTextFile((fs::path(a.out) / "texel.json").string(), doc.dump(1) + "\n");
  writeChartPng((fs::path(a.out) / "histogram.png").string(), histogramPng(hist, tau));
  return summary;
}

}  // namespace

nlohmann::json runMtaRender(const PathRunArgs& a) { return runRenderImpl(a); }
nlohmann::json runMtaRuns(const PathRunArgs& a, int tolerance) { return runRunsImpl(a, tolerance); }
nlohmann::json runTexel(const PathRunArgs& a) { return runTexelImpl(a); }

void addMtaRenderCommands(CLI::App& app, CLI::App* mtaCmd) {
  auto ra = std::make_shared<PathRunArgs>();
  auto* render = mtaCmd->add_subcommand(
      "render", "Render an atlas tree over a camera path with the memory manager (thesis 4.4, 4.6): PNG frames, per-frame JSON "
                "(texture_binds, draw_calls, bytes_resident, ...) and plot.png; prints a summary");
  render->add_option("tree", ra->input, "Paging file (.mta)")->required();
  addPathRunOptions(render, *ra, true);
  render->callback([ra] { std::printf("%s\n", runMtaRender(*ra).dump(2).c_str()); });

  auto rr = std::make_shared<PathRunArgs>();
  auto tolerance = std::make_shared<int>(16);
  auto* runs = mtaCmd->add_subcommand(
      "runs", "The thesis's three runs (4.7.2) on one path: original textures, one dummy texture, the atlas tree; texture state "
              "changes, draw calls and oracle frame time per run, and the atlas tree's image error against original textures");
  runs->add_option("tree", rr->input, "Paging file (.mta)")->required();
  addPathRunOptions(runs, *rr, true);
  runs->add_option("--tolerance", *tolerance, "Per-channel difference in 8-bit steps counted as 'within tolerance'")
      ->capture_default_str();
  runs->callback([rr, tolerance] {
    if (*tolerance < 0 || *tolerance > 255) throw Error("--tolerance must be 0..255");
    std::printf("%s\n", runMtaRuns(*rr, *tolerance).dump(2).c_str());
  });

  auto ta = std::make_shared<PathRunArgs>();
  auto* texel = app.add_subcommand(
      "texel", "Texel-per-pixel analysis over a camera path: per pixel, pixels per texel of the level sampled (analytic "
               "Jacobian), heat maps, a histogram, and magnification_violations (atlas used although it magnifies beyond tau; "
               "zero whenever every needed block is resident)");
  texel->add_option("input", ta->input, "Paging file (.mta), or a model (glTF, OBJ, ...) whose tree is built first into OUT/tree.mta")
      ->required();
  addPathRunOptions(texel, *ta, true);
  texel->add_option("--d-min", ta->buildDMin,
                    "With a model: d_min of its atlas tree build (default: scene diagonal / 72, which for a small scene "
                    "such as railway.glb means gigatexels; see docs/mta-build.md)");
  texel->callback([ta] { std::printf("%s\n", runTexel(*ta).dump(2).c_str()); });
}

}  // namespace tessera::cli
