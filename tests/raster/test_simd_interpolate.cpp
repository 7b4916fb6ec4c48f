// The interpolation kernels (raster/interpolate_simd.h) on every SIMD target this build compiled and
// this CPU runs: the bits of rast.h's pixelDepth, pixelBarycentrics and pixelVarying for every pixel,
// whatever the inputs (edge values from 0 to near 2^62 of either sign, so int64 -> double rounds;
// depths, 1/w and varyings with NaN, infinities, zeros and denormals), for every pixel count a block
// can gather and every number of varyings.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "raster/interpolate_simd.h"
#include "raster/rast.h"
#include "raster/simd_targets.h"

namespace tessera {
namespace {

using detail::InterpolationPlane;
using detail::QuadPixels;
using detail::TriSetup;

uint32_t interpBits(float f) {
  uint32_t b;
  std::memcpy(&b, &f, sizeof b);
  return b;
}

// A float that is usually ordinary and sometimes special.
float interpFloat(std::mt19937_64& rng) {
  switch (rng() % 16) {
    case 0: return std::numeric_limits<float>::quiet_NaN();
    case 1: return std::numeric_limits<float>::infinity();
    case 2: return -std::numeric_limits<float>::infinity();
    case 3: return 0.0f;
    case 4: return std::numeric_limits<float>::denorm_min();
    case 5: {
      const uint32_t bits = uint32_t(rng());
      float f;
      std::memcpy(&f, &bits, sizeof f);
      return f;
    }
    default: return std::uniform_real_distribution<float>(-4.0f, 4.0f)(rng);
  }
}

// An edge value: small, large, near the int64 range the guard band allows and beyond, or zero.
int64_t interpEdge(std::mt19937_64& rng) {
  const int shift = 1 + int(rng() % 62);  // |v| in [2^(shift-1), 2^shift)
  const int64_t v = int64_t(rng() >> (64 - shift)) | int64_t(1) << (shift - 1);
  switch (rng() % 8) {
    case 0: return 0;
    case 1: return -v;
    default: return v;
  }
}

struct InterpCase {
  TriSetup t{};
  int varyings = 0;
  size_t n = 0;
  QuadPixels px;
};

InterpCase interpCase(std::mt19937_64& rng) {
  InterpCase c;
  c.varyings = int(rng() % (kMaxVaryings + 1));
  c.n = 4 * (1 + rng() % (QuadPixels::kMax / 4));
  for (int i = 0; i < 3; ++i) {
    c.t.z[i] = rng() % 4 ? std::uniform_real_distribution<float>(0.0f, 1.0f)(rng) : interpFloat(rng);
    c.t.invW[i] = rng() % 4 ? std::uniform_real_distribution<double>(1e-3, 10.0)(rng) : double(interpFloat(rng));
    for (int k = 0; k < kMaxVaryings; ++k) c.t.var[i][k] = interpFloat(rng);
  }
  c.t.area2 = int64_t(1) + int64_t(rng() >> (1 + rng() % 62));
  for (size_t j = 0; j < QuadPixels::kMax; ++j)
    for (int i = 0; i < 3; ++i) c.px.e[i][j] = interpEdge(rng);
  return c;
}

InterpolationPlane interpPlane(const InterpCase& c) {
  InterpolationPlane p{};
  for (int i = 0; i < 3; ++i) {
    p.z[i] = double(c.t.z[i]);
    p.invW[i] = c.t.invW[i];
    for (int k = 0; k < kMaxVaryings; ++k) p.var[i][k] = double(c.t.var[i][k]);
  }
  p.area2 = double(c.t.area2);
  p.varyings = c.varyings;
  return p;
}

TEST(SimdInterpolate, EveryTargetGivesRastsDepthAndVaryingBitsForEveryKindOfInput) {
  std::vector<std::string> targets = simd::availableTargets();
  ASSERT_EQ(targets.back(), "reference");
  targets.pop_back();  // "reference" has no kernels: rast.cpp runs rast.h per quad
  for (const std::string& target : targets) {
    simd::forceTarget(target);
    const detail::QuadDepthsFn depths = detail::quadDepthsKernel();
    const detail::QuadVaryingsFn varyings = detail::quadVaryingsKernel();
    ASSERT_TRUE(depths && varyings) << target;
    std::mt19937_64 rng(77);
    for (int iter = 0; iter < 3000; ++iter) {
      const InterpCase c = interpCase(rng);
      const InterpolationPlane plane = interpPlane(c);
      float z[QuadPixels::kMax], var[kMaxVaryings * QuadPixels::kMax];
      depths(c.px, c.n, plane, z);
      varyings(c.px, c.n, plane, var);
      for (size_t j = 0; j < c.n; ++j) {
        const int64_t e[3] = {c.px.e[0][j], c.px.e[1][j], c.px.e[2][j]};
        ASSERT_EQ(interpBits(z[j]), interpBits(detail::pixelDepth(c.t, e)))
            << "target " << target << ", case " << iter << ", pixel " << j << ": depth " << z[j];
        double b[3];
        detail::pixelBarycentrics(c.t, e, b);
        for (int k = 0; k < c.varyings; ++k)
          ASSERT_EQ(interpBits(var[size_t(k) * QuadPixels::kMax + j]), interpBits(detail::pixelVarying(c.t, b, k)))
              << "target " << target << ", case " << iter << ", pixel " << j << ", varying " << k;
      }
    }
  }
  simd::forceTarget("best");
}

uint64_t wideBits(double v) {
  if (std::isnan(v)) return 0x7ff8000000000000u;  // NaN bits are canonical only after the rounding
  uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

// The doubles before the rounding to float, which hides almost every change of summation order.
TEST(SimdInterpolate, EveryTargetComputesRastsDoublesBeforeTheRoundingToFloat) {
  std::vector<std::string> targets = simd::availableTargets();
  targets.pop_back();  // "reference"
  for (const std::string& target : targets) {
    simd::forceTarget(target);
    const detail::QuadDepthsWideFn depths = detail::quadDepthsWideKernel();
    const detail::QuadVaryingsWideFn varyings = detail::quadVaryingsWideKernel();
    std::mt19937_64 rng(78);
    for (int iter = 0; iter < 3000; ++iter) {
      const InterpCase c = interpCase(rng);
      const InterpolationPlane plane = interpPlane(c);
      double z[QuadPixels::kMax], var[kMaxVaryings * QuadPixels::kMax];
      depths(c.px, c.n, plane, z);
      varyings(c.px, c.n, plane, var);
      for (size_t j = 0; j < c.n; ++j) {
        const int64_t e[3] = {c.px.e[0][j], c.px.e[1][j], c.px.e[2][j]};
        ASSERT_EQ(wideBits(z[j]), wideBits(detail::pixelDepthWide(c.t, e)))
            << "target " << target << ", case " << iter << ", pixel " << j;
        double b[3];
        detail::pixelBarycentrics(c.t, e, b);
        for (int k = 0; k < c.varyings; ++k)
          ASSERT_EQ(wideBits(var[size_t(k) * QuadPixels::kMax + j]), wideBits(detail::pixelVaryingWide(c.t, b, k)))
              << "target " << target << ", case " << iter << ", pixel " << j << ", varying " << k;
      }
    }
  }
  simd::forceTarget("best");
}

TEST(SimdInterpolate, ReferenceHasNoKernelsSoTheRasterizerRunsRastHPerQuad) {
  simd::forceTarget("reference");
  EXPECT_EQ(detail::quadDepthsKernel(), nullptr);
  EXPECT_EQ(detail::quadVaryingsKernel(), nullptr);
  simd::forceTarget("best");
  EXPECT_NE(detail::quadDepthsKernel(), nullptr);
}

}  // namespace
}  // namespace tessera
