// `gl-dump` (hidden) and the child processes of `tessera crosscheck --stability` (stability_run.h).
#include <sched.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>

#include "base/atomic_file.h"
#include "base/error.h"
#include "gl/gl_backend.h"
#include "raster/serialize.h"
#include "tools/cli/gl_options.h"
#include "tools/cli/options.h"
#include "tools/cli/stability_run.h"
#include "tools/scenes/scenes.h"
#include "verify/expectations.h"
#include "verify/stability.h"

namespace tessera::cli {

namespace fs = std::filesystem;

namespace {

// A scene name or a .tframe path (as `crosscheck` loads it).
CommandList loadDumpFrame(const std::string& what, const std::string& size) {
  if (const scenes::SceneInfo* s = scenes::find(what)) {
    int w = s->width, h = s->height;
    if (!size.empty()) std::tie(w, h) = parseSize(size, "--size");
    return scenes::build(what, w, h);
  }
  if (what.ends_with(".tframe")) return readFrame(what);
  return scenes::build(what, 1, 1);  // throws "unknown scene ... (known: ...)"
}

// Keeps the commands through draw `draw` (its Draw command included).
void truncateThroughDraw(CommandList& list, size_t draw) {
  size_t seen = 0;
  for (size_t i = 0; i < list.commands().size(); ++i)
    if (std::holds_alternative<Draw>(list.commands()[i]) && seen++ == draw) {
      list.truncate(i + 1);
      return;
    }
}

struct DumpArgs {
  std::string frame, size, out;
  int runs = 1;
  int64_t throughDraw = -1;
  bool strict = false, oneCpu = false;
  ResourceLimits limits;
  gl::GlOptions gl;  // --gl-driver, --gl-version, --egl-platform, passed on by the parent
};

void runDump(const DumpArgs& a) {
  if (a.oneCpu) {
    // Before GL starts: Mesa counts the CPUs it may use when the display initialises, and its
    // rasterizer threads inherit this mask.
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) != 0) throw Error("gl-dump --one-cpu: sched_getaffinity failed");
    int first = -1;
    for (int c = 0; c < CPU_SETSIZE && first < 0; ++c)
      if (CPU_ISSET(c, &set)) first = c;
    CPU_ZERO(&set);
    CPU_SET(first, &set);
    if (sched_setaffinity(0, sizeof set, &set) != 0) throw Error("gl-dump --one-cpu: sched_setaffinity failed");
  }
  CommandList list = loadDumpFrame(a.frame, a.size);
  if (a.throughDraw >= 0) truncateThroughDraw(list, size_t(a.throughDraw));
  gl::GlOptions go = a.gl;
  go.strict = a.strict;
  go.limits = a.limits;
  auto gl = gl::GlBackend::create(go);
  size_t images = 0;
  for (int r = 0; r < a.runs; ++r) {
    gl->execute(list, a.frame);
    const auto presented = gl->presented();
    images = presented.size();
    for (size_t i = 0; i < presented.size(); ++i) {
      const std::vector<uint8_t> px = gl->readImage(presented[i]);
      writeFileAtomically((fs::path(a.out) / ("run" + std::to_string(r) + "_img" + std::to_string(i) + ".bin")).string(),
                          std::span<const uint8_t>(px));
    }
  }
  const nlohmann::json done = {{"runs", a.runs}, {"images", images}, {"gl_info", gl->info().toJson()}};
  writeFileAtomically((fs::path(a.out) / "done.json").string(), std::string_view(done.dump()));
}

std::vector<uint8_t> readBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw Error(p.string() + ": cannot read a stability child's image");
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

