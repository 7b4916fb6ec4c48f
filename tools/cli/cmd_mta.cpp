// `tessera mta build` / `tessera mta info`: the multiresolution texture atlas tree (mta/, docs/mta-build.md).
#include <cstdio>
#include <memory>

#include "model/model.h"
#include "mta/build.h"
#include "mta/info.h"
#include "mta/paging_file.h"
#include "mta/scene.h"
#include "base/error.h"
#include "tools/cli/commands.h"
#include "tools/cli/options.h"

namespace tessera::cli {

namespace {

struct MtaBuildArgs {
  std::string scene, out;
  mta::BuildParams p;
  double memoryLimitGiB = 4.0;
  bool quiet = false;
  ResourceLimits limits;  // the model budgets (--model-budget-*)
};

void printSummary(const nlohmann::json& j) {
  for (const auto& t : j["trees"])
    std::fprintf(stderr, "%s tree: depth %d, %d nodes, %d leaves, leaf coverage mean %.1f%% min %.1f%%\n",
                 t["kind"].get<std::string>().c_str(), t["depth"].get<int>(), t["nodes"].get<int>(), t["leaves"].get<int>(),
                 100.0 * t["leaf_atlas_coverage_mean"].get<double>(), 100.0 * t["leaf_atlas_coverage_min"].get<double>());
  std::fprintf(stderr, "d_min used %.6g (requested %.6g); critical triangles %llu -> %llu split (+%llu triangles); %.1f MiB\n",
               j["d_min_used"].get<double>(), j["d_min_requested"].get<double>(),
               (unsigned long long)j["critical_triangles"]["at_requested_d_min"].get<uint64_t>(),
               (unsigned long long)j["critical_triangles"]["at_used_d_min"].get<uint64_t>(),
               (unsigned long long)j["critical_triangles"]["triangles_added_by_splitting"].get<uint64_t>(),
               j["file_bytes"].get<double>() / 1048576.0);
}

}  // namespace

void addMtaCommands(CLI::App& app) {
  auto* mtaCmd = app.add_subcommand("mta", "Multiresolution texture atlas tree (Buchholz & Döllner): build a paging file, describe one");
  mtaCmd->require_subcommand(1);
  auto a = std::make_shared<MtaBuildArgs>();
  auto* build = mtaCmd->add_subcommand("build", "Build an atlas tree paging file from a model (glTF, OBJ, Assimp formats); prints info JSON");
  build->add_option("scene", a->scene, "Model file")->required();
  build->add_option("-o,--output", a->out, "Output paging file (.mta)")->required();
  addRealOption(build, "--d-min", a->p.dMin,
                "Minimum distance d_min in scene units (default 0: scene diagonal / --d-min-divisor)", kNonNegative);
  addRealOption(build, "--d-min-divisor", a->p.dMinDivisor, "k in d_min = D / k", kPositive)->capture_default_str();
  addRealOption(build, "--tau", a->p.tau, "Pixel-per-texel ratio", kPositive)->capture_default_str();
  build->add_option("--atlas-size", a->p.atlasSize, "Atlas size A (power of two)")->capture_default_str();
  build->add_option("--border", a->p.border, "Texture border in texels")->capture_default_str();
  addRealOption(build, "--fov", a->p.fovDegrees, "Horizontal field of view in degrees", {0.0, 180.0, true, true})
      ->capture_default_str();
  addRealOption(build, "--tan-half-fov", a->p.tanHalfFov, "tan(fov/2) given directly (overrides --fov)", kPositive);
  build->add_option("--screen-width", a->p.screenWidth, "Screen width in pixels")->capture_default_str();
  addRealOption(build, "--critical-threshold", a->p.criticalThreshold,
                "Raise d_min when more than this fraction of triangles is critical", {0.0, 1.0, false, false})
      ->capture_default_str();
  // Up to 1 PiB: GiB * 2^30 stays far inside 64 bits.
  addRealOption(build, "--memory-limit", a->memoryLimitGiB, "Peak resident memory in GiB (0 = unchecked)",
                {0.0, 1048576.0, false, false})
      ->capture_default_str();
  addThreadsOption(build, a->p.threads, "Worker threads; the bytes never depend on it");
  addModelBudgetOptions(build, a->limits);
  build->add_flag("--quiet", a->quiet, "No progress on stderr");
  build->callback([a] {
    a->p.memoryLimit = uint64_t(a->memoryLimitGiB * double(1ull << 30));
    a->p.progress = !a->quiet;
    a->p.validate();
    auto model = std::make_shared<const model::Model>(model::loadModel(a->scene, a->limits));
    const mta::Scene scene = mta::sceneFromModel(model);
    const mta::BuildReport r = mta::buildMta(scene, a->p, a->out);
    mta::PagingFile f(a->out);
    nlohmann::json j = mta::describe(f);
    j["build"] = {{"seconds", r.seconds}, {"peak_resident_bytes", r.peakResidentBytes}, {"images_decoded", r.imagesDecoded}};
    std::printf("%s\n", j.dump(2).c_str());
    if (!a->quiet) printSummary(j);
  });
  auto info = std::make_shared<std::pair<std::string, bool>>();
  auto* infoCmd = mtaCmd->add_subcommand("info", "Validate a paging file and print its structure as JSON (summary on stderr)");
  infoCmd->add_option("file", info->first, "Paging file")->required();
  infoCmd->add_flag("--verify", info->second, "Also read every block and check its SHA-256");
  infoCmd->callback([info] {
    mta::PagingFile f(info->first);
    const nlohmann::json j = mta::describe(f, info->second);
    std::printf("%s\n", j.dump(2).c_str());
    printSummary(j);
  });
  // In this order, as --help lists them: mta render, mta runs, then the top-level texel.
  addMtaRenderCommand(mtaCmd);
  addMtaRunsCommand(mtaCmd);
  addTexelCommand(app);
}

}  // namespace tessera::cli
