// A suite file (docs/suite.md): the documented JSON list of cases that `tessera suite run` executes,
// expanded into concrete command lines, and the --fraction K/M selection of one shard.
//
// Implements: reading and validating a suite (schema 1; every error names the file, the case index and
// the field), the case kinds (render, replay, crosscheck, visibility, compare, golden, mutant,
// command) and how each becomes one or more `tessera` command lines, the expansion of "scene": "*"
// (every built-in scene) and of file globs into one case per item with a stable name, the
// placeholders {out} (the case's output directory) and {repo} (the clone's root), the filter by
// --backends, and the shard selection.
// Does not implement: running the cases (suite_run.h) or judging their results (suite_results.h).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tessera::cli::suite {

struct SuiteCase {
  size_t index = 0;  // position in the expanded suite (after the --backends filter), from 0
  std::string name;  // stable, unique: [A-Za-z0-9._@+=-] segments joined by '/'
  std::string kind;  // the suite file's kind
  // One `tessera` command line (without the executable) per step; the steps run one after the other
  // and the case passes when every step exits 0. Placeholders are still in ({out}).
  std::vector<std::vector<std::string>> steps;
  bool needsGl = false;
  double timeoutSeconds = 300;
  uint64_t memoryBytes = 0;  // RLIMIT_AS of each step's process; 0 = none
};

struct Suite {
  std::string file;    // as given
  std::string name;    // the suite's "name"
  std::string sha256;  // of the file's bytes: shards of one run must read the same suite
  std::vector<SuiteCase> cases;
};

struct LoadOptions {
  bool gl = true;        // --backends includes gl; otherwise cases that need GL are left out
  std::string glDriver;  // --gl-driver, passed to every case that runs GL ("" = the default)
};

// Throws Error "<file>: case <i> (<name>): field '<f>': <reason>" (or "<file>: <reason>") on anything
// out of format, including duplicate names and globs that match nothing.
Suite loadSuite(const std::string& path, const LoadOptions& options);

// --fraction K/M: K is 1-based (1..M, as GitLab's CI_NODE_INDEX), M >= 1.
struct Fraction {
  size_t k = 1, m = 1;
  std::string text() const { return std::to_string(k) + "/" + std::to_string(m); }
};
// Throws Error "--fraction '<text>': <reason>".
Fraction parseFraction(std::string_view text);
// The cases with index % M == K - 1: every M-th case starting at the K-th. For a fixed M the shards
// K = 1..M are disjoint and their union is the whole list.
std::vector<SuiteCase> selectFraction(const std::vector<SuiteCase>& cases, const Fraction& f);

// Whether `name` is a valid case name (see SuiteCase::name).
bool isValidCaseName(std::string_view name);

// The clone's root (the folder holding golden/manifest.json, found like repoPath), absolute.
std::string repoRoot();

}  // namespace tessera::cli::suite
