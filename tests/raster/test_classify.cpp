// Triangle classification against the clip volume (raster/clip.h: classifyTriangle). The SSE2 form of
// the six fixed planes' tests runs unless the SIMD target is "reference", which runs the scalar
// steps; both must give the same result for every vertex, NaN, infinities, signed zeros and the
// planes' exact boundaries included (setup culls, clips or passes a triangle by it).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "raster/clip.h"
#include "raster/limits.h"
#include "raster/simd_targets.h"

namespace tessera::detail {
namespace {

// Values that sit on, just inside and just outside the planes for the w values among them, plus the
// special floats.
std::vector<float> interestingValues() {
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> v = {0.0f,  -0.0f, 1.0f,  -1.0f, 0.5f, -0.5f, 2.0f, -2.0f, 16.0f, -16.0f, 32.0f, -32.0f,
                          15.99f, -15.99f, 16.01f, -16.01f, 1e-30f, -1e-30f, 1e30f, -1e30f,
                          std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
                          std::numeric_limits<float>::denorm_min(), -std::numeric_limits<float>::denorm_min(), inf,
                          -inf, std::numeric_limits<float>::quiet_NaN()};
  // Guard-band boundaries: x = +-16 w for a few w, and the next floats either side.
  for (const float w : {1.0f, 3.0f, 0.1f, 1000.0f}) {
    const float b = float(kGuardBand) * w;
    for (const float s : {b, -b}) {
      v.push_back(s);
      v.push_back(std::nextafter(s, inf));
      v.push_back(std::nextafter(s, -inf));
    }
  }
  return v;
}

ClipResult classifyOn(const std::string& target, const VertexOut (&v)[3], uint8_t clipMask) {
  simd::forceTarget(target);
  const VertexOut* p[3] = {&v[0], &v[1], &v[2]};
  return classifyTriangle(p, clipMask);
}

TEST(Classify, EveryTargetClassifiesEveryVertexAsTheScalarStepsDo) {
  const std::vector<float> values = interestingValues();
  std::mt19937 rng(7);
  const std::vector<std::string> targets = simd::availableTargets();
  size_t checked = 0, outside = 0, clipped = 0, inside = 0;
  for (int n = 0; n < 60000; ++n) {
    VertexOut v[3] = {};
    for (VertexOut& o : v) {
      for (float& c : o.pos) c = (rng() % 4 == 0) ? values[rng() % values.size()] : float(int(rng() % 41) - 20) / 4.0f;
      if (rng() % 3 == 0) o.pos[3] = float(rng() % 8) / 2.0f;  // w in [0, 3.5], often on a boundary
      for (float& c : o.clip) c = values[rng() % values.size()];
    }
    // Triangles with all three vertices equal but one coordinate: many land exactly on a plane.
    if (n % 5 == 0) v[1] = v[0], v[2] = v[0];
    const uint8_t clipMask = uint8_t(n % 7 == 0 ? rng() : 0);
    const ClipResult expect = classifyOn("reference", v, clipMask);
    for (const std::string& target : targets) {
      ASSERT_EQ(int(classifyOn(target, v, clipMask)), int(expect))
          << "target " << target << ", triangle " << n << ": (" << v[0].pos[0] << ", " << v[0].pos[1] << ", "
          << v[0].pos[2] << ", " << v[0].pos[3] << ")";
    }
    ++checked;
    outside += expect == ClipResult::Outside, clipped += expect == ClipResult::Clipped,
        inside += expect == ClipResult::Inside;
  }
  simd::forceTarget("best");
  // Every outcome is exercised.
  EXPECT_GT(outside, checked / 20);
  EXPECT_GT(clipped, checked / 20);
  EXPECT_GT(inside, checked / 20);
}

TEST(Classify, APlaneBoundaryIsInsideAndTheNextFloatOutIsOutside) {
  for (const std::string& target : simd::availableTargets()) {
    // x = 16 w lies on the guard band's right plane (inside); the next float beyond it does not.
    VertexOut on[3] = {};
    for (VertexOut& o : on) o.pos = {16.0f, 0.0f, 0.0f, 1.0f};
    EXPECT_EQ(int(classifyOn(target, on, 0)), int(ClipResult::Inside)) << target;
    VertexOut beyond[3] = {};
    for (VertexOut& o : beyond) o.pos = {std::nextafter(16.0f, 17.0f), 0.0f, 0.0f, 1.0f};
    EXPECT_EQ(int(classifyOn(target, beyond, 0)), int(ClipResult::Outside)) << target;
    beyond[0].pos[0] = 0.0f;
    EXPECT_EQ(int(classifyOn(target, beyond, 0)), int(ClipResult::Clipped)) << target;
    // z = -w is on the near plane; a NaN or infinite coordinate discards the triangle.
    VertexOut near[3] = {};
    for (VertexOut& o : near) o.pos = {0.0f, 0.0f, -1.0f, 1.0f};
    EXPECT_EQ(int(classifyOn(target, near, 0)), int(ClipResult::Inside)) << target;
    near[2].pos[1] = std::numeric_limits<float>::infinity();
    EXPECT_EQ(int(classifyOn(target, near, 0)), int(ClipResult::Outside)) << target;
    near[2].pos[1] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(int(classifyOn(target, near, 0)), int(ClipResult::Outside)) << target;
  }
  simd::forceTarget("best");
}

}  // namespace
}  // namespace tessera::detail
