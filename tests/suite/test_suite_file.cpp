// Suite files and their errors, --fraction shards, the baseline and flakes files (suite_spec.h,
// suite_results.h), without running anything.
#include <gtest/gtest.h>

#include <set>

#include "base/error.h"
#include "tests/suite/suite_test_util.h"
#include "tools/cli/suite_results.h"
#include "tools/cli/suite_spec.h"
#include "tools/scenes/scenes.h"

namespace tessera::cli::suite {
namespace {

using test::scratchDir;
using test::writeText;

std::vector<SuiteCase> numbered(size_t n) {
  std::vector<SuiteCase> v(n);
  for (size_t i = 0; i < n; ++i) {
    v[i].index = i;
    v[i].name = std::to_string(i).insert(0, 1, 'c');  // not "c" + ...: GCC 12 warns falsely (-Wrestrict, bug 105329)
  }
  return v;
}

TEST(SuiteFraction, ShardsOfEveryCountAreDisjointAndTheirUnionIsTheSuite) {
  for (size_t n = 0; n <= 23; ++n) {
    const std::vector<SuiteCase> all = numbered(n);
    for (size_t m = 1; m <= 9; ++m) {
      std::vector<int> seen(n, 0);
      for (size_t k = 1; k <= m; ++k) {
        const std::vector<SuiteCase> shard = selectFraction(all, Fraction{k, m});
        // Every M-th case starting at the K-th: K-1, K-1+M, K-1+2M, ...
        for (size_t j = 0; j < shard.size(); ++j) EXPECT_EQ(shard[j].index, k - 1 + j * m) << n << " " << k << "/" << m;
        // Sizes: ceil((n - (k-1)) / m) for k-1 < n, else 0.
        EXPECT_EQ(shard.size(), n > k - 1 ? (n - (k - 1) + m - 1) / m : 0u);
        for (const SuiteCase& c : shard) ++seen[c.index];
      }
      for (size_t i = 0; i < n; ++i) EXPECT_EQ(seen[i], 1) << "case " << i << " of " << n << " with M = " << m;
    }
  }
}

TEST(SuiteFraction, KIsOneBasedAndEveryMalformedFractionIsAClearError) {
  EXPECT_EQ(parseFraction("1/1").k, 1u);
  EXPECT_EQ(parseFraction("4/4").k, 4u);
  EXPECT_EQ(parseFraction("3/7").m, 7u);
  for (const char* bad : {"0/4", "5/4", "1/0", "0/0", "a/b", "3", "-1/2", "1/-2", "/4", "1/", "1.5/4", " 1/4"}) {
    try {
      parseFraction(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("--fraction '") + bad + "'"), std::string::npos) << e.what();
    }
  }
  try {
    parseFraction("0/4");
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("1-based"), std::string::npos) << e.what();
  }
}

