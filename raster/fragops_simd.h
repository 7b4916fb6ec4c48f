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

// texels[4 p + k] = blendSourceOverRgba8(src + 4 p, texels + 4 p)[k] for the quad's pixels p < 4:
// src is the program's RGBA per pixel, texels the destination RGBA8 bytes, updated in place.
using BlendSourceOverQuadFn = void (*)(const float* src, uint8_t* texels);
BlendSourceOverQuadFn blendSourceOverQuadKernel();

}  // namespace tessera::detail