// One child per call: /proc/self/exe gl-dump ... with the condition's environment.
verify::GlRuns renderInChild(const std::string& frame, const std::string& size, const ResourceLimits& limits,
                             const gl::GlOptions& glBase, const verify::StabilityCondition& c,
                             std::optional<size_t> throughDraw) {
  std::string tmpl = (fs::temp_directory_path() / "tessera-stability-XXXXXX").string();
  if (!mkdtemp(tmpl.data())) throw Error("stability: cannot create a temporary directory under " + tmpl);
  const fs::path dir = tmpl;
  std::vector<std::string> args = {"tessera", "gl-dump", frame, "--out", dir.string(), "--runs", std::to_string(c.runs),
                                   "--memory-budget", std::to_string(limits.frameBytes)};
  if (!size.empty()) args.insert(args.end(), {"--size", size});
  if (throughDraw) args.insert(args.end(), {"--through-draw", std::to_string(*throughDraw)});
  // Every condition runs the implementation and GL path that the parent cross-checks.
  if (!glBase.driver.empty()) args.insert(args.end(), {"--gl-driver", glBase.driver});
  if (glBase.glVersion != 0) args.insert(args.end(), {"--gl-version", std::to_string(glBase.glVersion)});
  if (!glBase.eglPlatform.empty()) args.insert(args.end(), {"--egl-platform", glBase.eglPlatform});
  if (c.strict) args.push_back("--strict");
  if (c.oneCpu) args.push_back("--one-cpu");
  std::vector<char*> argv;
  for (std::string& s : args) argv.push_back(s.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw Error("stability: fork failed");
  if (pid == 0) {
    for (const auto& [k, v] : c.env) setenv(k.c_str(), v.c_str(), 1);
    execv("/proc/self/exe", argv.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw Error("stability: waitpid failed");
  }
  std::error_code ec;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !fs::exists(dir / "done.json")) {
    fs::remove_all(dir, ec);
    throw Error("stability: condition " + c.name + ": the child `tessera gl-dump` failed (status " +
                std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
  }
  const nlohmann::json done = nlohmann::json::parse(readBytes(dir / "done.json"));
  verify::GlRuns runs(done["runs"].get<size_t>());
  for (size_t r = 0; r < runs.size(); ++r)
    for (size_t i = 0; i < done["images"].get<size_t>(); ++i)
      runs[r].push_back(readBytes(dir / ("run" + std::to_string(r) + "_img" + std::to_string(i) + ".bin")));
  fs::remove_all(dir, ec);
  return runs;
}

int visibleCpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  return sched_getaffinity(0, sizeof set, &set) == 0 ? std::max(1, CPU_COUNT(&set)) : 1;
}

}  // namespace

void addGlDumpCommand(CLI::App& app) {
  auto a = std::make_shared<DumpArgs>();
  auto* cmd = app.add_subcommand("gl-dump", "Internal: the child process of `crosscheck --stability`");
  cmd->group("");  // hidden from --help: not a user command
  cmd->add_option("frame", a->frame, "Scene name or .tframe file")->required();
  cmd->add_option("--out", a->out, "Directory for run<r>_img<i>.bin and done.json")->required();
  addSizeOption(cmd, a->size, "Target size WxH for scenes");
  cmd->add_option("--runs", a->runs, "Renders in this process")->check(CLI::Range(1, 16));
  cmd->add_option("--through-draw", a->throughDraw, "Render the prefix through this draw only")->check(CLI::NonNegativeNumber);
  cmd->add_flag("--strict", a->strict, "llvmpipe fast paths off");
  cmd->add_flag("--one-cpu", a->oneCpu, "Restrict this process to one CPU before GL starts");
  addMemoryBudgetOption(cmd, a->limits);
  addGlBackendOptions(cmd, a->gl);
  cmd->callback([a] { runDump(*a); });
}

nlohmann::json runStability(const std::string& frame, const std::string& size, const CommandList& list,
                            const std::vector<size_t>& pixelsPerImage, const ResourceLimits& limits,
                            const gl::GlOptions& glBase) {
  const int cpus = visibleCpus();
  const auto conditions = verify::stabilityConditions(cpus);
  nlohmann::json j = verify::checkStability(
      list, conditions,
      [&](const verify::StabilityCondition& c, std::optional<size_t> throughDraw) {
        return renderInChild(frame, size, limits, glBase, c, throughDraw);
      },
      pixelsPerImage);
  j["cpus"] = cpus;
  return j;
}

}  // namespace tessera::cli
