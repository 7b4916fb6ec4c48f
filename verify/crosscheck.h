// Oracle vs GL on one frame: render both, judge every presented image pixel by pixel against the
// oracle's provenance (judge.h), check that GL issued exactly the calls the oracle counted, and on
// failure bisect to the first draw whose output diverges.
//
// Implements: the cross-check of docs/crosscheck.md for one CommandList and the JSON that
// `tessera crosscheck` prints. Does not implement: the report directory (crosscheck_report.h) or the
// GL replay itself (gl/gl_backend.h).
#pragma once

#include <functional>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "base/resource_limits.h"
#include "gl/gl_backend.h"
#include "raster/command_list.h"
#include "verify/expectations.h"
#include "verify/judge.h"

namespace tessera::verify {

struct CrosscheckOptions {
  int threads = 0;     // oracle worker threads (GL's are set when its backend is created)
  bool bisect = true;  // on failure, find the first diverging draw
  bool selfCheck = false;  // "--backends cpu,cpu": judge the oracle's fast path against its own provenance
  ResourceLimits limits;   // the oracle's frame budget (the GL backend has its own: GlOptions::limits)
  // Known deviations (expectations.h): entries matching `condition` and the frame re-label the
  // unexplained pixels they cover as expected deviations. With a GL backend and no condition, the
  // condition is the backend's (runConditionOf).
  const ExpectationSet* expectations = nullptr;
  std::optional<RunCondition> condition;
  // GL_SUBPIXEL_BITS of the other side, for the edge margin (tolerance::edgeMarginSub). 0: taken from
  // the GL context (crosscheck with a GlBackend), the oracle's 8 for the self-check, else GL's minimum 4.
  int otherSubpixelBits = 0;
};

struct ImageVerdict {
  std::string name;  // "attachment 0" / "attachment 1, layer 2"
  PresentedImage image;
  Judgement judgement;
  std::vector<uint8_t> oracle, other, lo, hi;  // top-down pixels, the target's format
  uint64_t expectedDeviation = 0;  // unexplained pixels covered by an expectations entry (failMap 3)
};

struct CrosscheckResult {
  bool passed = false;
  std::vector<ImageVerdict> images;
  nlohmann::json json;  // everything, as printed by the CLI
};

// `gl` may be null only with options.selfCheck.
CrosscheckResult crosscheck(const CommandList& list, std::string_view frameName, const CrosscheckOptions& options,
                            gl::GlBackend* gl);

// The other side as a function: renders a list and returns its presented images in imagePixels()
// layout, in presentation order. Lets tests stand in for GL (e.g. to check the bisection).
struct OtherBackend {
  std::string name;
  std::function<std::vector<std::vector<uint8_t>>(const CommandList&, std::string_view, double& ms)> render;
};
CrosscheckResult crosscheck(const CommandList& list, std::string_view frameName, const CrosscheckOptions& options,
                            const OtherBackend& other);

// The pipeline state in force at command `index` (program, units, samplers, blend, depth, raster,
// viewport, scissor, target), for naming the state of a diverging draw.
nlohmann::json stateAt(const CommandList& list, size_t index);

}  // namespace tessera::verify
