#include "tools/cli/rtta_render.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>

#include "base/error.h"
#include "batching/input_batches.h"
#include "model/model.h"
#include "mta/camera.h"
#include "mta/camera_path.h"
#include "raster/counters.h"
#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "raster/programs/atlas_ao.h"
#include "raster/serialize.h"
#include "rtta/layer_policy.h"
#include "rtta/rtta_record.h"
#include "rtta/shift_explain.h"
#include "tools/cli/frame_job.h"
#include "tools/cli/mta_path_run.h"
#include "tools/cli/options.h"
#include "tools/cli/output_directory.h"
#include "tools/cli/rtta_scenes.h"
#include "verify/html_escape.h"

namespace tessera::cli {

namespace fs = std::filesystem;
using rtta::Composite;
using rtta::Mode;

namespace {

struct Setup {
  std::vector<Mode> modes;
  rtta::RttaOptions options;  // mode filled per run
  rtta::LayerPolicy layers;
  int w = 0, h = 0;
};

Setup validateArgs(const RttaRenderArgs& a) {
  Setup s;
  if (a.mode == "all") s.modes = {Mode::Std, Mode::Rtt, Mode::Rtta};
  else if (a.mode == "std") s.modes = {Mode::Std};
  else if (a.mode == "rtt") s.modes = {Mode::Rtt};
  else if (a.mode == "rtta") s.modes = {Mode::Rtta};
  else throw Error("--mode '" + a.mode + "': expected std, rtt, rtta or all");
  if (a.composite == "depth") s.options.composite = Composite::Depth;
  else if (a.composite == "transparent") s.options.composite = Composite::Transparent;
  else if (a.composite == "ghosted") s.options.composite = Composite::Ghosted;
  else if (a.composite == "ghosted-ao") s.options.composite = Composite::GhostedAo;
  else throw Error("--composite '" + a.composite + "': expected depth, transparent, ghosted or ghosted-ao");
  if (a.texturing == "tab") s.options.texturing = rtta::Texturing::Tab;
  else if (a.texturing != "bind") throw Error("--texturing '" + a.texturing + "': expected bind or tab");
  if (a.objects != "mesh" && a.objects != "node") throw Error("--objects '" + a.objects + "': expected mesh or node");
  // The default border is 1 texel, or the occlusion kernel's radius for ghosted-ao (docs/rtta.md).
  const int32_t border = a.border != kDefaultBorder ? a.border
                         : s.options.composite == Composite::GhostedAo ? programs::kAoRadius
                                                                        : 1;
  if (border < 0 || border > 64) throw Error("--border " + std::to_string(border) + ": expected 0..64 pixels");
  if (s.options.composite == Composite::GhostedAo && border < programs::kAoRadius)
    throw Error("--border " + std::to_string(border) + ": --composite ghosted-ao needs at least " +
                std::to_string(programs::kAoRadius) +
                " (the occlusion kernel's radius), or its kernel would read a neighbour's atlas region");
  s.layers = rtta::parseLayerPolicy(a.layers, "--layers");
  std::tie(s.w, s.h) = parseSize(a.size, "--size");
  s.options.params.border = border;
  s.options.params.cull = !a.noCull;
  s.options.important = a.important;
  if (!a.atlas.empty()) {
    std::tie(s.options.atlasWidth, s.options.atlasHeight) = parseSize(a.atlas, "--atlas");
  } else {
    s.options.atlasWidth = rtta::defaultAtlasSide(s.w, border);
    s.options.atlasHeight = rtta::defaultAtlasSide(s.h, border);
  }
  try {
    rtta::validateAtlas(s.options.atlasWidth, s.options.atlasHeight, {0, 0, s.w, s.h}, border);
  } catch (const Error& e) {
    throw Error(std::string("--atlas: ") + e.what());
  }
  return s;
}

mta::CameraPath rttaCameraPath(const RttaRenderArgs& a, const std::array<float, 6>& bounds, bool empty) {
  if (a.input == "five" && a.path == "orbit") {
    const auto [w, h] = parseSize(a.size, "--size");
    return fiveOrbit(a.frames, w, h);
  }
  const auto names = mta::builtinPathNames();
  if (std::find(names.begin(), names.end(), a.path) != names.end()) {
    if (empty) throw Error(a.input + ": the scene has no vertices to lay a camera path over");
    return mta::builtinPath(a.path, bounds, a.frames);
  }
  mta::CameraPath p = mta::readPathFile(a.path);
  if (a.frames && a.frames < p.frames.size()) p.frames.resize(a.frames);
  return p;
}

rtta::RttaView viewOf(const mta::Camera& c, int w, int h) {
  rtta::RttaView v;
  v.mvp = mta::viewProjection(c, uint32_t(w), uint32_t(h));
  v.eye = c.eye;
  v.width = uint32_t(w);
  v.height = uint32_t(h);
  return v;
}

// Bottom-up RGBA8 of one layer of a 2D / array texture.
std::vector<uint8_t> layerBytes(const TextureData& t, uint32_t layer) {
  const size_t n = size_t(t.desc.width) * t.desc.height * 4;
  return {t.levels[0].begin() + ptrdiff_t(n * layer), t.levels[0].begin() + ptrdiff_t(n * (layer + 1))};
}

// An atlas layer for looking at: empty texels (the reserved alpha 0) as a dark checkerboard, every
// B_atlas outlined in red and every object's interior (B_atlas without its border) in yellow, like the
// red lines of the paper's Fig. 1.
std::vector<uint8_t> atlasPicture(const TextureData& t, uint32_t layer, const std::vector<rtta::Record>& recs) {
  std::vector<uint8_t> img = layerBytes(t, layer);
  const int w = int(t.desc.width), h = int(t.desc.height);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* p = &img[(size_t(y) * w + x) * 4];
      if (p[3] == 0) p[0] = p[1] = p[2] = ((x / 8 + y / 8) & 1) ? 40 : 56;
      p[3] = 255;
    }
  auto outline = [&](const rtta::PixelRect& r, std::array<uint8_t, 3> c) {
    auto put = [&](int x, int y) {
      if (x < 0 || y < 0 || x >= w || y >= h) return;
      std::memcpy(&img[(size_t(y) * w + x) * 4], c.data(), 3);
    };
    for (int x = r.x0; x < r.x1; ++x) put(x, r.y0), put(x, r.y1 - 1);
    for (int y = r.y0; y < r.y1; ++y) put(r.x0, y), put(r.x1 - 1, y);
  };
  for (const rtta::Record& r : recs) {
    if (r.layer != int32_t(layer)) continue;
    const int dx = r.atlas.x0 - r.viewport.x0, dy = r.atlas.y0 - r.viewport.y0;
    if (r.inner != r.viewport) outline({r.inner.x0 + dx, r.inner.y0 + dy, r.inner.x1 + dx, r.inner.y1 + dy}, {230, 200, 40});
    outline(r.atlas, {230, 40, 30});
  }
  return img;
}

// Per-object comparison of the RTTA capture with the RTT capture: over each visible object's interior
// pixels that are on screen, how many atlas texels equal the RTT layer's pixel (colour and depth).
struct CaptureCompare {
  uint64_t pixels = 0, identical = 0;
};

std::string fmtPercent(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f", v);
  return b;
}

void writeRttaIndex(const RttaRenderArgs& a, const nlohmann::json& table, const nlohmann::json& rows) {
  std::string h =
      "<!doctype html><html><head><meta charset=\"utf-8\"><title>tessera rtta render</title><style>"
      "body{font-family:sans-serif;margin:20px}table{border-collapse:collapse}td,th{border:1px solid #ccc;"
      "padding:3px 8px;text-align:right}img{max-width:300px;image-rendering:pixelated}</style></head><body>";
  h += "<h1>Render-to-texture-atlas: " + verify::escapeHtml(a.input) + "</h1>";
  h += "<p>STD draws the scene once; RTT renders one off-screen pass per object into a viewport-sized layer, then "
       "composites; RTTA packs every object's projected box into a layered atlas, captures all of them in one pass by "
       "screen-space vertex displacement, then composites (docs/rtta.md). Atlas pictures: red = B_atlas, yellow = the "
       "object's interior without its border, dark checkerboard = empty texels.</p>";
  h += "<h2>Table 1</h2><pre>" + verify::escapeHtml(table.dump(1)) + "</pre><img src=\"plot.png\" style=\"max-width:900px\">";
  h += "<h2>Frames</h2><table><tr><th>frame</th><th>mode</th><th>draw calls</th><th>render-target changes</th><th>clears</th>"
       "<th>texture binds</th><th>state changes</th><th>ms</th><th>identical % vs STD</th><th>images</th></tr>";
  for (const auto& r : rows) {
    h += "<tr><td>" + std::to_string(r["frame"].get<int>()) + "</td><td>" + r["mode"].get<std::string>() + "</td>";
    for (const char* k : {"draw_calls", "render_target_changes", "clears", "texture_binds", "state_changes"})
      h += "<td>" + std::to_string(r[k].get<uint64_t>()) + "</td>";
    h += "<td>" + fmtPercent(r["frame_time_ms"].get<double>()) + "</td><td>";
    if (r.contains("identical_percent_vs_std")) h += fmtPercent(r["identical_percent_vs_std"].get<double>());
    h += "</td><td>";
    if (r.contains("image")) h += "<img src=\"" + r["image"].get<std::string>() + "\">";
    if (r.contains("atlas_images"))
      for (const auto& im : r["atlas_images"]) h += " <img src=\"" + im.get<std::string>() + "\" title=\"atlas layer\">";
    h += "</td></tr>";
  }
  h += "</table></body></html>\n";
  writeTextFile((fs::path(a.out) / "index.html").string(), h);
}

}  // namespace

