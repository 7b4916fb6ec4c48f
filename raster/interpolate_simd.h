// Depth and varyings of many quads at once (rast.h's pixelDepth, pixelBarycentrics and pixelVarying)
// as Highway kernels, on every target raster/simd_targets.h lists. The fast-path rasterizer gathers
// the covered quads of an 8x8 block, computes their depths in one call, runs the early depth test,
// and computes the varyings of the quads that kept a pixel in a second call.
//
// Implements: quadDepthsKernel() and quadVaryingsKernel(), whose floats are rast.h's for every input.
// Why the bits are the same: every lane runs the scalar code's operations in its order, each one an
// IEEE-754 double operation with one rounding to nearest even:
//   - int64 -> double: AVX-512DQ's vcvtqq2pd; on the other targets Highway adds the exact halves
//     (2^84 + 2^63 + hi * 2^32) - (2^84 + 2^63 + 2^52) and 2^52 + lo, so one addition rounds the exact
//     value once, as the scalar cvtsi2sd does; the scalar target is static_cast;
//   - float -> double (exact), mul, add and div, never fused (-ffp-contract=off, Highway's separate
//     Mul and Add), summed left to right like the scalar expressions;
//   - double -> float: cvtpd2ps, or static_cast on the scalar target.
// There is no reciprocal, no reassociation and no reduction across lanes. Under "reference" there are
// no kernels (nullptr) and rast.cpp runs its per-quad code. tests/raster/test_simd_interpolate.cpp compares every target with
// them on random, huge (|e| near 2^62), zero, NaN and Inf inputs, and compares the wide kernels'
// doubles with rast.h's before the rounding to float (which would hide a changed summation order).
// Does not implement: coverage, the depth test, programs that write depth (rast.cpp keeps those
// per quad).
#pragma once

#include <cstddef>
#include <cstdint>

#include "raster/limits.h"

namespace tessera::detail {

// The pixels of up to 16 quads in SoA order: pixel 4 j + p is pixel p of quad j (p = x + 2 y in the
// quad), and e[i][.] is its exact edge value opposite vertex i (rast.cpp, TriangleRasterizer::edgeAt).
// Every entry is kept initialized (a kernel may read a vector past the last pixel, never past kMax).
struct QuadPixels {
  static constexpr size_t kMax = 64;
  alignas(64) int64_t e[3][kMax] = {};
};

// The triangle constants the kernels read, as doubles (the scalar code's conversions, exact).
struct InterpolationPlane {
  double z[3];      // window depth per vertex (TriSetup::z)
  double area2;     // TriSetup::area2
  double invW[3];   // TriSetup::invW
  double var[3][kMaxVaryings];  // TriSetup::var
  int varyings;
};

// z[j] = pixelDepth(t, e of pixel j) for j < n. n <= kMax; z has room for kMax values.
using QuadDepthsFn = void (*)(const QuadPixels& px, size_t n, const InterpolationPlane& t, float* z);
// var[k * kMax + j] = pixelVarying(t, pixelBarycentrics(t, e of pixel j), k) for j < n, k < varyings.
using QuadVaryingsFn = void (*)(const QuadPixels& px, size_t n, const InterpolationPlane& t, float* var);

// The kernels of the target running now, or nullptr under "reference". Resolve them once per tile: a
// dispatch calls into libhwy.
QuadDepthsFn quadDepthsKernel();
QuadVaryingsFn quadVaryingsKernel();

// For tests: the same kernels with their doubles stored before the rounding to float (rast.h's
// pixelDepthWide and pixelVaryingWide), on the target running now ("reference" has none: nullptr
// is never returned, the best target's are).
using QuadDepthsWideFn = void (*)(const QuadPixels& px, size_t n, const InterpolationPlane& t, double* z);
using QuadVaryingsWideFn = void (*)(const QuadPixels& px, size_t n, const InterpolationPlane& t, double* var);
QuadDepthsWideFn quadDepthsWideKernel();
QuadVaryingsWideFn quadVaryingsWideKernel();

}  // namespace tessera::detail
