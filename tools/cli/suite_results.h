// What a suite run decided, case by case, and the files that carry it (docs/suite.md).
//
// Implements: the case result (status, duration, attempts, exit, key figures), the two lists that
// change a status, the --flakes file (one ECMAScript regex per line over whole case names, as
// deqp-runner's) and the --baseline file of expected failures (the expectations file's layout:
// schema, comment, entries with id, case regex, optional status and condition, reason; every error
// names the file, the entry and the field), results.json (read back by `suite merge`), JUnit XML, the
// HTML summary, and the merge of shards (every case exactly once).
// Does not implement: running processes (suite_run.h) or reading the suite (suite_spec.h).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <string>
#include <vector>

namespace tessera::cli::suite {

// pass, fail, crash, timeout, flake, expected-fail, unexpected-pass.
struct CaseResult {
  size_t index = 0;
  std::string name, kind;
  std::string status;
  double durationSeconds = 0;  // every attempt's steps, wall time
  int attempts = 1;
  std::string exit;          // how the deciding attempt ended: "exit 0", "exit 1", "signal 6", "timeout after 5 s"
  std::string detail;        // for a crash: "out of memory" when the process said so
  std::string firstAttempt;  // for a flake or a retried failure: how attempt 1 ended
  std::string baselineId;    // the matching baseline entry, if any
  bool knownFlake = false;   // the name matches --flakes
  nlohmann::json figures = nlohmann::json::object();  // key figures taken from the last step's JSON
  std::string report;  // path of the case's report, relative to the run's output directory
  std::string log;     // path of the deciding attempt's last stdout, relative likewise

  // pass, expected-fail, and a flake that --flakes lists.
  bool acceptable() const;
  nlohmann::json toJson() const;
  static CaseResult fromJson(const nlohmann::json& j, const std::string& where);
};

// The key figures of a command's stdout when it is one JSON object: exact_match_percent, unexplained,
// expected_deviation, counters_equal, draw_calls, image_sha256, mismatches, killed_percent, ...
// whichever are present (docs/suite.md lists the paths). Empty when stdout is not JSON.
nlohmann::json keyFigures(const std::string& stdoutText);

struct FlakeList {
  std::string file;
  std::vector<std::pair<std::string, std::regex>> patterns;
  bool matches(const std::string& name) const;
};
// Throws Error "<file>:<line>: <reason>" for a pattern that does not compile.
FlakeList loadFlakes(const std::string& path);

struct BaselineEntry {
  std::string id, casePattern, status = "any", glDriver, reason;
  std::regex re;
};
struct Baseline {
  std::string file;
  std::vector<BaselineEntry> entries;
  // The first entry whose case regex matches the whole name and whose condition holds.
  const BaselineEntry* match(const std::string& name, const std::string& glDriver) const;
};
Baseline parseBaseline(const nlohmann::json& doc, const std::string& file);
Baseline loadBaseline(const std::string& path);
// Whether a failing status (fail, crash, timeout) is the one the entry expects.
bool baselineExpects(const BaselineEntry& e, const std::string& status);

// The run's identity, written into results.json; shards of one run must agree on it.
struct RunInfo {
  std::string suiteName, suiteFile, suiteSha256, backends, glDriver, fraction;
  size_t suiteCases = 0;                  // cases of the whole suite after the --backends filter
  std::vector<std::string> allCaseNames;  // in index order: lets `merge` name the missing ones
};

nlohmann::json resultsJson(const RunInfo& run, const std::vector<CaseResult>& results);
std::string junitXml(const RunInfo& run, const std::vector<CaseResult>& results);
std::string summaryHtml(const RunInfo& run, const std::vector<CaseResult>& results);
// Writes results.json, junit.xml and index.html into `dir` (atomically).
void writeRunOutputs(const std::string& dir, const RunInfo& run, const std::vector<CaseResult>& results);

// Reads DIR/results.json of each shard, checks that they are shards of one run and that every case of
// the suite appears exactly once (Error naming the missing and duplicated cases otherwise), and returns
// the cases in suite order with report/log paths made relative to `outDir`.
std::pair<RunInfo, std::vector<CaseResult>> mergeShards(const std::vector<std::string>& dirs,
                                                        const std::string& outDir);

}  // namespace tessera::cli::suite