// The error message of loading `text` as a suite.
std::string suiteError(const std::string& text) {
  const std::string dir = scratchDir("errors");
  writeText(dir + "/s.json", text);
  try {
    loadSuite(dir + "/s.json", {});
  } catch (const Error& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(SuiteFile, EveryMalformedSuiteNamesTheFileTheCaseAndTheField) {
  struct Bad {
    const char* text;
    std::vector<std::string> says;
  };
  const std::vector<Bad> bad = {
      {"{\"schema\": 1, \"name\": \"x\", \"cases\": [", {"s.json", "not valid JSON"}},
      {"[]", {"s.json", "JSON object"}},
      {"{\"schema\": 2, \"name\": \"x\", \"cases\": []}", {"s.json", "'schema'", "must be 1"}},
      {"{\"schema\": 1, \"name\": \"x\", \"cases\": []}", {"'cases'", "non-empty"}},
      {"{\"schema\": 1, \"name\": \"a b\", \"cases\": [{}]}", {"'name'"}},
      {"{\"schema\": 1, \"name\": \"x\", \"extra\": 1, \"cases\": [{}]}", {"'extra'", "unknown"}},
      {"{\"schema\": 1, \"name\": \"x\", \"cases\": [{\"kind\": \"golden\"}]}", {"case 0", "'name'", "missing"}},
      {"{\"schema\": 1, \"name\": \"x\", \"cases\": [{\"name\": \"g\", \"kind\": \"golden\"}, {\"name\": \"q\", "
       "\"kind\": \"paint\"}]}",
       {"case 1 (q)", "'kind'", "'paint'", "unknown"}},
      {"{\"schema\": 1, \"name\": \"x\", \"cases\": [{\"name\": \"r\", \"kind\": \"render\", \"scene\": "
       "\"no_such_scene\"}]}",
       {"case 0 (r)", "'scene'", "no_such_scene"}},
      {"{\"schema\": 1, \"name\": \"x\", \"cases\": [{\"name\": \"r\", \"kind\": \"render\", \"scene\": \"fill_fan\", "
       "\"frame\": \"y\"}]}",
       {"case 0 (r)", "'frame'", "unknown for kind 'render'"}},
      {"{\"schema\": 1, \"name\": \"x\", \"cases\": [{\"name\": \"g\", \"kind\": \"golden\"}, {\"name\": \"g\", "
       "\"kind\": \"golden\"}]}",
       {"case 1 (g)", "'name'", "earlier case"}},
      {"{\"schema\": 1, \"name\": \"x\", \"cases\": [{\"name\": \"../g\", \"kind\": \"golden\"}]}",
       {"case 0", "'name'"}},
      {"{\"schema\": 1, \"name\": \"x\", \"cases\": [{\"name\": \"f\", \"kind\": \"replay\", \"frame\": "
       "\"/nonexistent/*.tframe\"}]}",
       {"case 0 (f)", "'frame'", "matches no file"}},
      {"{\"schema\": 1, \"name\": \"x\", \"cases\": [{\"name\": \"g\", \"kind\": \"golden\", \"timeout_seconds\": 0}]}",
       {"case 0 (g)", "'timeout_seconds'"}},
      {"{\"schema\": 1, \"name\": \"x\", \"cases\": [{\"name\": \"g\", \"kind\": \"golden\", \"memory_limit\": "
       "\"4KB\"}]}",
       {"case 0 (g)", "'memory_limit'"}},
      {"{\"schema\": 1, \"name\": \"x\", \"cases\": [{\"name\": \"c\", \"kind\": \"command\", \"steps\": [[]]}]}",
       {"case 0 (c)", "'steps'"}},
      {"{\"schema\": 1, \"name\": \"x\", \"defaults\": {\"retries\": 3}, \"cases\": [{\"name\": \"g\", \"kind\": "
       "\"golden\"}]}",
       {"'defaults.retries'", "unknown"}},
  };
  for (const Bad& b : bad) {
    const std::string msg = suiteError(b.text);
    for (const std::string& s : b.says) EXPECT_NE(msg.find(s), std::string::npos) << b.text << "\n -> " << msg;
  }
}

TEST(SuiteFile, StarAndGlobsExpandToOneCaseNamedAfterEachItemInOrder) {
  const std::string dir = scratchDir("globs");
  for (const char* f : {"b.tframe", "a.tframe", "c.txt"}) writeText(dir + "/" + f, "x");
  writeText(dir + "/s.json",
            "{\"schema\": 1, \"name\": \"x\", \"cases\": ["
            "{\"name\": \"frames\", \"kind\": \"replay\", \"frame\": \"" +
                dir +
                "/*.tframe\"},"
                "{\"name\": \"scenes\", \"kind\": \"render\", \"scene\": \"*\", \"size\": \"8x8\"},"
                "{\"name\": \"one\", \"kind\": \"visibility\", \"frame\": \"fill_fan\"},"
                "{\"name\": \"xc\", \"kind\": \"crosscheck\", \"frame\": \"fill_fan\"}]}");
  const Suite s = loadSuite(dir + "/s.json", {});
  const size_t nScenes = scenes::all().size();
  ASSERT_EQ(s.cases.size(), 2 + nScenes + 2);
  EXPECT_EQ(s.cases[0].name, "frames/a");
  EXPECT_EQ(s.cases[1].name, "frames/b");
  EXPECT_EQ(s.cases[0].steps[0][0], "replay");
  EXPECT_EQ(s.cases[0].steps[0][1], dir + "/a.tframe");
  for (size_t i = 0; i < nScenes; ++i) {
    EXPECT_EQ(s.cases[2 + i].name, "scenes/" + std::string(scenes::all()[i].name));
    EXPECT_EQ(s.cases[2 + i].index, 2 + i);
  }
  EXPECT_EQ(s.cases[2 + nScenes].name, "one");  // a single scene keeps the case's own name
  EXPECT_TRUE(s.cases.back().needsGl);
  // --backends cpu leaves out the cross-check, and the indices stay dense.
  LoadOptions cpuOnly;
  cpuOnly.gl = false;
  const Suite c = loadSuite(dir + "/s.json", cpuOnly);
  ASSERT_EQ(c.cases.size(), s.cases.size() - 1);
  EXPECT_EQ(c.cases.back().index, c.cases.size() - 1);
}

TEST(SuiteBaseline, EntriesMatchWholeNamesUnderTheirConditionAndErrorsNameEntryAndField) {
  const Baseline b = parseBaseline(nlohmann::json::parse(R"({"schema": 1, "entries": [
      {"id": "soft", "case": "xc/.*", "condition": {"gl_driver": "softpipe"}, "reason": "r"},
      {"id": "crash-only", "case": "c", "status": "crash", "reason": "r"}]})"),
                                   "b.json");
  EXPECT_EQ(b.match("xc/triangle", "llvmpipe"), nullptr);
  ASSERT_NE(b.match("xc/triangle", "softpipe"), nullptr);
  EXPECT_EQ(b.match("xc/triangle", "softpipe")->id, "soft");
  EXPECT_EQ(b.match("axc/triangle", "softpipe"), nullptr);  // the whole name, not a substring
  ASSERT_NE(b.match("c", ""), nullptr);
  EXPECT_TRUE(baselineExpects(*b.match("c", ""), "crash"));
  EXPECT_FALSE(baselineExpects(*b.match("c", ""), "fail"));
  EXPECT_TRUE(baselineExpects(*b.match("xc/t", "softpipe"), "timeout"));
  const std::vector<std::pair<const char*, const char*>> bad = {
      {R"({"schema": 1, "entries": [{"id": "a", "case": "(", "reason": "r"}]})", "entry 0 (a): field 'case'"},
      {R"({"schema": 1, "entries": [{"id": "a", "case": "x", "status": "pass", "reason": "r"}]})",
       "entry 0 (a): field 'status'"},
      {R"({"schema": 1, "entries": [{"id": "a", "case": "x"}]})", "entry 0 (a): field 'reason': missing"},
      {R"({"schema": 1, "entries": [{"id": "a", "case": "x", "reason": "r", "pixels": 3}]})",
       "entry 0 (a): field 'pixels'"},
      {R"({"schema": 1, "entries": [{"id": "a", "case": "x", "reason": "r"}, {"id": "a", "case": "y", "reason": "r"}]})",
       "entry 1 (a): field 'id'"},
      {R"({"schema": 1, "entries": [{"id": "A", "case": "x", "reason": "r"}]})", "entry 0 (A): field 'id'"},
      {R"({"schema": 1, "entries": [{"id": "a", "case": "x", "reason": "r", "condition": {"lp": "1"}}]})",
       "entry 0 (a): field 'condition.lp'"},
  };
  for (const auto& [text, says] : bad) {
    try {
      parseBaseline(nlohmann::json::parse(text), "b.json");
      ADD_FAILURE() << text << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("b.json: ") + says), std::string::npos) << e.what();
    }
  }
}

