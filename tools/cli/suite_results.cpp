#include "tools/cli/suite_results.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "base/atomic_file.h"
#include "base/error.h"
#include "verify/html_escape.h"

namespace tessera::cli::suite {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string readText(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot read the " + what);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::regex compileWhole(const std::string& pattern) {
  return std::regex(pattern, std::regex::ECMAScript);  // matched with regex_match: the whole name
}

// XML 1.0 text: the five entities, and control characters (not allowed in XML 1.0) as '?'.
std::string xmlEscape(std::string_view s) {
  std::string out;
  for (char ch : s) {
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        if (static_cast<unsigned char>(ch) < 0x20 && ch != '\n' && ch != '\t')
          out += '?';
        else
          out += ch;
    }
  }
  return out;
}

}  // namespace

bool CaseResult::acceptable() const {
  return status == "pass" || status == "expected-fail" || (status == "flake" && knownFlake);
}

json CaseResult::toJson() const {
  json j = {{"index", index},
            {"name", name},
            {"kind", kind},
            {"status", status},
            {"duration_seconds", durationSeconds},
            {"attempts", attempts},
            {"exit", exit},
            {"figures", figures}};
  if (!detail.empty()) j["detail"] = detail;
  if (!firstAttempt.empty()) j["first_attempt"] = firstAttempt;
  if (!baselineId.empty()) j["baseline"] = baselineId;
  if (knownFlake) j["known_flake"] = true;
  if (!report.empty()) j["report"] = report;
  if (!log.empty()) j["log"] = log;
  return j;
}

CaseResult CaseResult::fromJson(const json& j, const std::string& where) {
  try {
    CaseResult r;
    r.index = j.at("index").get<size_t>();
    r.name = j.at("name").get<std::string>();
    r.kind = j.at("kind").get<std::string>();
    r.status = j.at("status").get<std::string>();
    r.durationSeconds = j.at("duration_seconds").get<double>();
    r.attempts = j.at("attempts").get<int>();
    r.exit = j.at("exit").get<std::string>();
    r.figures = j.at("figures");
    r.detail = j.value("detail", "");
    r.firstAttempt = j.value("first_attempt", "");
    r.baselineId = j.value("baseline", "");
    r.knownFlake = j.value("known_flake", false);
    r.report = j.value("report", "");
    r.log = j.value("log", "");
    return r;
  } catch (const json::exception& e) {
    throw Error(where + ": not a case result of `tessera suite run`: " + e.what());
  }
}

json keyFigures(const std::string& stdoutText) {
  json doc = json::parse(stdoutText, nullptr, false);
  json out = json::object();
  if (doc.is_discarded() || !doc.is_object()) return out;
  static const std::vector<std::pair<const char*, const char*>> kPaths = {
      {"/exact_match_percent", "exact_match_percent"},
      {"/unexplained", "unexplained"},
      {"/expected_deviation", "expected_deviation"},
      {"/counters/equal", "counters_equal"},
      {"/counters/draw_calls", "draw_calls"},
      {"/image_sha256", "image_sha256"},
      {"/mismatches", "mismatches"},
      {"/explained", "explained"},
      {"/differing_pixels", "differing_pixels"},
      {"/tests", "tests"},
      {"/passed", "passed"},
      {"/killed_percent", "killed_percent"},
      {"/false_alarms", "false_alarms"}};
  for (const auto& [ptr, key] : kPaths) {
    const json::json_pointer p(ptr);
    if (doc.contains(p) && !doc[p].is_object() && !doc[p].is_array()) out[key] = doc[p];
  }
  return out;
}

bool FlakeList::matches(const std::string& name) const {
  for (const auto& [text, re] : patterns)
    if (std::regex_match(name, re)) return true;
  return false;
}

