// The quad interpolation of the fast path (interpolateQuadDepth / interpolateQuadVaryings, written
// over the four pixels so a compiler may use SIMD lanes) gives exactly the bits of the per-pixel
// reference interpolatePixel, which the provenance path uses: the two paths must never disagree.
// Both call the same three per-pixel steps (rast.h), so this guards against a path that stops doing
// so; an operand reordered inside a step would change both and is caught by the goldens instead.
#include <gtest/gtest.h>

#include <bit>
#include <random>

#include "raster/rast.h"

namespace tessera::detail {

namespace {

// A triangle with random per-vertex 1/w, depth and varyings over wide ranges (perspective with
// w from 1e-3 to 1e4, varyings up to +-1e6 and tiny ones), and edge values of pixels inside,
// outside and far outside it (helper pixels extrapolate).
TriSetup randomTriangle(std::mt19937_64& rng) {
  TriSetup t{};
  std::uniform_real_distribution<double> logw(-3.0, 4.0), z(0.0, 1.0), v(-1.0, 1.0), scale(-6.0, 6.0);
  for (int i = 0; i < 3; ++i) {
    t.invW[i] = 1.0 / std::pow(10.0, logw(rng));
    t.z[i] = float(z(rng));
    for (int k = 0; k < kMaxVaryings; ++k) t.var[i][k] = float(v(rng) * std::pow(10.0, scale(rng)));
  }
  t.area2 = int64_t(std::uniform_int_distribution<int64_t>(1, int64_t(1) << 40)(rng));
  return t;
}

}  // namespace

TEST(InterpolateQuad, DepthAndVaryingsAreTheBitsOfThePerPixelReferenceForRandomTrianglesAndPixels) {
  std::mt19937_64 rng(20261202);
  int compared = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const TriSetup t = randomTriangle(rng);
    std::uniform_int_distribution<int64_t> edge(-(int64_t(1) << 41), int64_t(1) << 41);
    int64_t e[4][3];
    for (auto& px : e)
      for (int64_t& x : px) x = edge(rng);
    if (trial % 3 == 0)  // pixels inside: every edge value positive and summing to 2A
      for (auto& px : e) {
        px[0] = std::uniform_int_distribution<int64_t>(0, t.area2)(rng);
        px[1] = std::uniform_int_distribution<int64_t>(0, t.area2 - px[0])(rng);
        px[2] = t.area2 - px[0] - px[1];
      }
    float z[4], var[4][kMaxVaryings];
    interpolateQuadDepth(t, e, z);
    interpolateQuadVaryings(t, kMaxVaryings, e, var);
    for (int p = 0; p < 4; ++p) {
      float ref[kMaxVaryings];
      const float zr = interpolatePixel(t, kMaxVaryings, e[p], ref);
      ASSERT_EQ(std::bit_cast<uint32_t>(z[p]), std::bit_cast<uint32_t>(zr)) << "trial " << trial << " pixel " << p;
      for (int k = 0; k < kMaxVaryings; ++k)
        ASSERT_EQ(std::bit_cast<uint32_t>(var[p][k]), std::bit_cast<uint32_t>(ref[k]))
            << "trial " << trial << " pixel " << p << " varying " << k;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 80000);
}

}  // namespace tessera::detail
