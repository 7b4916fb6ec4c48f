// The per-vertex window kernel (raster/window_simd.h) on every SIMD target this build compiled and this
// CPU runs: the records setup.cpp's reference gives, vertex by vertex (classifyVertex, then toWindow),
// for every run length (short last groups), NaN, infinities, signed zeros, w at and below zero, points
// on the planes and their neighbours, user clip distances, and viewports up to the int32 extremes.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "raster/clip.h"
#include "raster/limits.h"
#include "raster/simd_targets.h"
#include "raster/window_simd.h"
#include "tests/raster/render_helpers.h"

namespace tessera::detail {
namespace {

// Records in vectors, with a sentinel after the last element (the kernel must not write past it).
struct Records {
  explicit Records(size_t n) : x(n + 1, kSentinel), y(n + 1, kSentinel), invW(n + 1), z(n + 1), code(n + 1, 0xdeadbeefu) {}
  static constexpr int64_t kSentinel = 0x5a5a5a5a5a5a5a5a;
  std::vector<int64_t> x, y;
  std::vector<double> invW;
  std::vector<float> z;
  std::vector<uint32_t> code;
  VertexWindows view() { return {x.data(), y.data(), invW.data(), z.data(), code.data()}; }
};

std::vector<float> specialPositionValues() {
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> v = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, -0.5f, 2.0f, -2.0f, 16.0f, -16.0f, 1e-30f, -1e-30f,
                          1e30f, -1e30f, std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
                          std::numeric_limits<float>::denorm_min(), inf, -inf,
                          std::numeric_limits<float>::quiet_NaN()};
  for (const float w : {1.0f, 3.0f, 0.1f}) {  // the guard band's boundaries and their neighbours
    const float b = float(kGuardBand) * w;
    for (const float s : {b, -b}) v.insert(v.end(), {s, std::nextafter(s, inf), std::nextafter(s, -inf)});
  }
  return v;
}

VertexOut randomVertex(std::mt19937& rng, const std::vector<float>& values) {
  VertexOut o = {};
  for (float& c : o.pos) c = rng() % 5 == 0 ? values[rng() % values.size()] : float(int(rng() % 81) - 40) / 8.0f;
  // Mostly a positive w, so most vertices have a window; some with a 1 / w that rounds.
  if (rng() % 3) o.pos[3] = rng() % 2 ? float(rng() % 16 + 1) / 4.0f : float(rng() % 1000 + 1) / 7.0f;
  if (rng() % 8 == 0) {
    o.pos[3] = rng() % 2 ? 0.0f : -0.0f;
    // The clip-space origin, with either zero: inside every fixed plane, but with no window position.
    if (rng() % 2)
      for (int k = 0; k < 3; ++k) o.pos[k] = rng() % 2 ? 0.0f : -0.0f;
  }
  // On the near or far plane, where z / w may round past -1 or 1 and the depth clamp decides.
  if (rng() % 4 == 0) o.pos[2] = rng() % 2 ? o.pos[3] : -o.pos[3];
  for (float& c : o.clip) c = rng() % 2 ? values[rng() % values.size()] : float(int(rng() % 9) - 4);
  return o;
}

Rect randomViewport(std::mt19937& rng) {
  switch (rng() % 4) {
    case 0: return {0, 0, int32_t(rng() % 4096 + 1), int32_t(rng() % 4096 + 1)};
    case 1: return {int32_t(rng() % 200) - 100, int32_t(rng() % 200) - 100, 640, 480};
    // The extremes an int32 viewport allows: the window coordinates reach 2^43 sub-pixels.
    case 2: return {std::numeric_limits<int32_t>::max(), std::numeric_limits<int32_t>::min(),
                    std::numeric_limits<int32_t>::max(), std::numeric_limits<int32_t>::max()};
    default: return {int32_t(rng() % 16384), int32_t(rng() % 16384), int32_t(rng() % 16384 + 1), int32_t(rng() % 16384 + 1)};
  }
}

TEST(SimdWindow, EveryTargetGivesTheReferenceRecordForEveryVertex) {
  const std::vector<float> values = specialPositionValues();
  const std::vector<std::string> targets = simd::availableTargets();
  const tessera::testing::SimdTargetGuard guard;  // the best target again, however the test ends
  std::mt19937 rng(11);
  size_t placed = 0, noWindow = 0, nonFinite = 0, clipBits = 0, clamped = 0;
  for (int iter = 0; iter < 3000; ++iter) {
    const size_t n = rng() % 70 + 1;
    std::vector<VertexOut> v(n);
    for (VertexOut& o : v) o = randomVertex(rng, values);
    const Rect vp = randomViewport(rng);
    const uint8_t clipMask = rng() % 3 ? 0 : uint8_t(rng());
    simd::forceTarget("reference");
    Records want(n);
    windowVerticesKernel()(v.data(), n, vp, clipMask, want.view());
    for (size_t i = 0; i < n; ++i) {
      const uint32_t c = want.code[i];
      const bool held = (c & (kClipFixedPlaneBits | kClipNonFinite | kVertexNoWindow)) == 0;
      placed += held;
      // Whether the depth clamp changed the value. It never does for a vertex inside the planes:
      // |z| <= w exactly, and z * RN(1 / w) rounds to a magnitude of at most 1 (the exact product is
      // within 2^-53 of +-1, half the spacing of the doubles above 1). The clamp stays in both forms
      // for clipped vertices (setup.cpp), whose depth the clipper computes.
      if (held) {
        const double zw = double(v[i].pos[2]) * (1.0 / double(v[i].pos[3])) * 0.5 + 0.5;
        clamped += zw < 0.0 || zw > 1.0;
      }
      noWindow += (c & kVertexNoWindow) != 0;
      nonFinite += c == kClipNonFinite;
      clipBits += (c & kClipPlaneBits & ~kClipFixedPlaneBits) != 0;
    }
    for (const std::string& target : targets) {
      simd::forceTarget(target);
      Records got(n);
      windowVerticesKernel()(v.data(), n, vp, clipMask, got.view());
      for (size_t i = 0; i < n; ++i) {
        SCOPED_TRACE("target " + target + ", case " + std::to_string(iter) + ", vertex " + std::to_string(i));
        ASSERT_EQ(got.code[i], want.code[i]);
        if (want.code[i] & (kClipFixedPlaneBits | kClipNonFinite | kVertexNoWindow)) continue;
        ASSERT_EQ(got.x[i], want.x[i]);
        ASSERT_EQ(got.y[i], want.y[i]);
        ASSERT_EQ(std::bit_cast<uint64_t>(got.invW[i]), std::bit_cast<uint64_t>(want.invW[i]));
        ASSERT_EQ(std::bit_cast<uint32_t>(got.z[i]), std::bit_cast<uint32_t>(want.z[i]));
      }
      ASSERT_EQ(got.x[n], Records::kSentinel) << target << ": wrote past the last record";
      ASSERT_EQ(got.y[n], Records::kSentinel) << target;
      ASSERT_EQ(got.code[n], 0xdeadbeefu) << target;
    }
  }
  // The cases above reach every kind of record.
  EXPECT_GT(placed, 10000u);
  EXPECT_GT(noWindow, 1000u);
  EXPECT_GT(nonFinite, 1000u);
  EXPECT_GT(clipBits, 1000u);
  EXPECT_EQ(clamped, 0u);
}

// The record of a vertex as the rule states it: classifyVertex's bits; for a vertex inside the fixed
// planes with w > 0 the viewport transform of GL 4.6 §13.8 snapped to sub-pixels (half to even) and
// the depth clamped to [0, 1].
TEST(SimdWindow, ARecordIsTheSnappedViewportTransform) {
  VertexOut v[3] = {};
  v[0].pos = {0.5f, -0.25f, 0.5f, 1.0f};    // inside
  v[1].pos = {40.0f, 0.0f, 0.0f, 1.0f};     // outside the guard band (x > 16 w)
  v[2].pos = {0.0f, 0.0f, 0.0f, 0.0f};      // the clip-space origin: no window position
  const tessera::testing::SimdTargetGuard guard;
  for (const std::string& target : simd::availableTargets()) {
    simd::forceTarget(target);
    Records r(3);
    windowVerticesKernel()(v, 3, Rect{10, 20, 100, 50}, 0, r.view());
    EXPECT_EQ(r.code[0], 0u) << target;
    // x_w = 0.5 * 50 + 60 = 85, y_w = -0.25 * 25 + 45 = 38.75, z_w = 0.75.
    EXPECT_EQ(r.x[0], 85 * kSubpixelOne) << target;
    EXPECT_EQ(r.y[0], 3875 * kSubpixelOne / 100) << target;
    EXPECT_EQ(r.z[0], 0.75f) << target;
    EXPECT_EQ(r.invW[0], 1.0) << target;
    EXPECT_EQ(r.code[1], 1u << 3) << target;  // plane 3: x <= 16 w
    EXPECT_EQ(r.code[2], kVertexNoWindow) << target;
  }
}

}  // namespace
}  // namespace tessera::detail
