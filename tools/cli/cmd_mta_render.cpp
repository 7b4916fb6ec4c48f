// `tessera mta render`: the atlas tree at run time (thesis §4.4, §4.6) over a camera path with the
// memory manager: per-frame JSON, frame images and plot.png (docs/mta-render.md).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "base/sha256.h"
#include "raster/serialize.h"
#include "tools/cli/commands.h"
#include "tools/cli/frame_job.h"
#include "tools/cli/mta_path_run.h"
#include "tools/cli/output_directory.h"

namespace tessera::cli {

namespace fs = std::filesystem;

nlohmann::json runMtaRender(const PathRunArgs& a) {
  prepareOutputDirectory(a.out, "-o");
  mta::PagingFile file(a.input);
  const mta::CameraPath path = loadPath(a, file.meta());
  const mta::RendererOptions o = rendererOptions(a, mta::RenderMode::AtlasTree);
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
      if (a.recordFrames) {
        const std::string tframe = fs::path(name).replace_extension(".tframe").string();
        writeFrame(renderer.lastList(), (fs::path(a.out) / tframe).string());
        j["tframe"] = tframe;
      }
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
  const auto [decodedMax, decodedMean] = maxMean(column(rows, "decoded_bytes_resident"));
  uint64_t framesMissing = 0, loadedTotal = 0, framesCapped = 0, framesOverCap = 0;
  double worstCapRatio = 1.0;
  for (const auto& r : rows) {
    framesMissing += r["needed_blocks_missing"].get<uint64_t>() > 0 ? 1 : 0;
    loadedTotal += r["blocks_loaded"].get<uint64_t>();
    if (r["nodes_coarsened_for_binds"].get<uint64_t>() > 0) {
      ++framesCapped;
      worstCapRatio = std::min(worstCapRatio, r["bind_cap_worst_ratio"].get<double>());
    }
    if (o.maxBinds != 0 && r["texture_binds"].get<uint64_t>() > o.maxBinds) ++framesOverCap;
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
      {"peak_decoded_bytes_resident", decodedMax},
      {"decoded_bytes_resident_mean", decodedMean},
      {"blocks_loaded_total", loadedTotal},
      {"blocks_loaded_max_per_frame", loadedMax},
      {"frames_with_needed_blocks_missing", framesMissing},
      {"frames_with_nodes_coarsened_for_binds", framesCapped},
      {"bind_cap_worst_ratio", framesCapped ? nlohmann::json(worstCapRatio) : nlohmann::json(nullptr)},
      {"frames_over_max_binds", framesOverCap},
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
                        {"coarser than needed", column(rows, "nodes_coarser_than_needed"), kRed, true, 1},
                        {"coarsened for --max-binds", column(rows, "nodes_coarsened_for_binds"), kOrange, true, 1}}};
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

void addMtaRenderCommand(CLI::App* mtaCmd) {
  auto ra = std::make_shared<PathRunArgs>();
  auto* render = mtaCmd->add_subcommand(
      "render", "Render an atlas tree over a camera path with the memory manager (thesis 4.4, 4.6): PNG frames, per-frame JSON "
                "(texture_binds, draw_calls, bytes_resident, ...) and plot.png; prints a summary");
  render->add_option("tree", ra->input, "Paging file (.mta)")->required();
  addPathRunOptions(render, *ra, true);
  render->add_flag("--record", ra->recordFrames,
                   "Also write every saved frame's command list as a .tframe next to its image, for `tessera crosscheck` "
                   "(it uploads every texture the frame binds, so a file holds the frame's atlases and originals)");
  render->callback([ra] { std::printf("%s\n", runMtaRender(*ra).dump(2).c_str()); });
}

}  // namespace tessera::cli
