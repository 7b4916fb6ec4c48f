// `tessera rtta`: render-to-texture-atlas (Trapp & Döllner 2010) — print one frame's records, and
// render STD, RTT and RTTA over a camera path with Table 1's measures (docs/rtta.md).
#include <cstdio>
#include <memory>

#include "tools/cli/commands.h"
#include "tools/cli/options.h"
#include "tools/cli/rtta_render.h"

namespace tessera::cli {

namespace {

std::string sceneHelp() {
  std::string h = "A model file (glTF, OBJ, AC3D, Assimp formats) or a built-in scene:";
  for (const std::string& n : rttaSceneNames()) h += " " + n;
  return h;
}

void addCommon(CLI::App* cmd, RttaRenderArgs& a) {
  cmd->add_option("scene", a.input, sceneHelp())->required();
  cmd->add_option("--path", a.path,
                  "Camera path: orbit, street, thesis (laid out over the scene's bounds; for `five`, orbit is its "
                  "default camera swung from -45 to +45 degrees about the vertical) or a camera path file "
                  "(docs/mta-camera-path.md)")
      ->capture_default_str();
  addSizeOption(cmd, a.size, "Viewport WxH (the paper measured 1024x1024)")->capture_default_str();
  cmd->add_option("--atlas", a.atlas,
                  "Atlas layer size WxH, at least the viewport plus the border on each side (default: the smallest "
                  "power of two that holds it; powers of two make the transforms exact)");
  cmd->add_option("--border", a.border,
                  "Border in pixels around every atlas region (0..64); it keeps alpha 0 (default: 1, or 2 for "
                  "--composite ghosted-ao, whose occlusion kernel reaches 2 texels)");
  cmd->add_flag("--no-cull", a.noCull, "No view-frustum culling (the paper's Table 1 runs); off-screen objects still get no region");
  cmd->add_option("--objects", a.objects, "What an object is: mesh (one per model mesh) or node (one per scene-graph node instance)")
      ->capture_default_str();
  cmd->add_option("--texturing", a.texturing, "Capture texturing: bind (one bind and one draw per texture) or tab")
      ->capture_default_str();
  cmd->add_option("--layers", a.layers,
                  "Atlas layer allocation: exact (reallocate whenever Td changes) or lazy:K (grow at once, shrink after "
                  "K frames with the same smaller need; the paper's §4.2)")
      ->capture_default_str();
  addModelBudgetOptions(cmd, a.limits);
}

void addRttaRender(CLI::App* rtta) {
  auto a = std::make_shared<RttaRenderArgs>();
  auto* render = rtta->add_subcommand(
      "render",
      "Render STD (the scene once), RTT (one off-screen pass per object, then composite) and RTTA (one layered atlas "
      "pass by screen-space vertex displacement, then composite) over a camera path: composite and atlas-layer PNGs, "
      ".tframe files, frames.json, table.json (Table 1), plot.png and index.html; prints table.json");
  addCommon(render, *a);
  render->add_option("--mode", a->mode, "std, rtt, rtta or all")->capture_default_str();
  render->add_option("--composite", a->composite,
                     "depth (3A: depth sprites), transparent (3B: blended back to front), ghosted (3C: --important "
                     "objects opaque and highlighted, the rest translucent) or ghosted-ao (3D: ghosted, with ambient "
                     "occlusion and edge enhancement computed on the important objects' own atlas regions)")
      ->capture_default_str();
  render->add_option("--important", a->important, "Object ids shown opaque by --composite ghosted / ghosted-ao (default: the largest on screen)")
      ->delimiter(',');
  render->add_option("--frames", a->frames, "Frames (0 = the path's own count)")->capture_default_str();
  addThreadsOption(render, a->threads, "Oracle worker threads; images never depend on it");
  render->add_option("--save-every", a->saveEvery, "Write PNGs and .tframe of every K-th frame and the last (0 = none)")
      ->capture_default_str();
  render->add_option("-o,--output", a->out, "Output directory")->required();
  render->add_flag("--quiet", a->quiet, "No progress on stderr");
  render->callback([a] { std::printf("%s\n", runRttaRender(*a).dump(2).c_str()); });
}

void addParams(CLI::App* rtta) {
  auto a = std::make_shared<RttaRenderArgs>();
  a->quiet = true;
  auto* params = rtta->add_subcommand(
      "params",
      "Print the records of one frame as JSON (Algorithm 1: B_world, culling, B_viewport, B_atlas, layer, T) for the "
      "first camera of --path");
  addCommon(params, *a);
  params->callback([a] { std::printf("%s\n", rttaParams(*a).dump(2).c_str()); });
}

}  // namespace

void addRttaCommands(CLI::App& app) {
  auto* rtta = app.add_subcommand("rtta", "Render-to-texture-atlas, RTTA (Trapp & Döllner 2010): records, STD / RTT / RTTA frames");
  rtta->require_subcommand(1);
  addRttaRender(rtta);
  addParams(rtta);
}

}  // namespace tessera::cli