std::vector<std::string> rttaSceneNames() { return builtinRttaSceneNames(); }

nlohmann::json rttaParams(const RttaRenderArgs& a) {
  Setup s = validateArgs(a);
  const LoadedRttaScene ls = loadRttaScene(a.input, a.objects, a.limits, true, a.texturing == "tab");
  const mta::CameraPath path = rttaCameraPath(a, ls.scene.tab.bounds, ls.scene.vertices.empty());
  if (path.frames.empty()) throw Error(a.path + ": the camera path has no frames");
  mta::validate(path.frames[0], "rtta params: camera path frame 0");
  s.options.mode = Mode::Rtta;
  const rtta::RttaFrame f = rtta::recordRttaFrame(ls.scene, viewOf(path.frames[0], s.w, s.h), s.options);
  nlohmann::json recs = nlohmann::json::array();
  auto rect = [](const rtta::PixelRect& r) { return nlohmann::json{r.x0, r.y0, r.x1, r.y1}; };
  for (const rtta::Record& r : f.records) {
    nlohmann::json j = {{"id", r.id},
                        {"name", ls.scene.objectNames[r.id]},
                        {"b_world", {{"min", {r.world.lo.x, r.world.lo.y, r.world.lo.z}}, {"max", {r.world.hi.x, r.world.hi.y, r.world.hi.z}}}},
                        {"culled", rtta::culledName(r.culled)}};
    if (r.visible()) {
      j["near_clipped"] = r.nearClipped;
      j["whole_viewport"] = r.wholeViewport;
      j["b_viewport_inner"] = rect(r.inner);
      j["b_viewport"] = rect(r.viewport);
      j["b_atlas"] = rect(r.atlas);
      j["layer"] = r.layer;
      j["T"] = {{"a", r.T.a}, {"b", r.T.b}, {"c", r.T.c}, {"d", r.T.d}, {"tx", r.T.tx}, {"ty", r.T.ty}};
    }
    recs.push_back(std::move(j));
  }
  return {{"scene", a.input},
          {"objects", a.objects},
          {"viewport", {s.w, s.h}},
          {"border", s.options.params.border},
          {"atlas", {{"width", f.atlas.width}, {"height", f.atlas.height}, {"layers", f.atlas.layers}}},
          {"inexact_transforms", f.inexactTransforms},
          {"camera", {{"eye", {path.frames[0].eye.x, path.frames[0].eye.y, path.frames[0].eye.z}},
                      {"target", {path.frames[0].target.x, path.frames[0].target.y, path.frames[0].target.z}}}},
          {"records", recs}};
}

