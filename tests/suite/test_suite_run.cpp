// `tessera suite run | merge` end to end through the built executable: the same suite as one shard and
// as four, the statuses that misbehaving cases get, JUnit that an XML parser reads, merge errors.
#include <gtest/gtest.h>

#include <set>

#include "tests/suite/suite_test_util.h"

namespace tessera::cli::suite {
namespace {

using nlohmann::json;
using test::readJson;
using test::scratchDir;
using test::tessera;
using test::writeText;

// Seven CPU cases of a few milliseconds: renders at 16x16 and the test-only case in pass mode.
std::string smallSuite(const std::string& dir) {
  const std::string path = dir + "/small.json";
  writeText(path, R"({"schema": 1, "name": "small", "cases": [
    {"name": "render/a", "kind": "render", "scene": "fill_fan", "size": "16x16"},
    {"name": "ok/1", "kind": "command", "steps": [["suite", "_case", "--mode", "pass"]]},
    {"name": "render/b", "kind": "render", "scene": "fill_fan", "size": "24x8"},
    {"name": "ok/2", "kind": "command", "steps": [["suite", "_case", "--mode", "pass"], ["suite", "_case", "--mode", "pass"]]},
    {"name": "ok/3", "kind": "command", "steps": [["suite", "_case", "--mode", "pass"]]},
    {"name": "render/c", "kind": "render", "scene": "fill_fan", "size": "8x8"},
    {"name": "ok/4", "kind": "command", "steps": [["suite", "_case", "--mode", "pass"]]}]})");
  return path;
}

// A case result without what may vary between runs (durations) or between directories (paths).
json comparable(json c) {
  c.erase("duration_seconds");
  c.erase("log");
  c.erase("report");
  return c;
}

TEST(SuiteRun, FourShardsMergedEqualOneRunCaseByCaseApartFromDurations) {
  const std::string dir = scratchDir("shards");
  const std::string suite = smallSuite(dir);
  const test::Run one = tessera("suite run '" + suite + "' --backends cpu --jobs 2 -o '" + dir + "/one'", dir + "/one");
  ASSERT_EQ(one.exitCode, 0) << one.err;
  std::string dirs;
  std::set<std::string> ran;
  for (int k = 1; k <= 4; ++k) {
    const std::string out = dir + "/shard" + std::to_string(k);
    const test::Run r = tessera(
        "suite run '" + suite + "' --backends cpu --fraction " + std::to_string(k) + "/4 -o '" + out + "'", out);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const json shard = readJson(out + "/results.json");
    for (const json& c : shard["cases"]) {
      EXPECT_EQ(c["index"].get<size_t>() % 4, size_t(k - 1)) << c;  // every 4th case starting at the k-th
      EXPECT_TRUE(ran.insert(c["name"]).second) << c["name"] << " ran in two shards";
    }
    dirs += " '" + out + "'";
  }
  EXPECT_EQ(ran.size(), 7u);
  const test::Run m = tessera("suite merge" + dirs + " -o '" + dir + "/merged'", dir + "/merged");
  ASSERT_EQ(m.exitCode, 0) << m.err;
  const json a = readJson(dir + "/one/results.json")["cases"], b = readJson(dir + "/merged/results.json")["cases"];
  ASSERT_EQ(a.size(), 7u);
  ASSERT_EQ(b.size(), 7u);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(comparable(a[i]), comparable(b[i])) << i;
    EXPECT_EQ(a[i]["status"], "pass");
  }
  // The renders' key figures: one draw call, and 16x16, 24x8, 8x8 images of different hashes.
  EXPECT_EQ(a[0]["figures"]["draw_calls"], 1);
  EXPECT_NE(a[0]["figures"]["image_sha256"], a[2]["figures"]["image_sha256"]);
  EXPECT_EQ(a[1]["figures"]["unexplained"], 0);
  // The merged page links the shards' case reports (a render's stats JSON) and, without one, logs.
  const std::string html = test::readText(dir + "/merged/index.html");
  EXPECT_NE(html.find("\"../shard1/cases/render/a/stats.json\""), std::string::npos);
  EXPECT_NE(html.find("\"../shard2/cases/ok/1/attempt1.step1.stdout.txt\""), std::string::npos);
}

