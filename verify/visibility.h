// Embree visibility oracle: an independent answer to "which triangle is nearest at each pixel
// centre", used to check the CPU oracle's coverage, fill rule and depth test on ID frames.
//
// Implements:
// - castVisibility(): replays the frame's state (independent vertex fetch; the SAME Program objects
//   for the vertex and geometry stages; clipping through raster/clip.h), builds an Embree scene of
//   the window-space triangles (z = window depth) that the presented target's draws produce, casts
//   one ray per pixel centre (x + 1/2, y + 1/2) along +z and reports, per pixel, the flat object id,
//   the primitive id and the depth of the nearest hit;
// - the comparison with the oracle's ID targets (rendered with CpuBackend), where every mismatching
//   pixel must be explained by a triangle edge within `edgeEpsilon` of the pixel centre or by a depth
//   near-tie within the float32 bound; everything else is "unexplained". docs/visibility.md derives
//   both bounds.
// Scope (anything else is an Error naming the command): the draws issued while the presented render
// target (the one bound when the list ends) is bound, non-layered, program "object_id", depth test on
// with LESS or LEQUAL and depth writes on, a depth attachment, clears of that target only before its
// first draw and never scissored.
// Does not implement: coverage of anything but pixel centres (single sample), blending, discard.
//
// Coordinates are GL window coordinates: x to the right, y UP from the bottom row (row 0 = bottom),
// as in the oracle's TextureData. Image files store the top row first: file_y = height - 1 - y.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/resource_limits.h"
#include "raster/command_list.h"

namespace tessera::verify {

// The most the oracle's snapping (8 sub-pixel bits, round half to even per axis) moves a vertex, and
// therefore any point of an edge: sqrt(2) / 512 px. edgeEpsilon must not be smaller.
constexpr double kMaxSnapDisplacement = 0.0027621358640099515;

struct VisibilityOptions {
  int threads = 0;                   // rays and the oracle render; 0 = all hardware threads
  double edgeEpsilon = 1.0 / 256.0;  // px; docs/visibility.md "Edge bound"
  size_t maxListed = 20;             // first_unexplained entries kept
  // Embree ISA, pinned so that Embree's own float arithmetic is the same on every machine of a kind.
  // Tried in order; the first that creates a device wins.
  std::vector<std::string> isas = {"avx2", "sse4.2"};
  ResourceLimits limits;  // the frame budget of the oracle render and of validation (raster/validate.h)
};

// The ID images of a frame, GL row order (row 0 = bottom), width * height entries each.
struct IdImages {
  int32_t width = 0, height = 0;
  std::vector<uint32_t> object;     // attachment 0
  std::vector<uint32_t> primitive;  // attachment 1
  std::vector<float> depth;         // the depth attachment; empty when unknown
};

struct UnexplainedPixel {
  int32_t x = 0, y = 0;  // GL window coordinates
  uint32_t oracleObject = 0, oraclePrimitive = 0;
  uint32_t embreeObject = 0, embreePrimitive = 0;
  double oracleDepth = 0, embreeDepth = 0;  // NaN when unknown (background or no depth attachment)
  double edgeDistance = 0;                  // px to the nearest triangle boundary; +inf if none near
  std::string reason;
};

struct VisibilityResult {
  int32_t width = 0, height = 0;
  uint64_t draws = 0, triangles = 0;  // in-scope draws; window-space triangles given to Embree
  uint64_t primitivesClipped = 0;     // primitives that went through clipTriangle
  uint64_t pixels = 0, matching = 0;
  double exactMatchPercent = 0;
  uint64_t mismatches = 0;
  uint64_t backgroundMismatches = 0;  // one side background, the other a triangle
  uint64_t explainedEdge = 0;
  uint64_t explainedDepthTie = 0;
  // Embree disagreed but the double-precision reference agrees with the oracle exactly (Embree's own
  // float error); kept apart so it cannot hide anything.
  uint64_t explainedReference = 0;
  uint64_t unexplained = 0;
  std::vector<UnexplainedPixel> firstUnexplained;
  // How much of the bounds the explained pixels used (evidence that the bounds are not loose).
  double maxEdgeDistanceUsed = 0;  // px, over edge-explained pixels
  double maxDepthTieUsed = 0;      // |z_oracle_choice - z_nearest|, over depth-tie pixels
  // Depth attachment vs the reference plane at pixels whose ids match.
  uint64_t depthChecked = 0, depthOutOfTolerance = 0;
  double depthMaxAbsDiff = 0;
  double edgeEpsilon = 0;
  std::string embreeVersion, embreeIsa;
  double buildMs = 0, castMs = 0;  // wall time of the Embree build and the ray cast (not deterministic)
  IdImages embree;                 // the ray-cast images (depth = reference plane depth, float)
  // The frame was not drawn with object_id and was checked through rewriteToObjectIds()
  // (visibility_rewrite.h): object id = draw index.
  bool rewrittenToObjectId = false;
};

// Casts the frame and compares it with the CPU oracle's render of the same list. A frame whose
// presented target was drawn with other programs is first rewritten to object_id
// (visibility_rewrite.h); the ids are then draw indices.
VisibilityResult castVisibility(const CommandList& list, const VisibilityOptions& options = {});

// The parts, for callers that have the oracle images already (or want to perturb them).
// Renders `list` on CpuBackend and reads attachments 0 and 1 (R32UI) and the depth of the final target.
IdImages renderOracleIds(const CommandList& list, int threads = 0, const ResourceLimits& limits = {});
VisibilityResult compareVisibility(const CommandList& list, const IdImages& oracle,
                                   const VisibilityOptions& options = {});

// Every figure of the result; timing only when asked (it is the one non-deterministic part).
nlohmann::json visibilityToJson(const VisibilityResult& result, bool includeTiming = false);

}  // namespace tessera::verify
