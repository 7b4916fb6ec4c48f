// Running the cases of a suite as child processes of the `tessera` executable (docs/suite.md).
//
// Implements: up to --jobs cases at once, each step a fork + exec of /proc/self/exe in its own process
// group with stdout / stderr captured to files of the case's directory (cases/<name>/), an optional
// RLIMIT_AS per step, a per-case timeout that kills the whole process group, the classification of how
// a step ended (exit 0 pass, another exit status fail, exit 3 or a signal crash, the timeout timeout),
// one retry of a failing case (pass then = flake), the baseline's expected failures and unexpected
// passes, the key figures of the last step's stdout, and progress lines on stderr. Results come back in
// case order whatever the completion order. SIGINT / SIGTERM kill every running case before the runner
// dies of the same signal.
// Does not implement: reading the suite (suite_spec.h) or writing results (suite_results.h).
#pragma once

#include <string>
#include <vector>

#include "tools/cli/suite_results.h"
#include "tools/cli/suite_spec.h"

namespace tessera::cli::suite {

struct RunOptions {
  int jobs = 1;
  std::string outDir;    // cases go to <outDir>/cases/<name>/
  std::string glDriver;  // for the baseline's condition
  const Baseline* baseline = nullptr;
  const FlakeList* flakes = nullptr;
  bool progress = true;  // a line per finished case on stderr
};

std::vector<CaseResult> runCases(const std::vector<SuiteCase>& cases, const RunOptions& options);

}  // namespace tessera::cli::suite
