// Why an RTTA capture region can differ from its object rendered alone (and so a depth composite from
// STD): the capture draws each triangle displaced by T in clip space, x' = (a x + b y) + tx w in float
// (Trapp & Döllner 2010 §2.3: (T (v / w)) w without the division), and cut by four clip planes at the
// screen edges. Where the float displacement rounds, a vertex can snap to a neighbouring 1/256-px
// position in the atlas, and a triangle the planes (or the near / far planes) cut gets new vertices
// computed from displaced positions. Every other triangle lands exactly shifted by whole pixels, with
// the same depth and w, so its coverage, interpolation and LOD are the same bits.
//
// Implements: replaying, per triangle of every visible object, the program's float transform and
// displacement and the pipeline's division, viewport transform and snapping (raster/setup.cpp
// toWindow, round half to even) on both paths, and marking the screen pixels that a triangle whose
// snapped vertices do not move by exactly the shift (or that clipping cuts) may touch.
// Does not implement: explaining depth ties between objects (composites order objects by id, STD by
// texture), or anything about GL (the cross-check judges GL against the oracle's own capture).
#pragma once

#include <cstdint>
#include <glm/mat4x4.hpp>
#include <span>
#include <vector>

#include "raster/types.h"
#include "rtta/packing.h"
#include "rtta/record.h"
#include "rtta/rtta_scene.h"

namespace tessera::rtta {

struct ShiftExplanation {
  // Per screen pixel (row y * width + x, GL window rows bottom first): 1 = a rounded triangle may touch
  // it, 2 = a clipped one may, 3 = both; 0 = the capture there is the alone rendering shifted.
  std::vector<uint8_t> mask;
  uint64_t triangles = 0, rounded = 0, clipped = 0;  // of visible objects
};

ShiftExplanation explainShift(const RttaScene& scene, std::span<const Record> records, const glm::mat4& mvp,
                              const Rect& vp, const AtlasSize& atlas);

}  // namespace tessera::rtta
