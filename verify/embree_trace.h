// The Embree half of the visibility oracle: one ray per pixel centre through the window-space
// triangles of a VisibilityScene.
//
// Implements: an Embree 3 device pinned to one ISA, one triangle geometry per
// draw (culled triangles left out), rays from (x + 1/2, y + 1/2, -1) along +z cast with rtcIntersect1
// in parallel over rows (oneTBB), and a filter function that makes the answer independent of BVH
// traversal order: it keeps the hit with the smallest t, breaking exact ties the way the depth test
// does (LESS: the earlier primitive stays, LEQUAL: the later one replaces it), and rejects hits on
// pixels outside the draw's viewport/scissor rectangle.
// Does not implement: comparison or classification (visibility_check.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "verify/visibility_scene.h"

namespace tessera::verify {

constexpr uint32_t kNoHit = 0xffffffffu;

struct EmbreeImage {
  int32_t width = 0, height = 0;
  std::vector<uint32_t> triangle;  // index into VisibilityScene::triangles or kNoHit, GL row order
  std::string version;             // Embree's runtime version, e.g. "3.13.5"
  std::string isa;                 // the ISA the device was created with
  uint64_t triangles = 0;          // triangles given to Embree
  double buildMs = 0, castMs = 0;
};

// Throws Error when no device can be created for any of `isas`.
EmbreeImage traceScene(const VisibilityScene& scene, const std::vector<std::string>& isas, int threads);

}  // namespace tessera::verify
