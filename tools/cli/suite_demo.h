// The corpus-run part of `tessera demo`: the CPU cases of suites/smoke.json (every scene rendered, and
// visibility where the frame allows it) run by `tessera suite`'s runner in child processes, with the
// summary page under OUT/suite/. The GL cross-checks of the smoke suite are left out: the demo's scene
// table already cross-checks every scene, and leaving them out keeps this part under a minute (60 s
// measured under load on 2 cores).
// Returns the report JSON (the suite summary) and an HTML section linking the summary page.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace tessera::cli {

struct SuiteDemoResult {
  nlohmann::json report;
  std::string html;
  bool allPassOrExpected = false;
};

// Throws Error naming the file when the suite is missing or malformed.
SuiteDemoResult runSuiteDemo(const std::string& outDir, const std::string& suitePath);

}  // namespace tessera::cli
