// `tessera mta build` / `tessera mta info`: the multiresolution texture atlas tree (mta/, docs/mta-build.md).
#include <sys/statvfs.h>

#include <cstdio>
#include <filesystem>
#include <memory>

#include "model/model.h"
#include "mta/build.h"
#include "mta/info.h"
#include "mta/paging_file.h"
#include "mta/scene.h"
#include "base/error.h"
#include "base/resource_limits.h"
#include "tools/cli/commands.h"
#include "tools/cli/options.h"

namespace tessera::cli {

namespace {

struct MtaBuildArgs {
  std::string scene, out;
  mta::BuildParams p;
  double memoryLimitGiB = 4.0;
  bool quiet = false, raw = false;
  uint64_t maxOutput = 0;  // --max-output; 0: not given (the default is derived from the free space)
  uint64_t fit = 0;        // --fit; 0: not given
  ResourceLimits limits;   // the model budgets (--model-budget-*)
};

// Without --max-output: at most 8 GiB, and never more than the free space where the output goes (a build
// that fills the disk fails after hours and takes other work down with it). With --fit the size asked
// for bounds the tree already, so only the free space applies.
constexpr uint64_t kDefaultMaxOutput = uint64_t(8) << 30;

mta::OutputGuard outputGuard(const MtaBuildArgs& a) {
  mta::OutputGuard g;
  g.fitBytes = a.fit;
  if (a.maxOutput) {
    g.maxBytes = a.maxOutput;
    return g;
  }
  std::filesystem::path dir = std::filesystem::path(a.out).parent_path();
  if (dir.empty()) dir = ".";
  struct statvfs st{};
  // An output directory that cannot be queried (it may not exist) keeps 8 GiB; creating the file then
  // fails with its own message.
  const bool known = ::statvfs(dir.c_str(), &st) == 0;
  const uint64_t freeBytes = known ? uint64_t(st.f_bavail) * st.f_frsize : UINT64_MAX;
  const uint64_t cap = a.fit ? UINT64_MAX : kDefaultMaxOutput;
  g.maxBytes = std::min(cap, freeBytes);
  if (freeBytes < cap)
    g.maxReason = " (the free space in " + dir.string() + "; without --max-output the limit is the smaller of " +
                  (a.fit ? std::string("--fit's size") : formatBytes(kDefaultMaxOutput)) + " and the free space)";
  else
    g.maxReason = " (the default; the free space in " + dir.string() + " is " +
                  (known ? formatBytes(freeBytes) : std::string("unknown")) + ")";
  return g;
}

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
  addByteSizeOption(build, "--max-output", a->maxOutput,
                    "Largest file the build may write; a larger plan stops before writing, exit 2, naming a d_min "
                    "that fits (default: the smaller of 8 GiB and the free space in the output's directory)");
  auto* fitOpt = addByteSizeOption(build, "--fit", a->fit,
                                   "Choose d_min: the finest one (on a grid of two significant digits, from D / "
                                   "--d-min-divisor up) whose file fits this size; excludes --d-min");
  build->add_flag("--quiet", a->quiet, "No progress on stderr");
  build->add_flag("--raw", a->raw,
                  "Store raw RGB / RGBA8 texels instead of S3TC mip chains (BC1 for the RGB tree, BC3 for the RGBA "
                  "tree), for comparison");
  build->footer(
      "Before it creates the output, the build plans the whole tree (image headers only) and computes the file's\n"
      "exact size: 128-byte header + every atlas (the BC1 / BC3 mip chain of an A x A atlas per node and layer,\n"
      "or A x A x 3 or 4 bytes with --raw) and every block of original images, each padded to 16 bytes, + the\n"
      "metadata (nodes, geometry, tables). A plan over --max-output stops within seconds with exit 2 and no\n"
      "file, naming the size, the nodes and a d_min that fits. --fit SIZE searches that d_min itself by bisection over plans (same inputs, same choice) and\n"
      "reports it in build.fit of the JSON. Progress (unless --quiet) shows the file written of the total, and\n"
      "the time left. docs/mta-build.md");
  build->callback([a, fitOpt, build] {
    if (fitOpt->count() && build->get_option("--d-min")->count())
      throw Error("mta build: --fit chooses d_min itself; do not pass --d-min as well (--d-min-divisor sets the finest "
                  "d_min --fit may choose)");
    a->p.memoryLimit = uint64_t(a->memoryLimitGiB * double(1ull << 30));
    a->p.progress = !a->quiet;
    a->p.encoding = a->raw ? mta::BlockEncoding::Raw : mta::BlockEncoding::S3tc;
    a->p.validate();
    auto model = std::make_shared<const model::Model>(model::loadModel(a->scene, a->limits));
    const mta::Scene scene = mta::sceneFromModel(model);
    const mta::OutputGuard guard = outputGuard(*a);
    const mta::BuildReport r = mta::buildMta(scene, a->p, a->out, guard);
    mta::PagingFile f(a->out);
    nlohmann::json j = mta::describe(f);
    j["build"] = {{"seconds", r.seconds},
                  {"peak_resident_bytes", r.peakResidentBytes},
                  {"images_decoded", r.imagesDecoded},
                  {"plan_seconds", r.planSeconds},
                  {"estimated_bytes", r.estimate.totalBytes},
                  {"max_output_bytes", guard.maxBytes}};
    if (guard.fitBytes)
      j["build"]["fit"] = {{"size_bytes", guard.fitBytes},
                           {"d_min", r.fitDMin},
                           {"plans", r.fitPlans},
                           {"next_finer_d_min", r.fitFinerDMin},
                           {"next_finer_bytes", r.fitFinerBytes}};
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