FlakeList loadFlakes(const std::string& path) {
  FlakeList f;
  f.file = path;
  std::istringstream in(readText(path, "flakes file"));
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.pop_back();
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    line = line.substr(first);
    try {
      f.patterns.emplace_back(line, compileWhole(line));
    } catch (const std::regex_error& e) {
      throw Error(path + ":" + std::to_string(n) + ": '" + line +
                  "' is not an ECMAScript regular expression: " + e.what());
    }
  }
  return f;
}

const BaselineEntry* Baseline::match(const std::string& name, const std::string& glDriver) const {
  for (const BaselineEntry& e : entries) {
    if (!e.glDriver.empty() && e.glDriver != (glDriver.empty() ? "llvmpipe" : glDriver)) continue;
    if (std::regex_match(name, e.re)) return &e;
  }
  return nullptr;
}

bool baselineExpects(const BaselineEntry& e, const std::string& status) {
  return e.status == "any" ? (status == "fail" || status == "crash" || status == "timeout") : e.status == status;
}

Baseline parseBaseline(const json& doc, const std::string& file) {
  Baseline b;
  b.file = file;
  if (!doc.is_object()) throw Error(file + ": the baseline must be a JSON object");
  for (const auto& [k, v] : doc.items())
    if (k != "schema" && k != "comment" && k != "entries")
      throw Error(file + ": field '" + k + "': unknown (schema, comment, entries)");
  if (!doc.contains("schema") || doc["schema"] != 1) throw Error(file + ": field 'schema': must be 1");
  if (!doc.contains("entries") || !doc["entries"].is_array()) throw Error(file + ": field 'entries': must be an array");
  std::map<std::string, size_t> ids;
  for (size_t i = 0; i < doc["entries"].size(); ++i) {
    const json& e = doc["entries"][i];
    std::string id = e.is_object() && e.contains("id") && e["id"].is_string() ? e["id"].get<std::string>() : "";
    auto fail = [&](const std::string& field, const std::string& why) {
      throw Error(file + ": entry " + std::to_string(i) + (id.empty() ? "" : " (" + id + ")") + ": field '" + field +
                  "': " + why);
    };
    if (!e.is_object()) fail("", "an entry must be a JSON object");
    for (const auto& [k, v] : e.items())
      if (k != "id" && k != "case" && k != "status" && k != "condition" && k != "reason")
        fail(k, "unknown (id, case, status, condition, reason)");
    auto str = [&](const char* k, bool required) -> std::string {
      if (!e.contains(k)) {
        if (required) fail(k, "missing");
        return "";
      }
      if (!e[k].is_string() || e[k].get<std::string>().empty()) fail(k, "must be a non-empty string");
      return e[k].get<std::string>();
    };
    BaselineEntry be;
    be.id = str("id", true);
    if (be.id.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") != std::string::npos)
      fail("id", "'" + be.id + "': only a-z 0-9 _ -");
    if (!ids.emplace(be.id, i).second) fail("id", "'" + be.id + "' is used by entry " + std::to_string(ids[be.id]));
    be.casePattern = str("case", true);
    try {
      be.re = compileWhole(be.casePattern);
    } catch (const std::regex_error& ex) {
      fail("case", "'" + be.casePattern + "' is not an ECMAScript regular expression: " + ex.what());
    }
    if (e.contains("status")) {
      be.status = str("status", false);
      if (be.status != "any" && be.status != "fail" && be.status != "crash" && be.status != "timeout")
        fail("status", "'" + be.status + "': expected fail, crash, timeout or any");
    }
    if (e.contains("condition")) {
      if (!e["condition"].is_object()) fail("condition", "must be an object");
      for (const auto& [k, v] : e["condition"].items()) {
        if (k != "gl_driver") fail("condition." + k, "unknown (gl_driver)");
        if (!v.is_string() || v.get<std::string>().empty()) fail("condition.gl_driver", "must be a non-empty string");
        be.glDriver = v.get<std::string>();
      }
    }
    be.reason = str("reason", true);
    b.entries.push_back(std::move(be));
  }
  return b;
}

Baseline loadBaseline(const std::string& path) {
  const json doc = json::parse(readText(path, "baseline file"), nullptr, false);
  if (doc.is_discarded()) throw Error(path + ": not valid JSON");
  return parseBaseline(doc, path);
}

namespace {

json runJson(const RunInfo& run) {
  return {{"suite", run.suiteName},        {"suite_file", run.suiteFile},  {"suite_sha256", run.suiteSha256},
          {"backends", run.backends},      {"gl_driver", run.glDriver},    {"fraction", run.fraction},
          {"suite_cases", run.suiteCases}, {"all_cases", run.allCaseNames}};
}

std::map<std::string, size_t> countStatuses(const std::vector<CaseResult>& results) {
  std::map<std::string, size_t> n;
  for (const char* s : {"pass", "fail", "crash", "timeout", "flake", "expected-fail", "unexpected-pass"}) n[s] = 0;
  for (const CaseResult& r : results) ++n[r.status];
  return n;
}

bool allAcceptable(const std::vector<CaseResult>& results) {
  for (const CaseResult& r : results)
    if (!r.acceptable()) return false;
  return true;
}

}  // namespace

json resultsJson(const RunInfo& run, const std::vector<CaseResult>& results) {
  json cases = json::array();
  double total = 0;
  for (const CaseResult& r : results) cases.push_back(r.toJson()), total += r.durationSeconds;
  json counts = json::object();
  for (const auto& [k, v] : countStatuses(results)) counts[k] = v;
  return {{"run", runJson(run)},
          {"summary",
           {{"cases", results.size()},
            {"statuses", counts},
            {"all_pass_or_expected", allAcceptable(results)},
            {"case_seconds", total}}},
          {"cases", cases}};
}

std::string junitXml(const RunInfo& run, const std::vector<CaseResult>& results) {
  size_t failures = 0, errors = 0, skipped = 0;
  double total = 0;
  std::string body;
  for (const CaseResult& r : results) {
    total += r.durationSeconds;
    body += fmt::format("    <testcase classname=\"tessera.{}.{}\" name=\"{}\" time=\"{:.3f}\">\n",
                        xmlEscape(run.suiteName), xmlEscape(r.kind), xmlEscape(r.name), r.durationSeconds);
    const std::string info = r.exit + (r.detail.empty() ? "" : " (" + r.detail + ")") +
                             (r.log.empty() ? "" : "; log: " + r.log) +
                             (r.report.empty() ? "" : "; report: " + r.report);
    if (r.status == "fail" || r.status == "unexpected-pass" || (r.status == "flake" && !r.knownFlake)) {
      ++failures;
      const std::string msg = r.status == "unexpected-pass"
                                  ? "unexpected pass: baseline entry " + r.baselineId + " can be removed"
                              : r.status == "flake" ? "flaky: failed (" + r.firstAttempt + ") then passed on retry"
                                                    : "failed: " + r.exit;
      body += fmt::format("      <failure type=\"{}\" message=\"{}\">{}\nfigures: {}</failure>\n", r.status,
                          xmlEscape(msg), xmlEscape(info), xmlEscape(r.figures.dump()));
    } else if (r.status == "crash" || r.status == "timeout") {
      ++errors;
      body += fmt::format("      <error type=\"{}\" message=\"{}\">{}</error>\n", r.status,
                          xmlEscape(r.status + ": " + r.exit + (r.detail.empty() ? "" : " (" + r.detail + ")")),
                          xmlEscape(info));
    } else if (r.status == "expected-fail") {
      ++skipped;
      body += fmt::format("      <skipped message=\"{}\"/>\n",
                          xmlEscape("expected failure (baseline entry " + r.baselineId + "): " + r.exit));
    } else if (r.status == "flake") {
      body += fmt::format("      <system-out>{}</system-out>\n",
                          xmlEscape("known flake: failed (" + r.firstAttempt + ") then passed on retry"));
    }
    if (!r.figures.empty() && r.status == "pass")
      body += fmt::format("      <system-out>{}</system-out>\n", xmlEscape("figures: " + r.figures.dump()));
    body += "    </testcase>\n";
  }
  const std::string name = "tessera." + run.suiteName + (run.fraction == "1/1" ? "" : " (shard " + run.fraction + ")");
  return fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<testsuites name=\"{0}\" tests=\"{1}\" failures=\"{2}\" errors=\"{3}\" skipped=\"{4}\" time=\"{5:.3f}\">\n"
      "  <testsuite name=\"{0}\" tests=\"{1}\" failures=\"{2}\" errors=\"{3}\" skipped=\"{4}\" time=\"{5:.3f}\">\n"
      "{6}  </testsuite>\n</testsuites>\n",
      xmlEscape(name), results.size(), failures, errors, skipped, total, body);
}

