// Mutation testing of the cross-check (docs/mutants.md): the GL backend runs with each deliberate
// fault of gl/gl_mutation.h, and the oracle's verdict (judge.h, the rule of verify/crosscheck.h)
// must catch every one that GL does not allow.
//
// Implements: the mutant x frame table: the oracle rendered once per frame in provenance mode, GL
// once per frame unmodified (its unexplained pixels are the verdict's false alarms) and once per
// mutant x frame, every presented image judged; a mutant is killed by a frame when GL under the
// mutant has an unexplained pixel that the unmodified backend did not have (so a known false alarm
// never counts as a kill). Also the JSON of `tessera mutants` and its report directory.
// Does not implement: the mutants themselves (gl/gl_mutation.h) or the scenes (the CLI passes the
// frames in, as a library never depends on tools/).
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/resource_limits.h"
#include "gl/gl_backend.h"
#include "gl/gl_mutation.h"
#include "raster/command_list.h"

namespace tessera::verify {

struct MutantFrame {
  std::string name;  // the scene name
  CommandList list;
};

struct MutantsOptions {
  int threads = 0;  // oracle worker threads
  ResourceLimits limits;
  // Called with one line of progress per GL run (the CLI prints it on stderr).
  std::function<void(const std::string&)> progress;
};

struct MutantRow {
  const gl::Mutation* mutation = nullptr;
  std::string status;                    // "killed" | "survived" | "equivalent" (catalogued with an argument)
  bool verdictTooStrict = false;         // catalogued as equivalent, yet killed: the verdict rejects what GL allows
  bool killedByPin = false;              // ... and the mutant names the documented pin that kills it (Mutation::pin)
  std::vector<std::string> killedBy;     // frames with a new unexplained pixel
  std::vector<uint64_t> unexplained;     // per frame: unexplained pixels under the mutant
  std::vector<uint64_t> newUnexplained;  // per frame: of those, pixels the unmodified backend explains
};

struct MutantsResult {
  std::vector<std::string> frames;
  std::vector<uint64_t> falseAlarms;  // per frame: unexplained pixels of the unmodified backend
  std::vector<MutantRow> rows;
  double killedPercent = 0;  // killed / mutants not catalogued as equivalent
  double runtimeSeconds = 0;
  nlohmann::json json;  // as printed by `tessera mutants`
  // Every non-equivalent mutant killed, no equivalent one killed except through the documented pin it
  // names, and no false alarm.
  bool passed() const;
};

// Runs every mutation of `mutations` on every frame with `gl` (its mutation is reset to none at the
// end). Throws Error when a mutant does not compile or a frame fails to render.
MutantsResult runMutants(const std::vector<MutantFrame>& frames, const std::vector<const gl::Mutation*>& mutations,
                         gl::GlBackend& gl, const MutantsOptions& options);

// report.json (the JSON above) and index.html (the mutant x frame table, killed cells highlighted,
// the equivalence arguments), both written atomically into `dir` (created if missing).
void writeMutantsReport(const MutantsResult& result, const std::string& dir);

}  // namespace tessera::verify
