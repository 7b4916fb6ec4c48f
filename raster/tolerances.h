// The tolerances of provenance mode, in one place: how far a conformant GL implementation may move a
// result away from the oracle's because the GL 4.6 spec leaves it a freedom. Each constant cites the
// section that grants the freedom and the docs/crosscheck.md row (ambiguity class) that derives its
// value; the choices they refer to (R1, T7, ...) are the rows of docs/spec-choices.md.
//
// Implements: the values only. raster/rast_provenance.cpp applies the coverage, depth, output and
// blend tolerances, raster/rast.cpp the clear-colour one, raster/sample_interval.cpp the lookup ones.
// Does not implement: the intervals (provenance.h) or the comparison against GL (verify/judge.cpp).
// A value is changed only after its derivation in docs/crosscheck.md is (CONTRIBUTING.md, "Cross-checking
// against GL"); never to make a scene pass.
#pragma once

#include <cstdint>

namespace tessera::tolerance {

// ---- coverage and interpolation (rast_provenance.cpp) -------------------------------------------

// Edge margin, in sub-pixels (1/256 px) of distance between a pixel centre and an edge line, for an
// implementation with `bits` sub-pixel bits (GL_SUBPIXEL_BITS; GL 4.6 §14.5 requires at least 4).
// §14.5 leaves the snapping rule free (spec-choices R1): GL's snapped vertex is one of the grid points
// around the exact position (round or truncate, per axis), the oracle's the nearest 1/256 point. With
// the same grid (8 bits) the two are at most one grid step apart per axis; with another grid at most
// half the oracle's step plus one of GL's. A segment whose endpoints move by at most d moves by at most
// d everywhere, and d = sqrt(2) * (per-axis bound). docs/crosscheck.md, row EDGE_TIE.
inline double edgeMarginSub(int bits) {
  constexpr double kSqrt2 = 1.4142135623730951;
  if (bits == 8) return kSqrt2;
  const int b = bits < 4 ? 4 : (bits > 24 ? 24 : bits);
  return kSqrt2 * (0.5 + 256.0 / double(1 << b));
}

// The same per-axis bound on how far GL's snapped vertex may sit from the oracle's, in pixels: one
// 1/256 step at 8 bits, else half the oracle's step plus one of GL's. A point inside a triangle moves
// with the affine interpolation of its vertices' moves, so by at most this much per axis too; its
// depth at a fixed pixel centre then changes by at most (|dz/dx| + |dz/dy|) times it.
// docs/crosscheck.md, row DEPTH_NEAR_EQUAL.
inline double vertexSnapPx(int bits) { return edgeMarginSub(bits) / (1.4142135623730951 * 256.0); }

// Relative error of a clip-space component of a vertex that clipping made, in units of the largest
// clip-space magnitude among the primitive's vertices: 2^-18. GL 4.6 §13.7 gives the new vertex
// exactly (P = t P1 + (1 - t) P2 with t from the clip distances), §2.3.4.1 leaves the precision to the
// implementation. Assumption: IEEE float32 (unit roundoff 2^-24) and at most 64 roundings of
// quantities bounded by that magnitude along the vertex's chain (per clip plane: the two distances,
// their difference, the quotient t, and per component a difference, a product and a sum, about ten
// roundings; six planes in sequence). docs/crosscheck.md, row CLIP_EDGE.
constexpr double kClipVertexRel = 1.0 / 262144.0;  // 2^-18

// Sample-position shift, in pixels: two implementations each half a snapping step (1/256 px, GL 4.6
// §14.5, R1) off see the same pixel centre up to 1/128 px apart. Multiplied by the per-pixel gradient
// of whatever is interpolated (depth, texture coordinates, program outputs). docs/crosscheck.md, rows
// DEPTH_NEAR_EQUAL, SUBTEXEL_NEAR_HALF and OUTPUT_ROUNDING.
constexpr double kSamplePosPx = 1.0 / 128.0;

// Float interpolation error, relative to the value: 2^-20. GL 4.6 §14.6.1 leaves the precision of
// interpolation free (R5); §13.8 that of depth. Applies to depth, texture coordinates and program
// outputs. docs/crosscheck.md, rows DEPTH_NEAR_EQUAL, SUBTEXEL_NEAR_HALF and OUTPUT_ROUNDING.
constexpr double kInterpRel = 1.0 / 1048576.0;  // 2^-20

// Absolute depth error: 2^-21. GL 4.6 §13.8 (depth precision is not specified, spec-choices V5).
// Like kInterpRel and the position terms, it bounds one fragment's depth; a depth test adds the bounds
// of both fragments, the stored one's kept per candidate (CandidateDepth in provenance.h).
// docs/crosscheck.md, row DEPTH_NEAR_EQUAL.
constexpr double kDepthAbs = 1.0 / 2097152.0;  // 2^-21

// ---- per-fragment operations (rast_provenance.cpp, rast.cpp) ------------------------------------

// Blend arithmetic error, in [0, 1] units: 2.5 LSB of unorm8 before the final rounding of each blended
// write. GL 4.6 §17.3.6.1: blending is carried out "with a precision and dynamic range no lower than
// that used to represent destination components" (8 bits here). Assumption: every intermediate is
// rounded to that precision at most once: the source, the source factor and the destination factor
// (the destination is already 8-bit), and the two products. Each rounding errs by at most 1/2 LSB and
// carries into the result with a weight of at most 1 (the other operand is in [0, 1]): 5 * 1/2 LSB.
// docs/crosscheck.md, row BLEND_PRECISION.
constexpr double kBlendUnorm = 2.5 / 255.0;

// Relative error of a unorm clear colour converted in float32: 2^-24 of c * 255. GL 4.6 §17.4.3.1
// converts the clear colour as §2.3.5.2 says (float to unorm, spec-choices F3: round to nearest, a tie
// either way). Assumption: the implementation forms c * (2^8 - 1) as one float32 product (or more
// precisely), whose rounding error is at most the unit roundoff 2^-24 relative; the product may then
// land on a tie. docs/crosscheck.md, row OUTPUT_ROUNDING ("clear colours").
constexpr double kClearRel = 1.0 / 16777216.0;  // 2^-24

// ---- texture lookups (sample_interval.cpp) ------------------------------------------------------

// LOD error, in 8.8 fixed point: 1/16 in lambda. GL 4.6 §8.14.1 leaves the precision of lambda free
// (spec-choices T3); llvmpipe's piecewise-linear log2 errs by <= 0.043 in lambda, dEQP allows 2^-4.
// (The rho approximations of §8.14.1 eq. 8.7 and coarse vs fine derivatives are enumerated, not
// toleranced.) docs/crosscheck.md, row LOD_NEAR_SWITCH.
constexpr int32_t kLod8 = 16;

// Half an 8-bit weight step, in texels: 1/512. GL 4.6 §8.14.2 leaves the precision of the LINEAR
// weights free (spec-choices T7); an implementation with exact weights differs from 8-bit ones by at
// most half a step. docs/crosscheck.md, row SUBTEXEL_NEAR_HALF.
constexpr double kWeightTexel = 1.0 / 512.0;

// Array layer coordinate: r + 1/2 within 2^-16 of an integer may select either layer. GL 4.6 §8.14.2
// rounds with floor (spec-choices T10), Vulkan prefers round-half-even, and an interpolated r carries
// float error. docs/crosscheck.md, row LAYER_TIE.
constexpr float kLayer = 1.0f / 65536.0f;  // 2^-16

// Filter arithmetic error of a unorm lookup that blends texels with a fractional weight, in [0, 1]
// units: 1 LSB. GL 4.6 §8.14.2 gives the filter exactly and leaves its precision free (spec-choices
// T8 is the oracle's exact choice); the weights' own precision is kWeightTexel. Assumption: the
// weighted texels are accumulated without intermediate quantization (as a fixed-point sum with 8-bit
// or finer weights) and the sum is rounded or truncated once to the texel precision: an error below
// 1 LSB. (Applied per legal alternative and channel where that alternative weights differing texels
// with a weight not in {0, 1}: sample_interval.cpp, sampleBlended.) docs/crosscheck.md, row FILTER_PRECISION.
constexpr double kFilterUnorm = 1.0 / 255.0;

}  // namespace tessera::tolerance
