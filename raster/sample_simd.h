// The sampler's SIMD path: the exact RGBA8 LINEAR lookup for the pixels of one or more quads, compiled by
// Google Highway for every x86 target it can attain (SSSE3, SSE4, AVX2, AVX-512 and its one-lane
// scalar target) and chosen at run time for the CPU.
//
// Implements: sampleQuadRgba8Linear(), which gives the bytes of sample.cpp's scalar filter
// (samplePlanned<RGBA8>) for the plans it accepts: LINEAR within a level, one or two levels, wrap
// REPEAT on a power-of-two size or CLAMP_TO_EDGE on any size (per axis and level), no CLAMP_TO_BORDER,
// one array layer for the four lookups, w * h < 2^31 texels per layer, and |s * w|, |t * h| <= 2^14
// for every lookup and level (NaN fails that). For anything else it returns false and writes nothing
// the caller needs: the caller then runs the scalar filter, which stays the readable reference.
// Does not implement: NEAREST, other formats, other wraps, borders (all scalar), provenance mode's
// interval lookups (they call the scalar filter through sampleN with the kernel or without: same bits).
//
// Why the bits are the scalar filter's, on every target (docs/spec-choices.md A1, T7, T8):
//   - u = s * w and v = t * h are one IEEE float multiply each, as in the scalar code.
//   - 256 u is exact in float; it is rounded half to even by adding and subtracting 1.5 * 2^23, two
//     IEEE additions that round to nearest even, valid for |256 u| <= 2^22 (raster/round.h gives the
//     same argument in double); the scalar code rounds the same real number in double.
//   - Everything after is integer arithmetic with no wrap-around: each channel's sum is
//     levelW * (nb * (na t00 + a t10) + b * (na t01 + a t11)) <= 255 * 2^24 < 2^32, the same integer as
//     the scalar t00 (na nb levelW) + t10 (a nb levelW) + t01 (na b levelW) + t11 (a b levelW), whatever
//     the order; two 8-bit channels share a 32-bit lane in the first step (na t + a t' <= 255 * 256
//     cannot carry into the next 16 bits).
//   - The last step, float(double(sum) * kUnormReciprocal), is the scalar code's, in scalar code.
// Fused multiply-add, approximate reciprocals and float reductions are not used (tools/lint_fp.sh).
#pragma once

#include <cstddef>
#include <cstdint>
#include "raster/sample_detail.h"

namespace tessera::sample_simd {

// The kernel: out[i] = RGBA of lookup i at (s[i], t[i]) in `layer` (already clamped to p.lastLayer) for
// i < n, n a multiple of 4 (whole quads; several quads sharing one plan but for the level weights fill
// the target's wider vectors), or false when n is not, or the plan or a coordinate is outside what the
// kernel takes (see above); out is then partly written. weightL[i], when not nullptr, replaces
// p.levelWeight[L] for lookup i (the lookup's own plan's weight). Precondition: p is complete and its
// texture is RGBA8.
using Rgba8LinearFn = bool (*)(const sample_detail::Plan& p, uint32_t layer, const float* s, const float* t,
                               size_t n, const uint32_t* weight0, const uint32_t* weight1, float (*out)[4]);

// The kernel of the target running now (raster/simd_targets.h), nullptr under "reference". Resolve it
// once per triangle, not per quad: the dispatch is a call into libhwy.
Rgba8LinearFn rgba8LinearKernel();

// rgba8LinearKernel() and a call of it on one quad (n = 4); false under "reference".
bool sampleQuadRgba8Linear(const sample_detail::Plan& p, uint32_t layer, const float* s, const float* t,
                           float (*out)[4]);

}  // namespace tessera::sample_simd
