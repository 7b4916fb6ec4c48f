// `tessera golden check | update`: the golden images under golden/ (golden/golden_run.h does the work).
//
// golden/manifest.json maps each test name to one image file (golden/manifest.h). `check` re-renders
// every scene and the atlas tree frames and demands bit-exact pixels (exit 1 on any difference or stale
// entry); `update` rewrites the images and the manifest and prints what changed. `check --simd T` runs
// the sampler's SIMD kernel on target T (raster/sample_simd.h), so every target can be checked.
#include <cstdio>
#include <memory>
#include <string>

#include "golden/golden_run.h"
#include "raster/simd_targets.h"
#include "tools/cli/commands.h"
#include "tools/cli/repo_paths.h"
#include "tools/scenes/scene_goldens.h"

namespace tessera::cli {

namespace {

int runGolden(const golden::GoldenOptions& o, bool update) {
  const golden::GoldenReport r = update ? golden::updateGoldens(o) : golden::checkGoldens(o);
  std::printf("%s\n", r.toJson().dump(2).c_str());
  if (update) {
    for (const golden::GoldenChange& c : r.changed)
      std::fprintf(stderr, "golden: %s changed (%s -> %s)\n", c.test.c_str(), c.oldSha256.substr(0, 12).c_str(),
                   c.newSha256.substr(0, 12).c_str());
    return 0;
  }
  return r.passedAll() ? 0 : 1;
}

}  // namespace

void addGoldenCommands(CLI::App& app) {
  auto* golden = app.add_subcommand("golden", "Check or regenerate the golden images (golden/manifest.json)");
  golden->require_subcommand(1);
  auto a = std::make_shared<golden::GoldenOptions>();
  a->sceneImages = scenes::allSceneImages();
  auto* check =
      golden->add_subcommand("check", "Re-render every scene; demand bit-exact pixels (exit 1 on any difference)");
  check->add_option("--dir", a->dir, "Golden directory")->capture_default_str();
  check->add_option("--railway", a->railway, "railway.glb, the real scene of the atlas tree goldens (data/README.md)")
      ->capture_default_str();
  auto simd = std::make_shared<std::string>("best");
  check
      ->add_option("--simd", *simd,
                   "Target of the sampler's SIMD kernel: best, avx3, avx2, sse4, ssse3 or scalar (those this build "
                   "and CPU have), or reference (the scalar filter only). Every one must give the same bytes")
      ->capture_default_str();
  // The defaults are repository paths: found from the clone's root or beside the build folder.
  check->callback([a, simd] {
    a->dir = repoPath(a->dir), a->railway = repoPath(a->railway);
    simd::forceTarget(*simd);  // Error (exit 2) naming the available targets
    std::fprintf(stderr, "golden: sampler SIMD target %s\n", simd::activeTarget().c_str());
    if (int rc = runGolden(*a, false)) throw CLI::RuntimeError(rc);
  });
  auto* update = golden->add_subcommand("update", "Regenerate golden images and the manifest; print what changed");
  update->add_option("--dir", a->dir, "Golden directory")->capture_default_str();
  update->add_option("--railway", a->railway, "railway.glb, the real scene of the atlas tree goldens (data/README.md)")
      ->capture_default_str();
  update->add_flag("--only-failing", a->onlyFailing, "Rewrite only the images that no longer match");
  update->callback([a] {
    a->dir = repoPath(a->dir), a->railway = repoPath(a->railway);
    runGolden(*a, true);
  });
}

}  // namespace tessera::cli
