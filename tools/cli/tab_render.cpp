#include "tools/cli/tab_render.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "base/error.h"
#include "base/sha256.h"
#include "batching/tab_file.h"
#include "batching/tab_record.h"
#include "batching/tab_stats.h"
#include "mta/camera.h"
#include "mta/camera_path.h"
#include "raster/counters.h"
#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "raster/lod_probe.h"
#include "raster/serialize.h"
#include "tools/cli/frame_job.h"
#include "tools/cli/mta_path_run.h"
#include "tools/cli/options.h"
#include "tools/cli/output_directory.h"
#include "verify/html_escape.h"
#include "verify/lod_compare.h"

namespace tessera::cli {

namespace fs = std::filesystem;
using batching::Variant;

namespace {

mta::CameraPath tabCameraPath(const TabRenderArgs& a, const batching::TabScene& s) {
  const auto names = mta::builtinPathNames();
  if (std::find(names.begin(), names.end(), a.path) != names.end()) {
    if (s.vertices.empty()) throw Error(a.input + ": the scene has no vertices to lay a camera path over");
    return mta::builtinPath(a.path, s.bounds, a.frames);
  }
  mta::CameraPath p = mta::readPathFile(a.path);
  if (a.frames && a.frames < p.frames.size()) p.frames.resize(a.frames);
  return p;
}

// Pixels that differ in red, the others dimmed, for looking rather than reading.
std::vector<uint8_t> diffImage(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  std::vector<uint8_t> d(a.size());
  for (size_t p = 0; p + 3 < a.size(); p += 4) {
    const bool same = std::memcmp(&a[p], &b[p], 4) == 0;
    for (int k = 0; k < 3; ++k) d[p + k] = same ? uint8_t(a[p + k] / 3) : (k == 0 ? 255 : 0);
    d[p + 3] = 255;
  }
  return d;
}

void writeTabIndex(const TabRenderArgs& a, const nlohmann::json& table1, const nlohmann::json& summary,
                   const nlohmann::json& rows) {
  std::string h =
      "<!doctype html><html><head><meta charset=\"utf-8\"><title>tessera tab render</title><style>"
      "body{font-family:sans-serif;margin:20px}table{border-collapse:collapse}td,th{border:1px solid #ccc;"
      "padding:3px 8px;text-align:right}img{max-width:420px;image-rendering:pixelated}</style></head><body>";
  h += "<h1>Texture-array batching: " + verify::escapeHtml(table1.value("source", a.input)) + "</h1>";
  h += "<p>Baseline (w/o TAB): one draw per mesh, its texture bound when it changes. Batched (w TAB, Algorithm 2): per "
       "output batch, every texture array and the TAM bound once, one draw per geometry batch. Same triangles, same "
       "order (docs/tab.md).</p><h2>Scene (Table 1)</h2><pre>" +
       verify::escapeHtml(table1.dump(1)) + "</pre><h2>Summary</h2><pre>" + verify::escapeHtml(summary.dump(1)) +
       "</pre><img src=\"plot.png\" style=\"max-width:900px\"><h2>Frames</h2><table><tr><th>frame</th><th>variant</th>"
       "<th>draw calls</th><th>texture binds</th><th>texture state changes</th><th>state changes</th><th>ms</th>"
       "<th>identical %</th><th>image</th></tr>";
  for (const auto& r : rows) {
    h += "<tr><td>" + std::to_string(r["frame"].get<int>()) + "</td><td>" + r["variant"].get<std::string>() + "</td>";
    for (const char* k : {"draw_calls", "texture_binds", "texture_state_changes", "state_changes"})
      h += "<td>" + std::to_string(r[k].get<uint64_t>()) + "</td>";
    char ms[32];
    std::snprintf(ms, sizeof ms, "%.1f", r["frame_time_ms"].get<double>());
    h += std::string("<td>") + ms + "</td><td>";
    if (r.contains("identical_percent")) {
      char pc[32];
      std::snprintf(pc, sizeof pc, "%.3f", r["identical_percent"].get<double>());
      h += pc;
    }
    h += "</td><td>";
    if (r.contains("image")) h += "<img src=\"" + r["image"].get<std::string>() + "\">";
    if (r.contains("diff_image")) h += " <img src=\"" + r["diff_image"].get<std::string>() + "\" title=\"differing pixels in red\">";
    h += "</td></tr>";
  }
  h += "</table></body></html>\n";
  writeTextFile((fs::path(a.out) / "index.html").string(), h);
}

}  // namespace

nlohmann::json runTabRender(const TabRenderArgs& a) {
  if (a.baseline && a.both) throw Error("tab render: --baseline and --both exclude each other");
  const auto [w, h] = parseSize(a.size, "--size");
  prepareOutputDirectory(a.out, "-o");
  const batching::TabScene s = batching::readTabFile(a.input, a.limits);
  const mta::CameraPath path = tabCameraPath(a, s);
  std::vector<Variant> variants;
  if (a.both) variants = {Variant::Baseline, Variant::Batched};
  else variants = {a.baseline ? Variant::Baseline : Variant::Batched};

  CpuBackend backend(RenderOptions{a.threads});
  RenderOptions probeOptions{a.threads};
  probeOptions.lodProbe = true;
  CpuBackend probe(probeOptions);  // --both: the LOD maps of both variants, on reused storage
  LodMap baselineLod, batchedLod;
  nlohmann::json rows = nlohmann::json::array();
  PathRunArgs saveRule;
  saveRule.saveEvery = a.saveEvery;
  Progress progress("tab render", path.frames.size(), a.quiet);
  double identicalMin = 100.0, identicalSum = 0.0;
  uint64_t lambdaDiffering = 0, lambdaPixels = 0;
  // One list per variant, recorded into again every frame (CommandList::clear keeps the storage of the
  // texture-array uploads); with --both the batched frame is compared with the baseline's list.
  std::vector<CommandList> lists(variants.size());
  for (size_t i = 0; i < path.frames.size(); ++i) {
    mta::validate(path.frames[i], "tab render: camera path frame " + std::to_string(i));
    batching::TabView view;
    view.mvp = mta::viewProjection(path.frames[i], uint32_t(w), uint32_t(h));
    view.eye = path.frames[i].eye;
    view.width = uint32_t(w), view.height = uint32_t(h);
    const bool save = saveFrame(saveRule, i, path.frames.size());
    std::vector<uint8_t> firstImage;
    const CommandList* firstList = nullptr;
    std::string detail;
    for (size_t vi = 0; vi < variants.size(); ++vi) {
      const Variant v = variants[vi];
      batching::TabDraws draws;
      batching::recordTabFrame(s, v, view, lists[vi], &draws);
      const CommandList& list = lists[vi];
      const FrameCounters c = countCommands(list);
      const auto t0 = std::chrono::steady_clock::now();
      backend.execute(list, std::string("tab ") + batching::variantName(v) + " frame " + std::to_string(i));
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      const PresentedImage img = backend.presented().at(0);
      const TextureData& tex = *backend.texture(img.texture);
      std::vector<uint8_t> pixels = imagePixels(tex, img.level, img.layer);
      nlohmann::json r = {{"frame", i},
                          {"variant", batching::variantName(v)},
                          {"draw_calls", c.draw_calls},
                          {"textured_draws", draws.textured},
                          {"untextured_draws", draws.untextured},
                          {"blend_draws", draws.blend},
                          {"texture_binds", c.texture_binds},
                          {"texture_state_changes", c.texture_state_changes},
                          {"state_changes", c.state_changes},
                          {"redundant_state_changes", c.redundant_state_changes},
                          {"primitives_submitted", c.primitives_submitted},
                          {"frame_time_ms", ms},
                          {"image_sha256", imageSha256(tex, img.level, img.layer)}};
      const std::string stem = frameName(batching::variantName(v), i);
      if (save) {
        const std::string png = fs::path(stem).replace_extension(".png").string();
        writePngRGBA8((fs::path(a.out) / png).string(), w, h, pixels.data());
        const std::string tframe = fs::path(stem).replace_extension(".tframe").string();
        writeFrame(list, (fs::path(a.out) / tframe).string());
        r["image"] = png;
        r["tframe"] = tframe;
      }
      if (v == Variant::Batched && !firstImage.empty()) {  // --both: compare with the baseline of this frame
        size_t same = 0;
        for (size_t p = 0; p + 3 < pixels.size(); p += 4) same += std::memcmp(&pixels[p], &firstImage[p], 4) == 0;
        const double pct = 100.0 * double(same) / double(pixels.size() / 4);
        r["identical_pixels"] = same;
        r["identical_percent"] = pct;
        identicalMin = std::min(identicalMin, pct);
        identicalSum += pct;
        // The same LOD at every pixel (docs/texel.md): the probe re-renders both frames (untimed).
        lodMap(probe, *firstList, baselineLod);
        lodMap(probe, list, batchedLod);
        const verify::LodComparison lc = verify::compareLodMaps(baselineLod, batchedLod, "baseline", "batched");
        nlohmann::json reasons;
        for (int k = 1; k < verify::kLodDiffKinds; ++k) reasons[std::string(verify::lodDiffName(verify::LodDiff(k)))] = lc.count[k];
        r["lambda_pixels_with_lookups"] = lc.pixelsWithLookups;
        r["lambda_differing_pixels"] = lc.differing;
        r["lambda_differing_by_reason"] = reasons;
        lambdaDiffering += lc.differing;
        lambdaPixels += lc.pixelsWithLookups;
        if (save) {
          const std::string diff = frameName("diff", i);
          writePngRGBA8((fs::path(a.out) / diff).string(), w, h, diffImage(firstImage, pixels).data());
          r["diff_image"] = diff;
        }
      }
      if (firstImage.empty()) firstImage = std::move(pixels), firstList = &list;
      detail += std::string(batching::variantName(v)) + " " + std::to_string(c.draw_calls) + " draws ";
      rows.push_back(std::move(r));
    }
    progress.tick(i + 1, detail);
  }

  nlohmann::json summary = {{"frames", path.frames.size()}, {"path", path.name}, {"size", a.size}};
  std::vector<verify::Series> drawSeries, changeSeries, timeSeries;
  for (Variant v : variants) {
    nlohmann::json sub = nlohmann::json::array();
    for (const auto& r : rows)
      if (r["variant"] == batching::variantName(v)) sub.push_back(r);
    nlohmann::json js;
    for (const char* k : {"draw_calls", "texture_binds", "texture_state_changes", "state_changes", "frame_time_ms"}) {
      const auto [mx, mean] = maxMean(column(sub, k));
      js[std::string(k) + "_mean"] = mean;
      js[std::string(k) + "_max"] = mx;
    }
    summary[batching::variantName(v)] = js;
    const bool base = v == Variant::Baseline;
    const verify::Rgba col = base ? kGrey : kBlue;
    drawSeries.push_back({std::string(batching::variantName(v)) + " draw calls", column(sub, "draw_calls"), col, false, 2});
    changeSeries.push_back({std::string(batching::variantName(v)) + " texture state changes", column(sub, "texture_state_changes"), col, false, 2});
    timeSeries.push_back({std::string(batching::variantName(v)) + " oracle ms", column(sub, "frame_time_ms"), col, false, 2});
  }
  std::vector<verify::RgbaCanvas> panels;
  panels.push_back(verify::drawLineChart({"Draw calls per frame", "frame", "draw calls", drawSeries}));
  panels.push_back(verify::drawLineChart({"Texture state changes per frame", "frame", "changes", changeSeries}));
  panels.push_back(verify::drawLineChart({"Oracle frame time", "frame", "ms", timeSeries}));
  if (a.both) {
    const double n = double(path.frames.size());
    summary["identical_percent_mean"] = n > 0 ? identicalSum / n : 100.0;
    summary["identical_percent_min"] = identicalMin;
    summary["lambda_pixels_with_lookups"] = lambdaPixels;
    summary["lambda_differing_pixels"] = lambdaDiffering;
    summary["speedup_oracle"] = summary["batched"]["frame_time_ms_mean"].get<double>() > 0
                                    ? summary["baseline"]["frame_time_ms_mean"].get<double>() /
                                          summary["batched"]["frame_time_ms_mean"].get<double>()
                                    : 0.0;
    nlohmann::json batchedRows = nlohmann::json::array();
    for (const auto& r : rows)
      if (r["variant"] == "batched") batchedRows.push_back(r);
    verify::LineChart c{"Pixels identical to the baseline", "frame", "%", {{"identical %", column(batchedRows, "identical_percent"), kGreen, false, 2}}};
    panels.push_back(verify::drawLineChart(c));
  }
  writeChartPng((fs::path(a.out) / "plot.png").string(), verify::stackCharts(panels));
  const nlohmann::json table1 = batching::tableOneJson(s);
  nlohmann::json doc = {{"scene", table1}, {"summary", summary}, {"frames", rows}};
  writeTextFile((fs::path(a.out) / "frames.json").string(), doc.dump(1) + "\n");
  writeTabIndex(a, table1, summary, rows);
  return summary;
}

}  // namespace tessera::cli
