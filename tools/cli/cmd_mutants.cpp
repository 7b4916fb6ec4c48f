// `tessera mutants`: mutation testing of the cross-check (docs/mutants.md). Every mutant of
// gl/gl_mutation.h runs on every chosen scene through one GL backend; the verdict must catch each
// mutant that GL does not allow, and must raise no alarm on the unmodified backend.
#include <cstdio>
#include <memory>
#include <sstream>

#include "gl/gl_backend.h"
#include "gl/gl_mutation.h"
#include "tools/cli/commands.h"
#include "tools/cli/options.h"
#include "tools/cli/output_directory.h"
#include "tools/scenes/scenes.h"
#include "verify/mutants.h"

namespace tessera::cli {

namespace {

struct MutantsArgs {
  std::string scenes, mutants, report;
  int threads = 0;
  bool strict = false, list = false;
  ResourceLimits limits;
};

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

void listCatalogue() {
  nlohmann::json j = nlohmann::json::array();
  for (const gl::Mutation& m : gl::mutationCatalogue()) {
    nlohmann::json e = {{"name", m.name}, {"imitates", m.imitates}, {"kind", m.kind}, {"change", m.change}};
    if (!m.equivalent.empty()) e["equivalence_argument"] = m.equivalent;
    j.push_back(e);
  }
  std::printf("%s\n", j.dump(2).c_str());
}

void runMutantsCommand(const MutantsArgs& a) {
  if (a.list) return listCatalogue();
  std::vector<const gl::Mutation*> mutations;
  if (a.mutants.empty()) {
    for (const gl::Mutation& m : gl::mutationCatalogue()) mutations.push_back(&m);
  } else {
    for (const std::string& name : splitList(a.mutants)) {
      const gl::Mutation* m = gl::findMutation(name);
      if (m == nullptr) {
        std::string known;
        for (const gl::Mutation& k : gl::mutationCatalogue())
          known += (known.empty() ? "" : ", ") + std::string(k.name);
        throw Error("--mutants: unknown mutant '" + name + "' (known: " + known + ")");
      }
      mutations.push_back(m);
    }
  }
  std::vector<std::string> names;
  if (a.scenes.empty()) {
    for (const scenes::SceneInfo& s : scenes::all()) names.emplace_back(s.name);
  } else {
    names = splitList(a.scenes);
  }
  std::vector<verify::MutantFrame> frames;
  for (const std::string& n : names) {
    const scenes::SceneInfo* s = scenes::find(n);
    if (s == nullptr) scenes::build(n, 1, 1);  // throws "unknown scene ... (known: ...)"
    frames.push_back({n, scenes::build(n, s->width, s->height)});
  }
  if (!a.report.empty()) prepareOutputDirectory(a.report, "--report");

  gl::GlOptions go;
  go.strict = a.strict;
  if (a.threads > 0) go.lpThreads = a.threads;
  go.limits = a.limits;
  auto glb = gl::GlBackend::create(go);
  verify::MutantsOptions o;
  o.threads = a.threads;
  o.limits = a.limits;
  o.progress = [](const std::string& line) { std::fprintf(stderr, "mutants: %s\n", line.c_str()); };
  verify::MutantsResult r = verify::runMutants(frames, mutations, *glb, o);
  r.json["gl_info"] = glb->info().toJson();
  r.json["strict"] = a.strict;
  if (!a.report.empty()) verify::writeMutantsReport(r, a.report);
  std::printf("%s\n", r.json.dump(2).c_str());
  if (!r.passed()) throw CLI::RuntimeError(1);
}

}  // namespace

void addMutantsCommand(CLI::App& app) {
  auto a = std::make_shared<MutantsArgs>();
  auto* cmd = app.add_subcommand(
      "mutants",
      "Mutation testing of the cross-check: render each scene once on the oracle (with provenance), then on OpenGL\n"
      "unmodified and once per mutant - a deliberate, realistic driver fault (a small change to a GLSL twin or to\n"
      "GL state, gl/gl_mutation.cpp) - and judge every GL image as `crosscheck` does. A scene kills a mutant when\n"
      "the mutant leaves a pixel unexplained that the unmodified backend does not. Prints JSON: every mutant with\n"
      "what it imitates, its status (killed | survived | equivalent: catalogued with an argument that GL allows\n"
      "it), the scenes that killed it and its unexplained pixels per scene; false_alarms (unexplained pixels of the\n"
      "unmodified backend), killed_percent and runtime_seconds. Progress goes to stderr. Exit 1 when a\n"
      "non-equivalent mutant survives, an equivalent one is killed (the verdict rejects what GL allows), or the\n"
      "unmodified backend raises a false alarm. `crosscheck --mutant NAME` shows one kill pixel by pixel.\n"
      "See docs/mutants.md.");
  cmd->add_option("--scenes", a->scenes, "Comma-separated built-in scenes (default: every scene of `tessera scenes`)");
  cmd->add_option("--mutants", a->mutants,
                  "Comma-separated mutant names (default: the whole catalogue; --list shows it)");
  cmd->add_option("--report", a->report, "Write report.json and index.html (the mutant x scene table) here");
  cmd->add_flag("--list", a->list, "Print the catalogue (name, imitates, kind, change, equivalence argument) and exit");
  addThreadsOption(cmd, a->threads, "Oracle threads, and LP_NUM_THREADS for llvmpipe when > 0");
  addMemoryBudgetOption(cmd, a->limits);
  cmd->add_flag("--strict", a->strict,
                "Switch off llvmpipe fast paths that do not change GL semantics (as crosscheck)");
  cmd->callback([a] { runMutantsCommand(*a); });
}

}  // namespace tessera::cli
