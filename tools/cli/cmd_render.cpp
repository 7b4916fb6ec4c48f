// `tessera scenes | render | replay | validate`.
#include <cstdio>
#include <memory>

#include <fmt/format.h>

#include "raster/serialize.h"
#include "raster/validate.h"
#include "tools/cli/commands.h"
#include "tools/cli/frame_job.h"
#include "tools/cli/options.h"
#include "tools/scenes/scenes.h"

namespace tessera::cli {

namespace {

struct RenderArgs {
  std::string target;
  std::string size;
  FrameJob job;
};

void addJobOptions(CLI::App* c, RenderArgs& a) {
  addThreadsOption(c, a.job.threads, "Worker threads; the image bytes do not depend on it");
  addMemoryBudgetOption(c, a.job.limits);
  c->add_option("-o,--output", a.job.imagePath,
                "Image file for the presented target (PNG for RGBA8/R8, EXR for float and id targets); further "
                "attachments and layers get .aN / .lN suffixes");
  c->add_option("--stats", a.job.statsPath,
                "Write the stats JSON here (counters, pipeline counts, image_sha256 per image, timing)");
}

}  // namespace

void addRenderCommands(CLI::App& app) {
  auto* scenes = app.add_subcommand("scenes", "List the built-in scenes and the rule each one checks");
  scenes->callback([] {
    for (const scenes::SceneInfo& s : scenes::all())
      std::printf("%-16s %4dx%-4d  %s\n", std::string(s.name).c_str(), s.width, s.height, std::string(s.rule).c_str());
  });

  auto ra = std::make_shared<RenderArgs>();
  auto* render = app.add_subcommand("render", "Render a built-in scene on the oracle");
  render->add_option("scene", ra->target, "Scene name (see `tessera scenes`)")->required();
  addSizeOption(render, ra->size, "Target size WxH (default: the scene's own size)");
  render->add_option("--record", ra->job.recordPath, "Also record the frame as a .tframe file (replayable anywhere)");
  addJobOptions(render, *ra);
  render->callback([ra] {
    const scenes::SceneInfo* info = scenes::find(ra->target);
    int w = info ? info->width : 0, h = info ? info->height : 0;
    if (!ra->size.empty()) std::tie(w, h) = parseSize(ra->size, "--size");
    const CommandList list = scenes::build(ra->target, w, h);  // throws for unknown names
    FrameJob job = ra->job;
    job.name = ra->target;
    std::printf("%s\n", runFrame(list, job).dump(2).c_str());
  });

  auto rp = std::make_shared<RenderArgs>();
  auto* replay = app.add_subcommand("replay", "Render a recorded .tframe file on the oracle");
  replay->add_option("frame", rp->target, "A .tframe file written by `render --record`")->required();
  addJobOptions(replay, *rp);
  replay->callback([rp] {
    const CommandList list = readFrame(rp->target);
    FrameJob job = rp->job;
    job.name = rp->target;
    std::printf("%s\n", runFrame(list, job).dump(2).c_str());
  });

  struct ValidateArgs {
    std::string frame;
    ResourceLimits limits;
  };
  auto vp = std::make_shared<ValidateArgs>();
  auto* validateCmd = app.add_subcommand(
      "validate", "Check a .tframe file, its memory budget included, and list every problem found (exit 1 if any)");
  validateCmd->add_option("frame", vp->frame, "A .tframe file")->required();
  addMemoryBudgetOption(validateCmd, vp->limits);
  validateCmd->callback([vp] {
    const CommandList list = readFrame(vp->frame);
    const auto diags = validate(list, vp->limits);
    const char* name = vp->frame.c_str();
    for (const Diagnostic& d : diags)
      if (d.command < list.commands().size()) std::printf("%s: command %zu (%s): %s\n", name, d.command,
                  std::string(commandName(list.commands()[d.command].index())).c_str(), d.message.c_str());
    std::printf("%s: %zu commands, %zu problems\n", name, list.commands().size(), diags.size());
    if (!diags.empty()) throw CLI::RuntimeError(1);
  });
}

}  // namespace tessera::cli
