// Which pixels of an 8x8 block a triangle covers, as one 64-bit mask, with a Highway kernel on every
// target raster/simd_targets.h lists and a scalar reference.
//
// Implements: blockCoverageKernel(). Bit 8 y + x of the mask is pixel (bx + x, by + y) of the block;
// it is set iff e_i(x, y) - bias_i >= 0 for the three edges, where e_i(x, y) = e0_i + x dx_i + y dy_i
// is the exact int64 edge value at the pixel centre (rast.cpp, the fill rule of docs/spec-choices.md
// R3). Integer arithmetic only, so every target gives the reference's mask: each lane adds and
// subtracts int64 exactly (|e| < 2^55 and |dx|, |dy| < 2^36 by limits.h's guard band, so nothing
// overflows) and reads the sign of the OR of the three differences.
// Does not implement: the triangle's bounding box or the tile's bounds (rast.cpp masks those), the
// trivial reject or accept of a whole block (rast.cpp decides those before calling).
#pragma once

#include <cstdint>

namespace tessera::detail {

// Set once per triangle (setSteps) and per block (e0, the rows).
struct BlockEdges {
  int64_t e0[3];    // edge values at the centre of the block's first pixel (bx, by)
  int64_t dx[3];    // one pixel right
  int64_t dy[3];    // one pixel up
  int64_t bias[3];  // TriSetup::bias: 0 for an inclusive edge, 1 otherwise
  int32_t rowBegin = 0, rowEnd = 8;  // only rows [rowBegin, rowEnd) are tested; the others' bits are 0
  alignas(64) int64_t stepX[3][8];   // x dx_i - bias_i for x = 0..7 (exact: |dx| < 2^36)

  // By additions (x dx_i - bias_i exactly, as |x dx_i| < 2^39): x86-64 has no vector 64-bit multiply, and
  // the multiplying form was a hundred instructions per triangle.
  void setSteps() {
    for (int i = 0; i < 3; ++i) {
      int64_t v = -bias[i];
      for (int x = 0; x < 8; ++x, v += dx[i]) stepX[i][x] = v;
    }
  }
};

using BlockCoverageFn = uint64_t (*)(const BlockEdges& b);

// The kernel of the target running now, or the scalar reference under "reference". Resolve it once
// per tile: a dispatch calls into libhwy.
BlockCoverageFn blockCoverageKernel();

}  // namespace tessera::detail
