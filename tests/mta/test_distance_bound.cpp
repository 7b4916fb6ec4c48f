// The distance test's off-axis factor (traversal.h, DistanceBound): the per-node cos²θ_max of a box
// clipped to the frustum is sound at every point of the box the camera sees, never below the frustum's
// corner ray, and 1 on the view axis.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "base/error.h"
#include "mta/traversal.h"

namespace tessera::mta {
namespace {

// A camera at the origin looking down -z with tan(fovX/2) = 0.5 on a 4:3 frame: tan(fovY/2) = 0.375.
ViewContext axisContext(DistanceBound bound) {
  MtaMeta meta;
  meta.params.tau = 1.0;
  meta.params.screenWidth = 400;
  meta.params.tanHalfFov = 0.5;
  ViewParams v;
  v.camera.eye = {0, 0, 0};
  v.camera.target = {0, 0, -1};
  v.camera.tanHalfFovX = 0.5;
  v.camera.nearPlane = 0.1;
  v.camera.farPlane = 1000.0;
  v.width = 400;
  v.height = 300;
  v.bound = bound;
  return makeViewContext(meta, v);
}

constexpr double kCornerFactor = 1.0 / (1.0 + 0.25 + 0.140625);

std::array<float, 6> box(float x0, float y0, float z0, float x1, float y1, float z1) { return {x0, y0, z0, x1, y1, z1}; }

TEST(DistanceBound, APointOnTheViewAxisHasFactorOneAndTheWholeFrustumTheCornerRays) {
  const ViewContext node = axisContext(DistanceBound::PerNode);
  EXPECT_EQ(distanceFactor(node, box(0, 0, -10, 0, 0, -10)), 1.0);
  EXPECT_DOUBLE_EQ(distanceFactor(node, box(-100, -100, -20, 100, 100, -10)), kCornerFactor);
  // A quarter of the window, up to its top-right corner.
  EXPECT_DOUBLE_EQ(distanceFactor(node, box(0, 0, -10, 5, 3.75, -10)), kCornerFactor);
  // Half way to the right edge on the horizon: tan²θ = 0.25².
  EXPECT_DOUBLE_EQ(distanceFactor(node, box(0, 0, -10, 2.5, 0, -10)), 1.0 / (1.0 + 0.0625));
}

TEST(DistanceBound, ABoxReachingBehindTheEyeFallsBackToTheCornerRay) {
  EXPECT_DOUBLE_EQ(distanceFactor(axisContext(DistanceBound::PerNode), box(-1, -1, -10, 1, 1, 1)), kCornerFactor);
  EXPECT_DOUBLE_EQ(distanceFactor(axisContext(DistanceBound::PerNode), box(-1, -1, -10, 1, 1, 0)), kCornerFactor);
}

TEST(DistanceBound, TheOtherBoundsIgnoreTheBox) {
  EXPECT_DOUBLE_EQ(distanceFactor(axisContext(DistanceBound::FrameCorner), box(0, 0, -10, 0, 0, -10)), kCornerFactor);
  EXPECT_EQ(distanceFactor(axisContext(DistanceBound::Thesis), box(-100, -100, -20, 100, 100, -10)), 1.0);
}

TEST(DistanceBound, NamesParseBackAndAnUnknownOneIsAnErrorNamingTheOption) {
  for (DistanceBound b : {DistanceBound::PerNode, DistanceBound::FrameCorner, DistanceBound::Thesis})
    EXPECT_EQ(parseDistanceBound(distanceBoundName(b), "--distance-bound"), b);
  try {
    parseDistanceBound("axis", "--distance-bound");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "--distance-bound 'axis': expected node, corner or thesis");
  }
}

// What the test has to bound: min over the visible part of the box of r·cos²θ = depth² / r, the inverse
// of the projection's largest magnification (times f). For random cameras and boxes, every sampled point
// of the box inside the window must meet d · factor, d the eye-to-box distance.
TEST(DistanceBound, ThePerNodeFactorHoldsAtEveryVisiblePointOfTheBox) {
  uint64_t state = 0x9e3779b97f4a7c15ull;
  auto uniform = [&] {  // deterministic: splitmix64
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return double((z ^ (z >> 31)) >> 11) / 9007199254740992.0;
  };
  MtaMeta meta;
  meta.params.tau = 1.0;
  meta.params.screenWidth = 640;
  meta.params.tanHalfFov = 0.6;
  uint64_t checked = 0, tighter = 0;
  for (int trial = 0; trial < 400; ++trial) {
    ViewParams v;
    v.camera.eye = {uniform() * 20 - 10, uniform() * 20 - 10, uniform() * 20 - 10};
    v.camera.target = {uniform() * 20 - 10, uniform() * 20 - 10, uniform() * 20 - 10};
    v.camera.tanHalfFovX = 0.2 + uniform();
    v.width = 640;
    v.height = 480;
    const ViewContext ctx = makeViewContext(meta, v);
    const glm::dvec3 lo{uniform() * 24 - 12, uniform() * 24 - 12, uniform() * 24 - 12};
    const glm::dvec3 size{uniform() * 6, uniform() * 6, uniform() * 6};
    const std::array<float, 6> b = box(float(lo.x), float(lo.y), float(lo.z), float(lo.x + size.x), float(lo.y + size.y),
                                       float(lo.z + size.z));
    const double factor = distanceFactor(ctx, b);
    ASSERT_GE(factor, ctx.distanceFactor);
    if (factor > ctx.distanceFactor) ++tighter;
    const double bound = distanceToBox(ctx.eye, b) * factor;
    for (int k = 0; k < 300; ++k) {
      const glm::dvec3 p{b[0] + (b[3] - b[0]) * uniform(), b[1] + (b[4] - b[1]) * uniform(), b[2] + (b[5] - b[2]) * uniform()};
      const glm::dvec4 c = ctx.view * glm::dvec4(p, 1.0);
      const double depth = -c.z;
      if (!(depth > 1e-9) || std::fabs(c.x / depth) > ctx.tanX || std::fabs(c.y / depth) > ctx.tanY) continue;
      const double r = std::sqrt(c.x * c.x + c.y * c.y + c.z * c.z);
      ASSERT_GE(depth * depth / r, bound * (1.0 - 1e-12)) << "trial " << trial << ", point " << k;
      ++checked;
    }
  }
  EXPECT_GT(checked, 5000u);
  EXPECT_GT(tighter, 50u) << "the per-node factor should usually beat the corner ray";
}

}  // namespace
}  // namespace tessera::mta
