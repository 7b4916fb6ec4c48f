// `tessera texel`: the texel-per-pixel analysis of an atlas tree over a camera path (mta/texel_ratio.h):
// per-frame JSON, heat maps, frames and a histogram of pixels per texel (docs/mta-render.md). A .tframe
// input goes to runTexelFrame (cmd_texel_frame.cpp, docs/texel.md).
#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "base/error.h"
#include "model/model.h"
#include "mta/build.h"
#include "mta/scene.h"
#include "mta/texel_ratio.h"
#include "raster/image_io.h"
#include "tools/cli/commands.h"
#include "tools/cli/frame_job.h"
#include "tools/cli/mta_path_run.h"
#include "tools/cli/options.h"
#include "tools/cli/output_directory.h"
#include "tools/cli/texel_frame.h"

namespace tessera::cli {

namespace fs = std::filesystem;

namespace {

verify::RgbaCanvas ratioHistogramPng(const std::array<uint64_t, mta::kRatioBins>& hist, double tau) {
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

// A heat map (mta::heatMap) with a colour bar underneath: the pixels-per-texel scale from 1/4 to 4τ,
// logarithmic like the colours, τ marked, and the special colours named, so the image reads on its own.
verify::RgbaCanvas heatMapWithBar(const mta::TexelFrame& t, double tau, bool perAxis) {
  const std::vector<uint8_t> heat = mta::heatMap(t, tau, perAxis);
  const int w = std::max(int(t.width), 420), h = int(t.height), barH = 14, legend = 106, left = 12, barW = w - 2 * left;
  verify::RgbaCanvas c(w, h + legend, {255, 255, 255, 255});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < int(t.width); ++x) {
      const uint8_t* p = heat.data() + (size_t(y) * t.width + size_t(x)) * 4;
      c.set(x, y, {p[0], p[1], p[2], p[3]});
    }
  // log2 of the bar's ends: 1/4 and 4τ.
  const double lt = mta::log2Exact(tau), lo = -2.0, hi = lt + 2.0;
  auto xOf = [&](double ratio) { return left + int(double(barW) * (mta::log2Exact(ratio) - lo) / (hi - lo) + 0.5); };
  const int top = h + 22;  // τ's label goes above the bar
  for (int i = 0; i < barW; ++i) {
    const auto col = mta::heatColorLog2(lo + (hi - lo) * (i + 0.5) / barW, lt);
    c.fillRect(left + i, top, 1, barH, {col[0], col[1], col[2], col[3]});
  }
  const verify::Rgba black{0, 0, 0, 255};
  char label[32];
  for (double r : {0.25, 0.5, 1.0, 2.0, 4.0 * tau}) {
    if (r > 1.0 && std::fabs(r - tau) < 0.15 * tau) continue;  // τ gets its own mark
    c.fillRect(xOf(r), top + barH, 1, 4, black);
    std::snprintf(label, sizeof label, "%g", r);
    c.text(std::clamp(xOf(r) - verify::RgbaCanvas::textWidth(label, 2) / 2, 0, w - 12), top + barH + 6, label, black, 2);
  }
  const int xt = xOf(tau);
  c.fillRect(xt - 1, top - 4, 3, barH + 8, black);
  std::snprintf(label, sizeof label, "tau=%g", tau);
  c.text(std::clamp(xt - verify::RgbaCanvas::textWidth(label, 2) / 2, 0, w - 12), h + 6, label, black, 2);
  c.text(left, top + barH + 26,
         perAxis ? "pixels per texel along its s and t edges (the larger), at the level sampled"
                 : "pixels per texel (GL's isotropic rho), at the level sampled",
         black, 1);
  c.fillRect(left, top + barH + 38, 8, 8, {255, 0, 255, 255});
  c.text(left + 12, top + barH + 39, "violation: atlas beyond tau where the original texture was finer", black, 1);
  c.fillRect(left, top + barH + 50, 8, 8, {45, 45, 45, 255});
  c.text(left + 12, top + barH + 51, "untextured", black, 1);
  c.fillRect(left + 90, top + barH + 50, 8, 8, {90, 90, 90, 255});
  c.text(left + 102, top + barH + 51, "background", black, 1);
  return c;
}

}  // namespace

nlohmann::json runTexel(const PathRunArgs& a) {
  prepareOutputDirectory(a.out, "-o");
  std::string treePath = a.input;
  if (fs::path(a.input).extension() != ".mta") {
    // A model: build its tree with the default parameters first (kept, so later runs can reuse it).
    treePath = (fs::path(a.out) / "tree.mta").string();
    if (!a.quiet) std::fprintf(stderr, "texel: %s is a model; building its atlas tree into %s\n", a.input.c_str(), treePath.c_str());
    auto model = std::make_shared<const model::Model>(model::loadModel(a.input, a.limits));
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
  uint64_t framesCapped = 0, degenerate = 0;
  uint64_t axisViolations = 0, axisViolationsAllResident = 0, axisAbovePixels = 0, atlasNodes = 0, leaves = 0, binds = 0;
  double maxRatio = 0.0, maxAxis = 0.0;
  Progress progress("texel", path.frames.size(), a.quiet);
  for (size_t i = 0; i < path.frames.size(); ++i) {
    mta::FrameResult r = renderer.renderFrame(path.frames[i]);
    const std::vector<uint32_t> ids = renderer.triangleIds(path.frames[i], r.plan);
    const mta::TexelFrame t = mta::analyzeTexels(renderer, path.frames[i], r, ids, tau);
    nlohmann::json j = mta::toJson(t);
    j["frame"] = i;
    j["needed_blocks_missing"] = r.residency.neededMissing;
    j["nodes_coarser_than_needed"] = r.plan.coarserThanNeeded;
    j["nodes_coarsened_for_binds"] = r.plan.coarsenedForBinds;
    rows.push_back(j);
    for (int b = 0; b < mta::kRatioBins; ++b) hist[size_t(b)] += t.histogram[size_t(b)];
    violations += t.magnificationViolations;
    atlasPixels += t.pixelsAtlas;
    abovePixels += t.atlasAboveTau;
    maxRatio = std::max(maxRatio, t.maxAtlasRatioBase);
    axisViolations += t.perAxisViolations;
    axisAbovePixels += t.atlasAxisAboveTau;
    maxAxis = std::max(maxAxis, t.maxAtlasAxisBase);
    degenerate += t.atlasPixelsDegenerateTexcoords;
    atlasNodes += r.plan.atlasNodes;
    leaves += r.plan.originalLeaves;
    binds += r.counters.texture_binds;
    // The guarantee's frames: drawn as the distance test asks, with nothing coarsened for lack of a
    // block (Figure 30) or for --max-binds.
    if (r.plan.coarsenedForBinds > 0) ++framesCapped;
    if (r.plan.coarserThanNeeded == 0 && r.plan.coarsenedForBinds == 0) {
      ++framesAllResident;
      violationsAllResident += t.magnificationViolations;
      axisViolationsAllResident += t.perAxisViolations;
    }
    if (saveFrame(a, i, path.frames.size())) {
      writeChartPng((fs::path(a.out) / frameName("texel", i)).string(), heatMapWithBar(t, tau, false));
      writeChartPng((fs::path(a.out) / frameName("texel_axis", i)).string(), heatMapWithBar(t, tau, true));
      writeFramePng((fs::path(a.out) / frameName("frame", i)).string(), t.width, t.height, r.image);
    }
    progress.tick(i + 1, std::to_string(t.magnificationViolations) + " / " + std::to_string(t.perAxisViolations) +
                             " violations (isotropic / per axis)");
  }
  nlohmann::json histJson = nlohmann::json::array();
  for (int b = 0; b < mta::kRatioBins; ++b) histJson.push_back({{"ratio_at_least", mta::ratioBinLower(b)}, {"pixels", hist[size_t(b)]}});
  nlohmann::json summary = {{"frames", rows.size()},
                            {"tau", tau},
                            {"magnification_violations", violations},
                            {"frames_with_every_needed_block_resident", framesAllResident},
                            {"frames_with_nodes_coarsened_for_binds", framesCapped},
                            {"magnification_violations_when_every_needed_block_resident", violationsAllResident},
                            {"atlas_pixels", atlasPixels},
                            {"atlas_pixels_above_tau_capped_by_original", abovePixels - violations},
                            {"max_atlas_ratio_level0", maxRatio},
                            {"per_axis_magnification_violations", axisViolations},
                            {"per_axis_magnification_violations_when_every_needed_block_resident", axisViolationsAllResident},
                            {"atlas_pixels_above_tau_per_axis_capped_by_original", axisAbovePixels - axisViolations},
                            {"max_atlas_per_axis_level0", maxAxis},
                            {"atlas_pixels_degenerate_texcoords", degenerate},
                            {"atlas_nodes_drawn", atlasNodes},
                            {"original_leaves_drawn", leaves},
                            {"texture_binds", binds},
                            {"histogram", histJson}};
  nlohmann::json doc = {{"options", optionsJson(a, o, path)}, {"summary", summary}, {"frames", rows}};
  writeTextFile((fs::path(a.out) / "texel.json").string(), doc.dump(1) + "\n");
  writeChartPng((fs::path(a.out) / "histogram.png").string(), ratioHistogramPng(hist, tau));
  return summary;
}

void addTexelCommand(CLI::App& app) {
  auto ta = std::make_shared<PathRunArgs>();
  auto against = std::make_shared<std::string>();
  auto* texel = app.add_subcommand(
      "texel",
      "Texel-per-pixel analysis. (1) Of an atlas tree over a camera path: per pixel, pixels per texel of the level "
      "sampled (analytic Jacobian), isotropic (GL's rho) and per axis (along the texel's own s and t edges), heat maps "
      "of both with a colour bar (texel_NNNN.png, texel_axis_NNNN.png), a histogram, and magnification_violations on "
      "either measure (atlas used although it magnifies beyond tau where the original is finer; isotropic: zero "
      "whenever every needed block is resident). (2) Of a recorded frame (.tframe, e.g. from "
      "`tessera render SCENE --record F.tframe`): the frame is replayed on the oracle with its LOD probe, which records "
      "for each pixel the lookups of the fragment whose colour is stored (after depth test and discard): rho (GL 4.6 "
      "8.14.1, texels of level 0) and lambda (8.8, after bias and clamps), as the sampler computed them. Writes "
      "texel.json (pixels with a lookup, lambda and log2(rho) histograms, min/mean/max, counts per unit, per texture "
      "size and per lookup count), lambda.png (heat map of the first lookup's lambda with a colour bar), histogram.png "
      "and lambda.i32 (raw int32 per pixel, docs/texel.md). With --against B.tframe it also probes B (suffix _against) "
      "and compares the frames pixel by pixel: lod_diff.png and the counts of differing pixels by reason "
      "(only_in_a, only_in_b, lookup_count, completeness, texture_size, lambda); exit status 1 if any pixel differs, 0 "
      "if lambda is identical everywhere, 2 for a missing, corrupt or invalid frame or frames of different sizes. "
      "Path, memory and model options do not apply to a .tframe; --threads does (records never depend on it)");
  texel->add_option("input", ta->input,
                    "Paging file (.mta), a model (glTF, OBJ, ...) whose tree is built first into OUT/tree.mta, or a "
                    "recorded frame (.tframe)")
      ->required();
  texel->add_option("--against", *against,
                    "With a .tframe input: a second frame of the same size to compare with, pixel by pixel (lambda and "
                    "texture size of every lookup)");
  addPathRunOptions(texel, *ta, true);
  addRealOption(texel, "--d-min", ta->buildDMin,
                "With a model: d_min of its atlas tree build (default 0: scene diagonal / 72, which for a small scene "
                "such as railway.glb means gigatexels; see docs/mta-build.md)",
                kNonNegative);
  addModelBudgetOptions(texel, ta->limits);
  texel->callback([ta, against] {
    if (fs::path(ta->input).extension() == ".tframe") {
      const TexelFrameArgs f{ta->input, *against, ta->out, ta->threads};
      const nlohmann::json summary = runTexelFrame(f);
      std::printf("%s\n", summary.dump(2).c_str());
      if (summary.contains("identical_lambda") && !summary["identical_lambda"].get<bool>()) throw CLI::RuntimeError(1);
      return;
    }
    if (!against->empty())
      throw Error("--against " + *against + ": only a .tframe input can be compared (" + ta->input + " is not one)");
    std::printf("%s\n", runTexel(*ta).dump(2).c_str());
  });
}

}  // namespace tessera::cli
