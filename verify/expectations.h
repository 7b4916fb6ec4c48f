// The expectations file: known deviations of a GL implementation from the oracle, each pinned to the
// implementation, its version, the run condition under which it shows, the frame and the draw
// (docs/expectations.md, tests/expectations/gl-deviations.json).
//
// Implements: loading and validating the file (every error names the file, the entry and the field),
// the run condition of a GL backend (driver, Mesa version, strict, llvmpipe's rasterizer threads),
// matching entries against a run, and applying the matched entries to a cross-check's verdicts: an
// unexplained pixel is re-labelled "expected deviation" only if it lies where the entry's draw writes
// in the oracle, and only while the entry's pixel allowance is not exceeded. Everything else stays
// unexplained, so a pinned deviation cannot hide a regression elsewhere in the frame.
// Does not implement: judging pixels (judge.h) or rendering (crosscheck.h calls applyExpectations).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/resource_limits.h"
#include "raster/command_list.h"

namespace tessera::gl {
class GlBackend;
}

namespace tessera::verify {

struct ImageVerdict;

// A comparison of an integer run parameter: "any", "N", "==N", "!=N", ">=N", "<=N", ">N", "<N".
struct IntCondition {
  enum class Op { Any, Eq, Ne, Ge, Le, Gt, Lt } op = Op::Any;
  int64_t value = 0;
  bool matches(int64_t v) const;
  std::string text() const;
};
// Parses the forms above; throws Error naming `where` on anything else.
IntCondition parseIntCondition(std::string_view text, const std::string& where);

// The conditions under which the GL side of a cross-check ran.
struct RunCondition {
  std::string implementation;  // "llvmpipe", "softpipe", "zink", or the GL_RENDERER's first word
  std::string version;         // Mesa version, "22.3.6"
  bool strict = false;         // GlOptions::strict (llvmpipe fast paths off)
  // llvmpipe's rasterizer threads: LP_NUM_THREADS when set, else the CPUs this process may run on
  // (sched_getaffinity, as Mesa's util_cpu_caps counts them), and 0 when that is 1 (llvmpipe then
  // rasterizes on the calling thread).
  int lpThreads = 0;
  nlohmann::json toJson() const;
};

// The condition of a created GL backend (its GlInfo and options).
RunCondition runConditionOf(const gl::GlBackend& gl);
// llvmpipe's default rasterizer thread count in this process (see RunCondition::lpThreads).
int defaultLpThreads();

struct Expectation {
  std::string id;              // unique, [a-z0-9_-]+
  std::string implementation;  // RunCondition::implementation, exact
  std::string versions;        // ECMAScript regex, must match the whole Mesa version
  std::optional<bool> strict;  // condition.strict; nullopt = either
  IntCondition lpThreads;      // condition.lp_threads
  std::string frame;           // a scene name or a .tframe path; matched by name or file name
  // frame_sha256: when set (64 lowercase hex digits), the frame must also be exactly this command list:
  // the SHA-256 of its .tframe encoding (raster/serialize.h encodeFrame, the bytes writeFrame stores).
  // For frames that tools write under generic names (mta render --record: frame_0000.tframe).
  std::string frameSha256;
  std::optional<size_t> draw;  // draw index (as crosscheck's bisection counts); nullopt = whole frame
  uint64_t pixels = 0;         // the most pixels this entry may cover in one run
  std::string reason;          // why: the analysis, or where it is (docs/...)
  std::string reproducer;      // repo-relative .tframe
};

struct ExpectationSet {
  std::string file;
  std::vector<Expectation> entries;
  // The entries whose implementation, versions, condition and frame match. `list` is the frame's command
  // list, which entries with frameSha256 need; without it they never match.
  std::vector<const Expectation*> matching(const RunCondition& run, std::string_view frame,
                                           const CommandList* list = nullptr) const;
};

// Throws Error("<file>: entry <i> (<id>): field '<name>': <reason>") for anything out of format.
ExpectationSet parseExpectations(const nlohmann::json& doc, const std::string& file);
ExpectationSet loadExpectations(const std::string& path);

// Per matched entry, what it covered in one cross-check.
struct ExpectationUse {
  const Expectation* entry = nullptr;
  uint64_t maskPixels = 0;  // pixels the entry's draw writes in the oracle (all pixels if draw is null)
  uint64_t matched = 0;     // unexplained pixels inside that mask
  bool covered = false;     // matched <= entry->pixels: those pixels became expected deviations
};

// Re-labels the unexplained pixels that the entries cover (failMap 2 -> 3, Judgement::unexplained
// decreases, ImageVerdict::expectedDeviation increases, their records leave firstUnexplained).
// The mask of an entry with a draw is the set of pixels whose oracle value after that draw differs
// from the value before it (two fast-path oracle renders of prefixes of `list`).
std::vector<ExpectationUse> applyExpectations(std::vector<ImageVerdict>& images, const CommandList& list,
                                              const std::vector<const Expectation*>& entries, int threads,
                                              const ResourceLimits& limits);

nlohmann::json toJson(const std::vector<ExpectationUse>& uses);

}  // namespace tessera::verify