TEST(SuiteFlakes, LinesAreWholeNameRegexesCommentsAreSkippedAndABadLineIsNamed) {
  const std::string dir = scratchDir("flakes");
  writeText(dir + "/f.txt", "# known flakes\n\nxc/wrap_.*\n  exact  \n");
  const FlakeList f = loadFlakes(dir + "/f.txt");
  EXPECT_TRUE(f.matches("xc/wrap_filter"));
  EXPECT_TRUE(f.matches("exact"));
  EXPECT_FALSE(f.matches("exactly"));
  EXPECT_FALSE(f.matches("a/xc/wrap_filter"));
  writeText(dir + "/g.txt", "ok\n[unclosed\n");
  try {
    loadFlakes(dir + "/g.txt");
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("g.txt:2:"), std::string::npos) << e.what();
  }
}

TEST(SuiteFigures, TheKeyFiguresOfACrosscheckAreTakenFromItsJson) {
  const nlohmann::json f = keyFigures(
      R"({"exact_match_percent": 99.25, "unexplained": 0, "expected_deviation": 12,
          "counters": {"equal": true, "draw_calls": 4}, "images": []})");
  EXPECT_EQ(f["exact_match_percent"], 99.25);
  EXPECT_EQ(f["unexplained"], 0);
  EXPECT_EQ(f["expected_deviation"], 12);
  EXPECT_EQ(f["counters_equal"], true);
  EXPECT_EQ(f["draw_calls"], 4);
  EXPECT_TRUE(keyFigures("not json").empty());
  EXPECT_TRUE(keyFigures("{\"x\": 1}\n{\"y\": 2}").empty());
}

}  // namespace
}  // namespace tessera::cli::suite
