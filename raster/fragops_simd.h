// The colour write's conversion to unorm8 (fragops.h toUnorm8: clamp to [0, 1] with NaN -> 0, then
// round half to even of c * 255) for the 16 values of a quad (4 pixels x RGBA) as a Highway kernel, on
// every target raster/simd_targets.h lists.
//
// Implements: unorm8QuadKernel(), whose bytes are toUnorm8's for every float input: each lane widens
// the float to double (exact), multiplies by 255 (exact: 24 x 8 bits), rounds half to even by adding
// and subtracting 1.5 * 2^52 (valid below 2^51, as raster/round.h's roundHalfEvenNear), and selects 0
// where !(c > 0) and 255 where c >= 1, the same comparisons in the same order as toUnorm8; the integer
// in [0, 255] then narrows exactly. Under "reference" it is toUnorm8 per value.
//
// Also blendSourceOverQuadKernel(): fragops.h blendSourceOverRgba8 for a whole quad, whose bytes are
// that function's: the per-pixel factors a = clamp01(src alpha) and 1 - a are formed as there, the
// destination doubles are the IEEE quotients texel / 255 that its table holds, and each lane runs the
// same IEEE double
// operations in the same order (clamp01 of the source, s * a, d * (1 - a), their sum) followed by
// toUnorm8's steps as above. No operation is fused or reordered.
// Does not implement: other blend forms, other formats (fragops.cpp writeFragment).
#pragma once

#include <cstdint>

namespace tessera::detail {

// out[i] = toUnorm8(in[i]) for i < 16.
using Unorm8QuadFn = void (*)(const float* in, uint8_t* out);

// The kernel of the target running now. Resolve it once per triangle: a dispatch calls into libhwy.
Unorm8QuadFn unorm8QuadKernel();

// blendSourceOverRgba8(src + 4 p, texel p) for the quad's pixels p < 4: src is the program's RGBA per
// pixel; the destination RGBA8 texels, updated in place, are row0[0..7] (pixels 0, 1) and row1[0..7]
// (pixels 2, 3). The rows are the target's own bytes: a copy through a 16-byte buffer cost a failed
// store forwarding per row (the kernel stores a pixel's 4 bytes, the copy then loaded 8).
using BlendSourceOverQuadFn = void (*)(const float* src, uint8_t* row0, uint8_t* row1);
BlendSourceOverQuadFn blendSourceOverQuadKernel();

}  // namespace tessera::detail