TEST(SuiteMerge, AMissingOrDuplicatedShardIsNamedCaseByCase) {
  const std::string dir = scratchDir("merge");
  const std::string suite = smallSuite(dir);
  for (int k : {1, 2})
    ASSERT_EQ(tessera("suite run '" + suite + "' --backends cpu --quiet --fraction " + std::to_string(k) + "/2 -o '" +
                          dir + "/s" + std::to_string(k) + "'",
                      dir + "/s" + std::to_string(k))
                  .exitCode,
              0);
  // Shard 2 of 2 holds cases 1, 3, 5: ok/1, ok/2, render/c.
  const test::Run missing = tessera("suite merge '" + dir + "/s1' -o '" + dir + "/m1'", dir + "/m1");
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.err.find("3 missing: ok/1, ok/2, render/c"), std::string::npos) << missing.err;
  const test::Run dup =
      tessera("suite merge '" + dir + "/s1' '" + dir + "/s2' '" + dir + "/s1' -o '" + dir + "/m2'", dir + "/m2");
  EXPECT_EQ(dup.exitCode, 2);
  EXPECT_NE(dup.err.find("4 duplicated: render/a (in " + dir + "/s1, " + dir + "/s1)"), std::string::npos) << dup.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/m1/results.json"));
}

TEST(SuiteRun, MisbehavingCasesGetTheirOwnStatusAndTheRunGoesOn) {
  const std::string dir = scratchDir("statuses");
  writeText(dir + "/bad.json", R"({"schema": 1, "name": "bad", "defaults": {"timeout_seconds": 60}, "cases": [
    {"name": "crashes", "kind": "command", "steps": [["suite", "_case", "--mode", "crash"]]},
    {"name": "hangs", "kind": "command", "timeout_seconds": 1, "steps": [["suite", "_case", "--mode", "hang"]]},
    {"name": "flaky", "kind": "command", "steps": [["suite", "_case", "--mode", "fail-once", "--state", "{out}/state"]]},
    {"name": "known-flaky", "kind": "command", "steps": [["suite", "_case", "--mode", "fail-once", "--state", "{out}/state"]]},
    {"name": "fails", "kind": "command", "steps": [["suite", "_case", "--mode", "fail"]]},
    {"name": "expected/fails", "kind": "command", "steps": [["suite", "_case", "--mode", "pass"], ["suite", "_case", "--mode", "fail"]]},
    {"name": "expected/passes", "kind": "command", "steps": [["suite", "_case", "--mode", "pass"]]},
    {"name": "passes", "kind": "command", "steps": [["suite", "_case", "--mode", "pass"]]}]})");
  writeText(dir + "/baseline.json", R"({"schema": 1, "entries": [
    {"id": "known-failures", "case": "expected/.*", "status": "fail", "reason": "the test's expected failures"}]})");
  writeText(dir + "/flakes.txt", "# known\nknown-.*\n");
  const test::Run r = tessera("suite run '" + dir + "/bad.json' --jobs 2 --baseline '" + dir +
                                  "/baseline.json' --flakes '" + dir + "/flakes.txt' -o '" + dir + "/out'",
                              dir + "/out");
  EXPECT_EQ(r.exitCode, 1) << r.err;
  const json cases = readJson(dir + "/out/results.json")["cases"];
  ASSERT_EQ(cases.size(), 8u);
  std::map<std::string, json> by;
  for (const json& c : cases) by[c["name"]] = c;
  EXPECT_EQ(by["crashes"]["status"], "crash");
  EXPECT_EQ(by["crashes"]["exit"], "signal 6 (ABRT)");
  EXPECT_EQ(by["crashes"]["attempts"], 2);
  EXPECT_EQ(by["hangs"]["status"], "timeout");
  EXPECT_EQ(by["hangs"]["exit"], "timeout after 1 s");
  EXPECT_EQ(by["flaky"]["status"], "flake");
  EXPECT_EQ(by["flaky"]["first_attempt"], "exit 1");
  EXPECT_FALSE(by["flaky"].contains("known_flake"));
  EXPECT_EQ(by["known-flaky"]["status"], "flake");
  EXPECT_EQ(by["known-flaky"]["known_flake"], true);
  EXPECT_EQ(by["fails"]["status"], "fail");
  EXPECT_EQ(by["fails"]["figures"]["unexplained"], 7);
  EXPECT_EQ(by["expected/fails"]["status"], "expected-fail");
  EXPECT_EQ(by["expected/fails"]["attempts"], 1);  // an expected failure is not retried
  EXPECT_EQ(by["expected/fails"]["baseline"], "known-failures");
  EXPECT_EQ(by["expected/passes"]["status"], "unexpected-pass");
  EXPECT_EQ(by["passes"]["status"], "pass");
  // In suite order, whatever the completion order.
  for (size_t i = 0; i < cases.size(); ++i) EXPECT_EQ(cases[i]["index"], i);
  const json s = readJson(dir + "/out/results.json")["summary"]["statuses"];
  EXPECT_EQ(s["flake"], 2);
  EXPECT_EQ(s["pass"], 1);

  // The JUnit file parses with Python's xml.etree and counts: failures = fail, unexpected pass and the
  // unknown flake; errors = crash and timeout; skipped = the expected failure.
  const std::string py =
      "python3 -c \"import sys, xml.etree.ElementTree as E; r = E.parse(sys.argv[1]).getroot(); "
      "s = r.find('testsuite'); print(r.tag, s.get('tests'), s.get('failures'), s.get('errors'), "
      "s.get('skipped'), len(s.findall('testcase')))\" '" +
      dir + "/out/junit.xml' > '" + dir + "/py.txt'";
  if (std::system("python3 -c 'import xml.etree.ElementTree' 2>/dev/null") != 0) GTEST_SKIP() << "no python3";
  ASSERT_EQ(std::system(py.c_str()), 0);
  EXPECT_EQ(test::readText(dir + "/py.txt"), "testsuites 8 3 2 1 8\n");
}