std::string summaryHtml(const RunInfo& run, const std::vector<CaseResult>& results) {
  using verify::escapeHtml;
  static const std::map<std::string, std::string> kColour = {
      {"pass", "#cfc"},  {"fail", "#f99"},          {"crash", "#f66"},          {"timeout", "#fc6"},
      {"flake", "#ffc"}, {"expected-fail", "#ddd"}, {"unexpected-pass", "#9cf"}};
  std::string counts;
  for (const auto& [k, v] : countStatuses(results))
    counts += fmt::format("<span style='background:{};padding:2px 6px'>{} {}</span> ", kColour.at(k), escapeHtml(k), v);
  std::string rows;
  for (const CaseResult& r : results) {
    const std::string link = !r.report.empty() ? r.report : r.log;
    const std::string nameCell =
        link.empty() ? escapeHtml(r.name) : fmt::format("<a href=\"{}\">{}</a>", escapeHtml(link), escapeHtml(r.name));
    std::string figs;
    for (const auto& [k, v] : r.figures.items()) {
      std::string val = v.is_string() ? v.get<std::string>().substr(0, 16) : v.dump();
      if (v.is_number_float()) val = fmt::format("{:.4f}", v.get<double>());
      figs += fmt::format("{}={} ", escapeHtml(k), escapeHtml(val));
    }
    std::string note = r.detail;
    if (!r.baselineId.empty()) note += (note.empty() ? "" : "; ") + std::string("baseline ") + r.baselineId;
    if (!r.firstAttempt.empty()) note += (note.empty() ? "" : "; ") + std::string("attempt 1: ") + r.firstAttempt;
    if (r.knownFlake) note += (note.empty() ? "" : "; ") + std::string("known flake");
    rows += fmt::format(
        "<tr><td>{}</td><td>{}</td><td style='background:{}'>{}</td><td>{:.2f}</td><td>{}</td><td><code>{}</code></td>"
        "<td>{}</td></tr>\n",
        r.index, nameCell, kColour.count(r.status) ? kColour.at(r.status) : "#fff", escapeHtml(r.status),
        r.durationSeconds, escapeHtml(r.exit), figs, escapeHtml(note));
  }
  return fmt::format(
      "<!doctype html><meta charset=utf-8><title>Tessera suite {0}</title>"
      "<style>body{{font-family:sans-serif}}td{{padding:3px 6px;vertical-align:top}}</style>"
      "<h1>Tessera suite <code>{0}</code></h1><p>{1} of {2} cases (fraction {3}, backends {4}); {5}</p><p>{6}</p>"
      "<p>Machine-readable: <a href='results.json'>results.json</a>, <a href='junit.xml'>junit.xml</a></p>"
      "<table border=1 cellspacing=0><tr><th>#</th><th>case</th><th>status</th><th>s</th><th>exit</th>"
      "<th>key figures</th><th>note</th></tr>\n{7}</table>\n",
      escapeHtml(run.suiteName), results.size(), run.suiteCases, escapeHtml(run.fraction), escapeHtml(run.backends),
      allAcceptable(results) ? "every result is a pass or expected"
                             : "<b>some results are neither a pass nor expected</b>",
      counts, rows);
}

