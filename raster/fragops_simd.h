// The colour write's conversion to unorm8 (fragops.h toUnorm8: clamp to [0, 1] with NaN -> 0, then
// round half to even of c * 255) for the 16 values of a quad (4 pixels x RGBA) as a Highway kernel, on
// every target raster/simd_targets.h lists.
//
// Implements: unorm8QuadKernel(), whose bytes are toUnorm8's for every float input: each lane widens
// the float to double (exact), multiplies by 255 (exact: 24 x 8 bits), rounds half to even by adding
// and subtracting 1.5 * 2^52 (valid below 2^51, as raster/round.h's roundHalfEvenNear), and selects 0
// where !(c > 0) and 255 where c >= 1, the same comparisons in the same order as toUnorm8; the integer
// in [0, 255] then narrows exactly. Under "reference" it is toUnorm8 per value.
// Does not implement: blending, other formats (fragops.cpp writeFragment).
#pragma once

#include <cstdint>

namespace tessera::detail {

// out[i] = toUnorm8(in[i]) for i < 16.
using Unorm8QuadFn = void (*)(const float* in, uint8_t* out);

// The kernel of the target running now. Resolve it once per triangle: a dispatch calls into libhwy.
Unorm8QuadFn unorm8QuadKernel();

}  // namespace tessera::detail
