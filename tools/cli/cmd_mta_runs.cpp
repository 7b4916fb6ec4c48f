// `tessera mta runs`: the three runs of the thesis (§4.7.2) on one camera path: original textures, one
// dummy texture, the atlas tree; state changes, draw calls, frame time, and the atlas tree's image error
// against original textures (PSNR), with runs.json and runs.png (docs/mta-render.md).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "base/image_diff.h"
#include "tools/cli/commands.h"
#include "tools/cli/frame_job.h"
#include "tools/cli/mta_path_run.h"
#include "tools/cli/output_directory.h"

namespace tessera::cli {

namespace fs = std::filesystem;

namespace {

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

}  // namespace

nlohmann::json runMtaRuns(const PathRunArgs& a, int tolerance) {
  prepareOutputDirectory(a.out, "-o");
  mta::PagingFile file(a.input);
  const mta::CameraPath path = loadPath(a, file.meta());
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

void addMtaRunsCommand(CLI::App* mtaCmd) {
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
}

}  // namespace tessera::cli