nlohmann::json runRttaRender(const RttaRenderArgs& a) {
  Setup s = validateArgs(a);
  // Everything that can be refused is checked before the output directory is made.
  const LoadedRttaScene ls = loadRttaScene(a.input, a.objects, a.limits, a.quiet, a.texturing == "tab");
  const rtta::RttaScene& scene = ls.scene;
  for (uint32_t id : a.important)
    if (id >= scene.objectNames.size())
      throw Error("--important " + std::to_string(id) + ": the scene has " + std::to_string(scene.objectNames.size()) + " objects");
  const mta::CameraPath path = rttaCameraPath(a, scene.tab.bounds, scene.vertices.empty());
  prepareOutputDirectory(a.out, "-o");
  CpuBackend backend(RenderOptions{a.threads});
  rtta::LayerAllocator allocator(s.layers);
  nlohmann::json rows = nlohmann::json::array();
  PathRunArgs saveRule;
  saveRule.saveEvery = a.saveEvery;
  Progress progress("rtta render", path.frames.size(), a.quiet);
  std::map<Mode, std::vector<double>> ms;
  uint64_t culledTotal = 0, layersNeededMax = 0, layersAllocatedMax = 0;
  uint64_t captureCompared = 0, captureIdentical = 0, captureUnexplained = 0;
  struct VsStd {
    double min = 100.0, sum = 0.0;
    uint64_t frames = 0, differing = 0, explained = 0, ties = 0, unexplained = 0;
  };
  std::map<Mode, VsStd> vsStd;  // depth composites of RTT and RTTA against STD
  nlohmann::json lastAtlas;
  for (size_t i = 0; i < path.frames.size(); ++i) {
    mta::validate(path.frames[i], "rtta render: camera path frame " + std::to_string(i));
    const rtta::RttaView view = viewOf(path.frames[i], s.w, s.h);
    const bool save = saveFrame(saveRule, i, path.frames.size());
    std::vector<uint8_t> stdImage, stdDepth, rttCapture;
    std::vector<uint32_t> rttLayerOf;  // object id -> RTT layer
    std::string detail;
    for (Mode m : s.modes) {
      rtta::RttaOptions o = s.options;
      o.mode = m;
      rtta::RttaFrame f = rtta::recordRttaFrame(scene, view, o);
      if (m == Mode::Rtta) {
        const uint32_t alloc = allocator.frame(uint32_t(f.atlas.layers));
        if (alloc != f.allocatedLayers) {
          o.allocatedLayers = alloc;
          f = rtta::recordRttaFrame(scene, view, o);
        }
      }
      // Where the capture may differ from the objects rendered alone (shift_explain.h).
      rtta::ShiftExplanation why;
      if (m == Mode::Rtta) why = rtta::explainShift(scene, f.records, view.mvp, {0, 0, s.w, s.h}, f.atlas);
      const FrameCounters c = countCommands(f.list);
      const auto t0 = std::chrono::steady_clock::now();
      backend.execute(f.list, std::string("rtta ") + rtta::modeName(m) + " frame " + std::to_string(i));
      const double t = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      ms[m].push_back(t);
      const TextureData& screen = *backend.texture(f.screen);
      std::vector<uint8_t> pixels = imagePixels(screen, 0, 0);
      uint64_t culled = 0;
      for (const rtta::Record& r : f.records) culled += r.visible() ? 0 : 1;
      nlohmann::json r = {{"frame", i},
                          {"mode", rtta::modeName(m)},
                          {"draw_calls", c.draw_calls},
                          {"render_target_changes", c.render_target_changes},
                          {"clears", c.clears},
                          {"texture_binds", c.texture_binds},
                          {"texture_state_changes", c.texture_state_changes},
                          {"state_changes", c.state_changes},
                          {"redundant_state_changes", c.redundant_state_changes},
                          {"primitives_submitted", c.primitives_submitted},
                          {"target_bytes", f.targetBytes},
                          {"objects_culled", culled},
                          {"frame_time_ms", t},
                          {"image_sha256", imageSha256(screen, 0, 0)}};
      if (m == Mode::Std) stdImage = pixels, stdDepth = backend.texture(f.screenDepth)->levels[0];
      else if (!stdImage.empty() && o.composite == Composite::Depth) {
        size_t same = 0, explained = 0, ties = 0;
        for (size_t p = 0; p + 3 < pixels.size(); p += 4) {
          if (std::memcmp(&pixels[p], &stdImage[p], 4) == 0) {
            ++same;
            continue;
          }
          // pixels are top row first; the mask is GL rows, bottom first.
          const size_t px = (p / 4) % size_t(s.w), py = size_t(s.h) - 1 - (p / 4) / size_t(s.w);
          if (!why.mask.empty() && why.mask[py * size_t(s.w) + px] != 0) {
            ++explained;
            continue;
          }
          // A depth tie: the composite kept another object at exactly STD's depth.
          float zs, zc;
          std::memcpy(&zs, &stdDepth[(py * size_t(s.w) + px) * 4], 4);
          std::memcpy(&zc, backend.texture(f.screenDepth)->texel(0, 0, uint32_t(px), uint32_t(py)), 4);
          ties += zs == zc;
        }
        const double pct = 100.0 * double(same) / double(pixels.size() / 4);
        r["identical_percent_vs_std"] = pct;
        const size_t unexplained = pixels.size() / 4 - same - explained - ties;
        r["differing_vs_std"] = {{"pixels", pixels.size() / 4 - same},
                                 {"where_the_capture_rounds_or_clips", explained},
                                 {"depth_ties_between_objects", ties},
                                 {"unexplained", unexplained}};

        VsStd& acc = vsStd[m];
        acc.min = std::min(acc.min, pct);
        acc.sum += pct;
        ++acc.frames;
        acc.differing += pixels.size() / 4 - same;
        acc.explained += explained;
        acc.ties += ties;
        acc.unexplained += unexplained;
      }
      if (m == Mode::Rtt) {
        rttCapture = backend.texture(f.captureColor)->levels[0];
        rttLayerOf.assign(scene.objectNames.size(), ~0u);
        uint32_t layer = 0;
        for (const rtta::Record& rec : f.records)
          if (rec.visible()) rttLayerOf[rec.id] = layer++;
      }
      if (m == Mode::Rtta) {
        culledTotal += culled;
        layersNeededMax = std::max<uint64_t>(layersNeededMax, uint64_t(f.atlas.layers));
        layersAllocatedMax = std::max<uint64_t>(layersAllocatedMax, f.allocatedLayers);
        r["atlas"] = {{"width", f.atlas.width}, {"height", f.atlas.height}, {"layers_needed", f.atlas.layers},
                      {"layers_allocated", f.allocatedLayers}, {"inexact_transforms", f.inexactTransforms}};
        // Utilization and waste, in texels of the needed layers.
        const TextureData& atlas = *backend.texture(f.captureColor);
        uint64_t regions = 0, interiors = 0, covered = 0;
        for (const rtta::Record& rec : f.records) {
          if (!rec.visible()) continue;
          regions += uint64_t(rec.viewport.width()) * uint64_t(rec.viewport.height());
          interiors += uint64_t(rec.inner.width()) * uint64_t(rec.inner.height());
          const int dx = rec.atlas.x0 - rec.viewport.x0, dy = rec.atlas.y0 - rec.viewport.y0;
          for (int y = rec.inner.y0; y < rec.inner.y1; ++y)
            for (int x = rec.inner.x0; x < rec.inner.x1; ++x) {
              const uint8_t* texel = atlas.texel(0, uint32_t(rec.layer), uint32_t(x + dx), uint32_t(y + dy));
              covered += texel[3] != 0;
              if (!rttCapture.empty() && x >= 0 && y >= 0 && x < s.w && y < s.h) {
                const size_t off = ((size_t(rttLayerOf[rec.id]) * size_t(s.h) + size_t(y)) * size_t(s.w) + size_t(x)) * 4;
                ++captureCompared;
                const bool same = std::memcmp(texel, &rttCapture[off], 4) == 0;
                captureIdentical += same;
                captureUnexplained += !same && why.mask[size_t(y) * size_t(s.w) + size_t(x)] == 0;
              }
            }
        }
        const uint64_t total = uint64_t(f.atlas.layers) * uint64_t(f.atlas.width) * uint64_t(f.atlas.height);
        r["atlas"]["utilization_percent"] = total ? 100.0 * double(covered) / double(total) : 0.0;
        r["atlas"]["texels_wasted"] = {{"packing", total - regions}, {"border", regions - interiors}, {"aabb", interiors - covered}};
        lastAtlas = r["atlas"];
        if (save) {
          nlohmann::json ims = nlohmann::json::array();
          for (int32_t l = 0; l < std::min(f.atlas.layers, 8); ++l) {
            const std::string name = frameName(("atlas_l" + std::to_string(l)).c_str(), i);
            writeFramePng((fs::path(a.out) / name).string(), uint32_t(f.atlas.width), uint32_t(f.atlas.height),
                          atlasPicture(atlas, uint32_t(l), f.records));
            ims.push_back(name);
          }
          r["atlas_images"] = ims;
        }
      }
      if (save) {
        const std::string stem = frameName(rtta::modeName(m), i);
        writePngRGBA8((fs::path(a.out) / stem).string(), s.w, s.h, pixels.data());
        const std::string tframe = fs::path(stem).replace_extension(".tframe").string();
        writeFrame(f.list, (fs::path(a.out) / tframe).string());
        r["image"] = stem;
        r["tframe"] = tframe;
        if (m == Mode::Rtta) {  // the capture alone, so its atlas layers are presented images (crosscheck)
          rtta::RttaOptions co = o;
          co.captureOnly = true;
          const std::string atlasFrame = fs::path(frameName("atlas", i)).replace_extension(".tframe").string();
          writeFrame(rtta::recordRttaFrame(scene, view, co).list, (fs::path(a.out) / atlasFrame).string());
          r["atlas_tframe"] = atlasFrame;
        }
      }
      detail += std::string(rtta::modeName(m)) + " " + std::to_string(c.draw_calls) + " draws ";
      rows.push_back(std::move(r));
    }
    progress.tick(i + 1, detail);
  }

  nlohmann::json modes;
  std::vector<verify::Series> timeSeries, drawSeries;
  const verify::Rgba colours[3] = {kGrey, kOrange, kBlue};
  for (Mode m : s.modes) {
    nlohmann::json sub = nlohmann::json::array();
    for (const auto& r : rows)
      if (r["mode"] == rtta::modeName(m)) sub.push_back(r);
    nlohmann::json js;
    for (const char* k : {"draw_calls", "render_target_changes", "clears", "texture_binds", "state_changes", "target_bytes",
                          "frame_time_ms"}) {
      const auto [mx, mean] = maxMean(column(sub, k));
      js[std::string(k) + "_mean"] = mean;
      js[std::string(k) + "_max"] = mx;
    }
    modes[rtta::modeName(m)] = js;
    timeSeries.push_back({std::string(rtta::modeName(m)) + " oracle ms", column(sub, "frame_time_ms"), colours[int(m)], false, 2});
    drawSeries.push_back({std::string(rtta::modeName(m)) + " draw calls", column(sub, "draw_calls"), colours[int(m)], false, 2});
  }
  nlohmann::json table = {{"scene", a.input},
                          {"objects_mode", a.objects},
                          {"vertex_count", scene.vertices.size()},
                          {"face_count", scene.triangles()},
                          {"object_count", scene.objectNames.size()},
                          {"size", a.size},
                          {"composite", a.composite},
                          {"border", s.options.params.border},
                          {"culling", !a.noCull},
                          {"layers_policy", s.layers.name()},
                          {"frames", path.frames.size()},
                          {"path", path.name},
                          {"modes", modes}};
  if (std::find(s.modes.begin(), s.modes.end(), Mode::Rtta) != s.modes.end()) {
    table["atlas"] = {{"width", s.options.atlasWidth},
                      {"height", s.options.atlasHeight},
                      {"layers_needed_max", layersNeededMax},
                      {"layers_allocated_max", layersAllocatedMax},
                      {"reallocations", allocator.reallocations()},
                      {"objects_culled_total", culledTotal},
                      {"last_frame", lastAtlas}};
    if (captureCompared) {
      table["capture_vs_rtt_identical_percent"] = 100.0 * double(captureIdentical) / double(captureCompared);
      table["capture_vs_rtt_differing_pixels"] = captureCompared - captureIdentical;
      table["capture_vs_rtt_differing_unexplained"] = captureUnexplained;
    }
  }
  for (const auto& [m, acc] : vsStd)
    table["composite_vs_std"][rtta::modeName(m)] = {{"identical_percent_mean", acc.sum / double(acc.frames)},
                                                    {"identical_percent_min", acc.min},
                                                    {"differing_pixels", acc.differing},
                                                    {"where_the_capture_rounds_or_clips", acc.explained},
                                                    {"depth_ties_between_objects", acc.ties},
                                                    {"unexplained", acc.unexplained}};
  std::vector<verify::RgbaCanvas> panels;
  panels.push_back(verify::drawLineChart({"Oracle frame time", "frame", "ms", timeSeries}));
  panels.push_back(verify::drawLineChart({"Draw calls per frame", "frame", "draw calls", drawSeries}));
  writeChartPng((fs::path(a.out) / "plot.png").string(), verify::stackCharts(panels));
  writeTextFile((fs::path(a.out) / "table.json").string(), table.dump(1) + "\n");
  nlohmann::json doc = {{"table", table}, {"frames", rows}};
  writeTextFile((fs::path(a.out) / "frames.json").string(), doc.dump(1) + "\n");
  writeRttaIndex(a, table, rows);
  return table;
}

}  // namespace tessera::cli