void writeRunOutputs(const std::string& dir, const RunInfo& run, const std::vector<CaseResult>& results) {
  writeFileAtomically(dir + "/results.json", resultsJson(run, results).dump(2) + "\n");
  writeFileAtomically(dir + "/junit.xml", junitXml(run, results));
  writeFileAtomically(dir + "/index.html", summaryHtml(run, results));
}

std::pair<RunInfo, std::vector<CaseResult>> mergeShards(const std::vector<std::string>& dirs,
                                                        const std::string& outDir) {
  if (dirs.empty()) throw Error("suite merge: no shard directories given");
  RunInfo run;
  std::vector<std::vector<std::string>> seen;  // per suite index, the shard directories that ran it
  std::vector<CaseResult> byIndex;
  for (size_t d = 0; d < dirs.size(); ++d) {
    const std::string file = dirs[d] + "/results.json";
    const json doc =
        json::parse(readText(file, "results of a shard (results.json of `tessera suite run`)"), nullptr, false);
    if (doc.is_discarded() || !doc.contains("run") || !doc.contains("cases") || !doc["cases"].is_array())
      throw Error(file + ": not the results.json of `tessera suite run`");
    RunInfo r;
    try {
      const json& j = doc["run"];
      r = {j.at("suite"),     j.at("suite_file"), j.at("suite_sha256"), j.at("backends"),
           j.at("gl_driver"), j.at("fraction"),   j.at("suite_cases"),  j.at("all_cases")};
    } catch (const json::exception& e) {
      throw Error(file + ": field 'run': " + e.what());
    }
    if (d == 0) {
      run = r;
      run.fraction = "merged";
      seen.resize(run.suiteCases);
      byIndex.resize(run.suiteCases);
    } else if (r.suiteSha256 != run.suiteSha256 || r.backends != run.backends || r.glDriver != run.glDriver ||
               r.suiteCases != run.suiteCases) {
      throw Error(file + ": a shard of another run (suite " + r.suiteName + " " + r.suiteSha256.substr(0, 12) +
                  ", backends " + r.backends + ") than " + dirs[0] + " (suite " + run.suiteName + " " +
                  run.suiteSha256.substr(0, 12) + ", backends " + run.backends + ")");
    }
    for (size_t i = 0; i < doc["cases"].size(); ++i) {
      CaseResult c = CaseResult::fromJson(doc["cases"][i], file + ": case " + std::to_string(i));
      if (c.index >= run.suiteCases || run.allCaseNames[c.index] != c.name)
        throw Error(file + ": case " + std::to_string(i) + " (" + c.name + "): not case " + std::to_string(c.index) +
                    " of the suite");
      auto rel = [&](const std::string& p) {
        return p.empty() ? p : fs::relative(fs::absolute(dirs[d]) / p, fs::absolute(outDir)).string();
      };
      c.report = rel(c.report), c.log = rel(c.log);
      seen[c.index].push_back(dirs[d]);
      byIndex[c.index] = std::move(c);
    }
  }
  std::string missing, duplicated;
  size_t nMissing = 0, nDup = 0;
  for (size_t i = 0; i < seen.size(); ++i) {
    if (seen[i].empty()) missing += (nMissing++ ? ", " : "") + run.allCaseNames[i];
    if (seen[i].size() > 1) {
      std::string where;
      for (const std::string& s : seen[i]) where += (where.empty() ? "" : ", ") + s;
      duplicated += (nDup++ ? "; " : "") + run.allCaseNames[i] + " (in " + where + ")";
    }
  }
  if (nMissing || nDup)
    throw Error("suite merge: every case must run exactly once: " +
                (nMissing ? std::to_string(nMissing) + " missing: " + missing : std::string()) +
                (nMissing && nDup ? "; " : "") +
                (nDup ? std::to_string(nDup) + " duplicated: " + duplicated : std::string()));
  return {run, byIndex};
}

}  // namespace tessera::cli::suite
