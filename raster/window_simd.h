// Per vertex, what triangle setup needs from the vertex's clip-space position alone: which clip planes
// it lies outside of, and its window position. Computed once per shaded vertex, right after the vertex
// stage (cpu_backend.cpp), with a Highway kernel on every target raster/simd_targets.h lists and a
// scalar reference; setup then classifies a triangle by three ANDs and ORs and reads its window
// vertices, instead of classifying and transforming each vertex once per triangle that uses it.
//
// Implements: windowVerticesKernel(), whose records are windowVerticesReference()'s (setup.cpp, the
// readable rule: clip.h's classifyVertex, then setup.cpp's toWindow) for every input. Why the bits are
// the same: every lane runs the reference's double operations in its order, each one an IEEE-754
// operation with one rounding to nearest even (float -> double exact; the plane sums w + z, w - z and
// kGuardBand * w +- x; 1 / w, the products and sums of the viewport transform, never fused:
// -ffp-contract=off and Highway's separate Mul and Add; the clamp of z as std::clamp's two compares).
// Snapping takes the two-addition round half to even of raster/round.h, read off the sum's bits
// (x + 1.5 * 2^52 lies in [2^52, 2^53] for |x| <= 2^51, where a double's bits minus the constant's
// bits are the integer): no float -> int64 conversion, which x86 has as a vector instruction on
// AVX-512 only (window_simd.cpp shows that every window coordinate inside the guard band is below
// 2^43 sub-pixels). tests/raster/test_simd_window.cpp compares every target with the reference.
// Does not implement: user clip distances in the kernel (the enabled ones, usually none, are tested
// per vertex after it, as the reference does), clipping, anything per triangle (setup.cpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "raster/program.h"
#include "raster/types.h"

namespace tessera::detail {

// Set when the six fixed planes hold the vertex (bits 0-5 of clip.h's classifyVertex clear) but w is
// not positive, so it has no window position: GL leaves such a primitive undefined (w = 0 passes every
// plane only at the clip-space origin) and setup drops an unclipped triangle with such a vertex.
constexpr uint32_t kVertexNoWindow = 1u << 30;

// The records of a run of vertices, one array per member (element i: vertex i), so that the kernel
// stores whole vectors: written record by record, the lanes cost more than the arithmetic.
struct VertexWindows {
  // Snapped window position (sub-pixels), 1 / w_clip and window depth, as setup.cpp's toWindow gives
  // them. Set iff (code & (kClipFixedPlaneBits | kClipNonFinite | kVertexNoWindow)) == 0; elsewhere
  // they hold unspecified values, which setup never reads.
  int64_t* x;
  int64_t* y;
  double* invW;
  float* z;
  // classifyVertex's bits (clip.h: the planes the vertex lies outside of, or kClipNonFinite alone),
  // plus kVertexNoWindow.
  uint32_t* code;
  VertexWindows at(size_t i) const { return {x + i, y + i, invW + i, z + i, code + i}; }
};

// n vertices' records (elements 0 .. n - 1 of out) for a draw with viewport vp and enabled user clip
// distances clipMask.
using WindowVerticesFn = void (*)(const VertexOut* v, size_t n, const Rect& vp, uint8_t clipMask,
                                  const VertexWindows& out);

// The kernel of the target running now, or windowVerticesReference under "reference". Resolve it
// once per batch of draws: a dispatch calls into libhwy.
WindowVerticesFn windowVerticesKernel();

// The rule, vertex by vertex (setup.cpp).
void windowVerticesReference(const VertexOut* v, size_t n, const Rect& vp, uint8_t clipMask, const VertexWindows& out);

}  // namespace tessera::detail
