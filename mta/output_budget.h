// A build that cannot run away (issue 14 §2): the output limit and the choice of d_min by size.
//
// Implements: the grid of d_min values that --fit and the refusal message choose from (two significant
// digits: ..., 0.98, 0.99, 1, 1.1, ..., 9.9, 10, 11, ...: readable, and each step is at most 10 %
// coarser), the search for the finest d_min whose planned file fits a byte limit (planning only, never
// writing: galloping up the grid from the finest allowed value, then bisection), and the messages that
// refuse a plan over the limit. Deterministic: the result depends only on the scene, the parameters and
// the limit (plans are), never on threads, time or the machine.
// Does not implement: the plan (build_plan.h), the size (output_size.h), free-space queries (the CLI
// passes the limit it derived, with its reason).
#pragma once

#include <cstdint>
#include <string>

#include "mta/build_plan.h"
#include "mta/output_size.h"

namespace tessera::mta {

// The grid: index i is m · 10^(e − 1) with e = floor(i / 90) and m = 10 + (i mod 90), so index 0 is 1.0;
// computed as one exact product or one correctly rounded quotient of integers, so it prints as written.
// Indices cover 1e-21 .. 9.9e23.
constexpr int64_t kDMinGridFirst = -21 * 90, kDMinGridLast = 24 * 90 - 1;
double dMinGridValue(int64_t index);
// The smallest index whose value is > d (kDMinGridLast + 1 if none).
int64_t dMinGridIndexAbove(double d);
// Shortest decimal text that reads back as `d` ("7.3", "0.29", "1e-05").
std::string formatDMin(double d);

// What a build may write. maxBytes 0: unchecked (the library's default; `tessera mta build` always sets
// it). maxReason follows the limit in messages, e.g. " (the free space in /data; ...)".
// fitBytes > 0: d_min is chosen by fitDMin for that size (BuildParams::dMin must then be 0).
struct OutputGuard {
  uint64_t maxBytes = 0;
  std::string maxReason;
  uint64_t fitBytes = 0;
};

struct DMinFit {
  bool found = false;
  double dMin = 0.0;        // found: the chosen d_min (requested; critical triangles may raise it)
  BuildPlan plan;           // found: the plan at dMin; else the coarsest plan tried
  OutputEstimate estimate;  // of `plan`
  double finerDMin = 0.0;   // found: the next finer candidate (the finest allowed, or the grid value below)
  uint64_t finerBytes = 0;  // its estimate (> limit)
  uint32_t plans = 0;       // plans evaluated
};

// The finest d_min among {finest} ∪ {grid values > finest} whose file fits `maxBytes`, where finest =
// resolveDMin(scene, params) (params.dMin or D / divisor). The search assumes nothing about monotony:
// whatever it returns fits, and its next finer candidate was planned and does not. It gallops up the grid
// (finest, then 1, 2, 4, ... steps above) and bisects; it gives up (found = false) when a plan is one
// atlas per tree and still too big (nothing coarser is smaller), or past d = 4 · D · w_screen /
// (2 · tan(φ/2) · τ), where the whole scene needs a quarter texel. finestEstimate: the caller already
// planned `finest` and it does not fit (saves one plan).
DMinFit fitDMin(const Scene& scene, const BuildParams& params, uint64_t maxBytes,
                const OutputEstimate* finestEstimate = nullptr);

// Throws the refusal (Error, exit 2 in the CLI) for a plan over guard.maxBytes, after searching the d_min
// that would fit: "mta build: the tree would take <size> (<n> nodes, <n> leaves at d_min <d>) but
// --max-output is <size><reason>; d_min <d> fits (<size>, <n> nodes): pass --d-min <d>, or --fit <size>,
// or raise --max-output". Does nothing when the plan fits or maxBytes is 0.
void refuseIfTooBig(const Scene& scene, const BuildParams& params, const BuildPlan& plan,
                    const OutputEstimate& estimate, const OutputGuard& guard);

// "8GiB", "1536MiB", "1000": the exact size as an option value (the largest binary unit that divides it).
std::string byteSizeArgument(uint64_t bytes);
// 18168 -> "18,168".
std::string groupThousands(uint64_t n);

}  // namespace tessera::mta