TEST(SuiteRun, ACaseOverItsMemoryLimitIsACrashSaidToBeOutOfMemory) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: RLIMIT_AS cannot apply";
#endif
  const std::string dir = scratchDir("oom");
  // 512 MiB of address space: `tessera suite _case` starts at about 70 MiB (Release), and the oom mode
  // touches every block it gets, so the limit is what the case costs. At 1536 MiB it wrote 1.4 GB of
  // pages, the longest gtest case of the Release run (17 s; 28.6 s wall, 6.7 CPU-s alone on the loaded 2-core
  // machine, against 6.3 s wall, 1.5 CPU-s at 512 MiB).
  writeText(dir + "/oom.json", R"({"schema": 1, "name": "oom", "cases": [
    {"name": "oom", "kind": "command", "memory_limit": "512MiB", "steps": [["suite", "_case", "--mode", "oom"]]},
    {"name": "after", "kind": "command", "steps": [["suite", "_case", "--mode", "pass"]]}]})");
  const test::Run r = tessera("suite run '" + dir + "/oom.json' -o '" + dir + "/out'", dir + "/out");
  EXPECT_EQ(r.exitCode, 1) << r.err;
  const json cases = readJson(dir + "/out/results.json")["cases"];
  ASSERT_EQ(cases.size(), 2u);
  EXPECT_EQ(cases[0]["status"], "crash");
  EXPECT_EQ(cases[0]["detail"], "out of memory");
  EXPECT_EQ(cases[1]["status"], "pass");
}

TEST(SuiteRun, BadInputExitsTwoNamingFileAndField) {
  const std::string dir = scratchDir("badinput");
  const std::string suite = smallSuite(dir);
  writeText(dir + "/broken.json", R"({"schema": 1, "name": "b", "cases": [{"name": "x", "kind": "render"}]})");
  const test::Run a = tessera("suite run '" + dir + "/broken.json' -o '" + dir + "/o1'", dir + "/o1");
  EXPECT_EQ(a.exitCode, 2);
  EXPECT_NE(a.err.find("broken.json: case 0 (x): field 'scene': missing"), std::string::npos) << a.err;
  const test::Run b = tessera("suite run '" + suite + "' --fraction 0/3 -o '" + dir + "/o2'", dir + "/o2");
  EXPECT_EQ(b.exitCode, 2);
  EXPECT_NE(b.err.find("--fraction '0/3'"), std::string::npos) << b.err;
  writeText(dir + "/f.txt", "(\n");
  const test::Run c =
      tessera("suite run '" + suite + "' --flakes '" + dir + "/f.txt' -o '" + dir + "/o3'", dir + "/o3");
  EXPECT_EQ(c.exitCode, 2);
  EXPECT_NE(c.err.find("f.txt:1:"), std::string::npos) << c.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/o1/results.json"));
  // The test-only case stays out of the help.
  const test::Run h = tessera("suite --help", dir + "/help");
  EXPECT_EQ(h.exitCode, 0);
  EXPECT_NE(h.out.find("merge"), std::string::npos);
  EXPECT_EQ(h.out.find("_case"), std::string::npos) << h.out;
}

}  // namespace
}  // namespace tessera::cli::suite
