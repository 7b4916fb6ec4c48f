// `tessera suite run | merge`: corpus runs of many cases, sharded across machines (docs/suite.md).
//
// `run` reads a suite (suite_spec.h), keeps the --fraction K/M shard, runs its cases as child processes
// (suite_run.h) and writes results.json, junit.xml and index.html (suite_results.h); exit 0 only when
// every result is a pass or expected, 1 otherwise, 2 for bad input. `merge` joins the outputs of the
// shards and checks that every case ran exactly once.
// The hidden `suite _case` is a deliberately misbehaving case for the tests (crash, hang, fail once,
// out of memory); it is no user command and stays out of --help.
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <thread>
#include <vector>

#include "base/atomic_file.h"
#include "base/error.h"
#include "tools/cli/commands.h"
#include "tools/cli/output_directory.h"
#include "tools/cli/suite_results.h"
#include "tools/cli/suite_run.h"
#include "tools/cli/suite_spec.h"

namespace tessera::cli {

namespace {

struct SuiteRunArgs {
  std::string suiteFile, backends = "cpu,gl", glDriver, fraction = "1/1", baseline, flakes, outDir;
  int jobs = 1;
  bool quiet = false, list = false;
};

int finish(const std::string& dir, const suite::RunInfo& run, const std::vector<suite::CaseResult>& results) {
  suite::writeRunOutputs(dir, run, results);
  const nlohmann::json j = suite::resultsJson(run, results);
  std::printf("%s\n", j["summary"].dump(2).c_str());
  std::fprintf(stderr, "suite: wrote %s/results.json, junit.xml and index.html\n", dir.c_str());
  return j["summary"]["all_pass_or_expected"].get<bool>() ? 0 : 1;
}

void runSuite(const SuiteRunArgs& a) {
  if (!a.list && a.outDir.empty()) throw Error("suite run: -o DIR is required (or --list)");
  if (a.backends != "cpu" && a.backends != "cpu,gl")
    throw Error("--backends '" + a.backends +
                "': expected cpu,gl (every case) or cpu (leave out the cases that need GL)");
  const suite::Fraction fraction = suite::parseFraction(a.fraction);
  suite::LoadOptions lo;
  lo.gl = a.backends == "cpu,gl";
  lo.glDriver = a.glDriver;
  const suite::Suite s = suite::loadSuite(a.suiteFile, lo);
  if (a.list) {
    // The shard's cases as they would run, without running them (and without -o).
    nlohmann::json j = nlohmann::json::array();
    for (const suite::SuiteCase& c : suite::selectFraction(s.cases, fraction))
      j.push_back(
          {{"index", c.index}, {"name", c.name}, {"kind", c.kind}, {"needs_gl", c.needsGl}, {"steps", c.steps}});
    std::printf("%s\n", j.dump(2).c_str());
    return;
  }
  std::optional<suite::Baseline> baseline;
  std::optional<suite::FlakeList> flakes;
  if (!a.baseline.empty()) baseline = suite::loadBaseline(a.baseline);
  if (!a.flakes.empty()) flakes = suite::loadFlakes(a.flakes);
  prepareOutputDirectory(a.outDir, "-o");
  const std::vector<suite::SuiteCase> mine = suite::selectFraction(s.cases, fraction);
  suite::RunInfo run{s.name, a.suiteFile, s.sha256, a.backends, a.glDriver, fraction.text(), s.cases.size(), {}};
  for (const suite::SuiteCase& c : s.cases) run.allCaseNames.push_back(c.name);
  if (!a.quiet)
    std::fprintf(stderr, "suite %s: %zu of %zu cases (fraction %s), %d jobs, into %s\n", s.name.c_str(), mine.size(),
                 s.cases.size(), fraction.text().c_str(), a.jobs, a.outDir.c_str());
  suite::RunOptions ro;
  ro.jobs = a.jobs;
  ro.outDir = a.outDir;
  ro.glDriver = a.glDriver;
  ro.baseline = baseline ? &*baseline : nullptr;
  ro.flakes = flakes ? &*flakes : nullptr;
  ro.progress = !a.quiet;
  const std::vector<suite::CaseResult> results = suite::runCases(mine, ro);
  if (int rc = finish(a.outDir, run, results)) throw CLI::RuntimeError(rc);
}

// The misbehaving case of the tests. Modes: pass, fail, crash (abort: SIGABRT, which the sanitizers
// do not intercept), hang (sleeps an hour), fail-once (fails while --state does not exist, creating
// it), oom (allocates and touches 64 MiB blocks until allocation fails).
void testCase(const std::string& mode, const std::string& state) {
  if (mode == "pass") {
    std::printf("{\"unexplained\": 0, \"exact_match_percent\": 100.0}\n");
  } else if (mode == "fail") {
    std::printf("{\"unexplained\": 7, \"exact_match_percent\": 99.5}\n");
    throw CLI::RuntimeError(1);
  } else if (mode == "crash") {
    std::fflush(stdout);
    // No core file: this crash is the test's intent, and on a machine with `ulimit -c unlimited` each
    // one would leave a core of the whole process in the case's directory.
    const rlimit noCore{0, 0};
    ::setrlimit(RLIMIT_CORE, &noCore);
    std::abort();
  } else if (mode == "hang") {
    std::this_thread::sleep_for(std::chrono::hours(1));
  } else if (mode == "fail-once") {
    if (state.empty()) throw Error("suite _case --mode fail-once needs --state FILE");
    if (!std::filesystem::exists(state)) {
      writeFileAtomically(state, std::string("failed once\n"));
      throw CLI::RuntimeError(1);
    }
    std::printf("{\"unexplained\": 0}\n");
  } else if (mode == "oom") {
    std::vector<std::unique_ptr<char[]>> blocks;
    for (int i = 0; i < 1 << 16; ++i) {
      blocks.emplace_back(new char[size_t(64) << 20]);
      std::memset(blocks.back().get(), 1, size_t(64) << 20);
    }
  } else {
    throw Error("suite _case --mode '" + mode + "': unknown");
  }
}

}  // namespace

void addSuiteCommands(CLI::App& app) {
  auto* cmd = app.add_subcommand("suite",
                                 "Run a suite of cases (scenes, frames, cross-checks, goldens, model frame sets) "
                                 "as child processes, sharded with --fraction; merge shards (docs/suite.md)");
  cmd->require_subcommand(1);
  auto a = std::make_shared<SuiteRunArgs>();
  auto* run = cmd->add_subcommand(
      "run",
      "Run the cases of SUITE.json (or shard K of M of them) in --jobs child processes, each with a timeout; retry a\n"
      "failing case once (a pass then is a flake); write results.json, junit.xml and index.html to -o DIR.\n"
      "Exit 0 when every result is a pass or expected (baseline, known flakes), 1 otherwise, 2 on bad input.");
  run->add_option("suite", a->suiteFile, "The suite file (docs/suite.md; suites/smoke.json, suites/full.json)")
      ->required();
  run->add_option("--backends", a->backends, "cpu,gl (every case) or cpu (leave out the cases that need GL)")
      ->capture_default_str();
  run->add_option("--gl-driver", a->glDriver, "Passed to every case that runs GL: llvmpipe, softpipe or zink");
  run->add_option("--jobs,-j", a->jobs, "Cases run at once (1..256)")->check(CLI::Range(1, 256))->capture_default_str();
  run->add_option("--fraction", a->fraction,
                  "K/M: run every M-th case starting at the K-th (K from 1 to M, as GitLab's CI_NODE_INDEX)")
      ->capture_default_str();
  run->add_option("--baseline", a->baseline, "Expected failures (docs/suite.md: the expectations file's layout)");
  run->add_option("--flakes", a->flakes, "Known flaky cases: one regular expression over whole case names per line");
  auto* outOpt = run->add_option("-o,--output", a->outDir, "Output directory (required unless --list)");
  run->add_flag("--quiet", a->quiet, "No progress lines on stderr");
  run->add_flag("--list", a->list, "Print the shard's cases (name, kind, command lines) as JSON and run nothing")
      ->excludes(outOpt);
  run->callback([a] { runSuite(*a); });

  struct MergeArgs {
    std::vector<std::string> dirs;
    std::string outDir;
  };
  auto m = std::make_shared<MergeArgs>();
  auto* merge = cmd->add_subcommand(
      "merge",
      "Join the output directories of the shards of one run into one results.json, junit.xml and index.html;\n"
      "exit 2 naming every case that is missing or ran more than once, else as `suite run`");
  merge->add_option("dirs", m->dirs, "The shards' output directories")->required();
  merge->add_option("-o,--output", m->outDir, "Output directory")->required();
  merge->callback([m] {
    prepareOutputDirectory(m->outDir, "-o");
    const auto [info, results] = suite::mergeShards(m->dirs, m->outDir);
    if (int rc = finish(m->outDir, info, results)) throw CLI::RuntimeError(rc);
  });

  auto mode = std::make_shared<std::pair<std::string, std::string>>();
  auto* tc = cmd->add_subcommand("_case", "A misbehaving case for the tests of `tessera suite`");
  tc->group("");  // hidden from --help: not a user command
  tc->add_option("--mode", mode->first)->required();
  tc->add_option("--state", mode->second);
  tc->callback([mode] { testCase(mode->first, mode->second); });
}

}  // namespace tessera::cli
