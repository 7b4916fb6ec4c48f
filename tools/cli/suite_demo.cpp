#include "tools/cli/suite_demo.h"

#include <fmt/format.h>

#include "tools/cli/output_directory.h"
#include "tools/cli/suite_results.h"
#include "tools/cli/suite_run.h"
#include "tools/cli/suite_spec.h"
#include "verify/html_escape.h"

namespace tessera::cli {

SuiteDemoResult runSuiteDemo(const std::string& outDir, const std::string& suitePath) {
  suite::LoadOptions lo;
  lo.gl = false;  // the scene table above cross-checks every scene already
  const suite::Suite s = suite::loadSuite(suitePath, lo);
  const std::string dir = outDir + "/suite";
  prepareOutputDirectory(dir, "-o");
  suite::RunInfo run{s.name, suitePath, s.sha256, "cpu", "", "1/1", s.cases.size(), {}};
  for (const suite::SuiteCase& c : s.cases) run.allCaseNames.push_back(c.name);
  std::fprintf(stderr, "suite %s: %zu CPU cases in child processes, 2 at a time\n", s.name.c_str(), s.cases.size());
  suite::RunOptions ro;
  ro.jobs = 2;
  ro.outDir = dir;
  const std::vector<suite::CaseResult> results = suite::runCases(s.cases, ro);
  suite::writeRunOutputs(dir, run, results);
  SuiteDemoResult r;
  const nlohmann::json j = suite::resultsJson(run, results);
  r.report = j["summary"];
  r.report["summary_page"] = "suite/index.html";
  r.allPassOrExpected = j["summary"]["all_pass_or_expected"].get<bool>();
  std::string counts;
  for (const auto& [k, v] : j["summary"]["statuses"].items())
    if (v.get<size_t>() > 0) counts += fmt::format("{} {}, ", verify::escapeHtml(k), v.get<size_t>());
  if (!counts.empty()) counts.resize(counts.size() - 2);
  r.html = fmt::format(
      "<h2>Corpus run: <code>tessera suite</code></h2><p>The CPU cases of <code>suites/smoke.json</code> ({} cases: "
      "every scene rendered, and visibility where the frame allows it), each in its own child process as a CI shard "
      "would run them: {}. <a href='suite/index.html'>Summary page</a> (every case with its status, key figures and "
      "log), <a href='suite/results.json'>results.json</a>, <a href='suite/junit.xml'>junit.xml</a>. "
      "See docs/suite.md for shards, baselines and the schedulers.</p>\n",
      results.size(), counts);
  return r;
}

}  // namespace tessera::cli
