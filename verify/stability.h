// Is the GL side of a cross-check a function of the frame alone? Renders the GL side again under
// other conditions (a second run in the same process, another process, LP_NUM_THREADS = 1 and N, one
// visible CPU, strict mode) and compares every presented image byte for byte with a reference run.
// Any change is reported as "GL nondeterministic / fast-path dependent", with the first draw whose
// output changes (found by bisecting the command list's draw prefixes, as crosscheck.h does).
//
// Implements: the condition catalogue, the comparison, the bisection and the JSON.
// Does not implement: rendering under a condition. llvmpipe reads its environment once per process
// (gl/gl_backend.h), so the caller supplies a StabilityRenderer that runs each condition in a fresh
// process (`tessera crosscheck --stability` spawns itself; tests pass a function).
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "raster/command_list.h"

namespace tessera::verify {

struct StabilityCondition {
  std::string name;         // "repeat_in_process", "lp_threads_1", ...
  std::string description;  // what differs from the reference
  std::vector<std::pair<std::string, std::string>> env;  // set in the child before GL starts
  bool strict = false;      // GlOptions::strict
  bool oneCpu = false;      // the child restricts itself to one CPU (sched_setaffinity) before GL starts
  int runs = 1;             // renders in the same process; with 2, run 1 is compared with run 0
};

// The reference (index 0: Mesa's defaults, one run) followed by the conditions compared with it.
// `cpus` = the CPUs this process may use; the LP_NUM_THREADS = N condition uses N = max(cpus, 2).
std::vector<StabilityCondition> stabilityConditions(int cpus);

// runs x presented images x bytes (imagePixels() layout).
using GlRuns = std::vector<std::vector<std::vector<uint8_t>>>;
// Renders the list, or its prefix through draw `throughDraw` (the draw's command included), under a
// condition. Returns condition.runs runs.
using StabilityRenderer = std::function<GlRuns(const StabilityCondition&, std::optional<size_t> throughDraw)>;

struct StabilityOptions {
  bool bisect = true;  // name the first draw whose output changes
};

// Compares every condition with the reference; pixelsPerImage[i] = width * height of presented image i
// (to count pixels, not bytes). JSON:
// {"stable", "verdict", "reference", "conditions": [{"name", "description", "env", "strict", "one_cpu",
//   "identical", "images": [{"image", "differing_pixels", "differing_bytes"}], "first_changing_draw"}]}.
nlohmann::json checkStability(const CommandList& list, const std::vector<StabilityCondition>& conditions,
                              const StabilityRenderer& render, const std::vector<size_t>& pixelsPerImage,
                              const StabilityOptions& options = {});

// A small HTML page of that JSON (one row per condition), for a report directory.
std::string stabilityHtml(const nlohmann::json& stability, const std::string& frame);

}  // namespace tessera::verify
