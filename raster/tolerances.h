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

// Edge margin, in sub-pixels (1/256 px) of distance between a pixel centre and an edge line.
// GL 4.6 §14.5 leaves sub-pixel snapping free (spec-choices R1) and §14.6.1 only asks shared edges to
// have no gaps and no double hits (R3). Another implementation with 8 sub-pixel bits may round each
// vertex to any of its 4 neighbouring grid points, so an edge moves by up to sqrt(2) sub-pixels.
// docs/crosscheck.md, row EDGE_TIE.
constexpr double kEdgeMarginSub = 1.4142135623730951;  // sqrt(2)

// Edge margin of a triangle made by clipping, in sub-pixels: 1 px. GL 4.6 §13.7 (Primitive Clipping)
// fixes the clip volume but not the precision of the new vertices: GL may clip in float and snap them,
// and because of the oracle's guard band (spec-choices V2) GL may clip where the oracle does not.
// docs/crosscheck.md, row CLIP_EDGE.
constexpr double kClipMarginSub = 256.0;

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
// docs/crosscheck.md, row DEPTH_NEAR_EQUAL.
constexpr double kDepthAbs = 1.0 / 2097152.0;  // 2^-21

// ---- per-fragment operations (rast_provenance.cpp, rast.cpp) ------------------------------------

// Blend arithmetic error, in [0, 1] units: 2.5 LSB of unorm8 before the final rounding of each blended
// write. GL 4.6 §17.3.6.1 leaves the precision of blending free (spec-choices F2); an 8-bit blender
// quantizes the source and both factors and rounds both products, five errors of at most 1/2 LSB.
// docs/crosscheck.md, row BLEND_PRECISION.
constexpr double kBlendUnorm = 2.5 / 255.0;

// Relative error of a unorm clear colour converted in float32: 2^-22 of c * 255, a float32 product's
// rounding with margin. GL 4.6 §2.3.5.2 (float to unorm conversion, spec-choices F3) allows either
// neighbour at a tie, and c * 255 rounded to float32 can land on one. docs/crosscheck.md, row
// OUTPUT_ROUNDING ("clear colours").
constexpr double kClearRel = 1.0 / 4194304.0;  // 2^-22

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

// Filter arithmetic error of a unorm lookup that blends texels, in [0, 1] units: 1 LSB. GL 4.6
// §8.14.2 leaves the precision of filtering free (spec-choices T8 is the oracle's exact choice);
// llvmpipe's AoS path lerps in 8-bit fixed point with its own rounding. docs/crosscheck.md, row
// FILTER_PRECISION.
constexpr double kFilterUnorm = 1.0 / 255.0;

}  // namespace tessera::tolerance
