// RTTA parameterization (rtta/parameterize.h): regions against the pixels the oracle really covers.
#include <gtest/gtest.h>

#include <cstdint>

#include "mta/camera.h"
#include "rtta/parameterize.h"
#include "tests/rtta/flat_render.h"

namespace tessera::rtta {
namespace {

constexpr int kParamW = 160, kParamH = 120;

mta::Camera camera() {
  mta::Camera c;
  c.eye = {0.0, 2.0, 10.0};
  c.target = {0.0, 0.0, 0.0};
  c.nearPlane = 0.5;
  c.farPlane = 60.0;
  return c;
}

// A deterministic scatter of boxes around and behind the camera, some off screen, some beyond far.
std::vector<Box3> scatter(std::vector<std::vector<glm::vec3>>& tris) {
  uint64_t s = 0x9e3779b97f4a7c15ull;
  auto next = [&] {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return double(s >> 11) / double(1ull << 53);
  };
  std::vector<Box3> boxes;
  for (int i = 0; i < 96; ++i) {
    const glm::vec3 c(float(-30 + 60 * next()), float(-8 + 16 * next()), float(-70 + 90 * next()));
    const glm::vec3 e(float(0.1 + 2.0 * next()), float(0.1 + 2.0 * next()), float(0.1 + 2.0 * next()));
    tris.emplace_back();
    testing::addBox(tris.back(), c - e, c + e);
    boxes.push_back(boundsOf(tris.back()));
  }
  return boxes;
}

TEST(RttaParameterization, CulledObjectsHaveNoVisiblePixelAndEveryCoveredPixelLiesInItsRegion) {
  std::vector<std::vector<glm::vec3>> tris;
  const std::vector<Box3> boxes = scatter(tris);
  const glm::mat4 vpm = mta::viewProjection(camera(), kParamW, kParamH);
  const std::vector<Record> recs = parameterize(boxes, vpm, {0, 0, kParamW, kParamH}, {.border = 2});
  int culled = 0, seen = 0;
  for (size_t i = 0; i < recs.size(); ++i) {
    const std::vector<uint8_t> mask = testing::coveredPixels(tris[i], vpm, kParamW, kParamH);
    int pixels = 0, outside = 0;
    for (int y = 0; y < kParamH; ++y)
      for (int x = 0; x < kParamW; ++x)
        if (mask[size_t(y) * kParamW + x]) ++pixels, outside += recs[i].inner.contains(x, y) ? 0 : 1;
    if (!recs[i].visible()) {
      ++culled;
      EXPECT_EQ(pixels, 0) << "object " << i << " was culled (" << culledName(recs[i].culled) << ") but covers pixels";
    } else {
      seen += pixels > 0;
      EXPECT_EQ(outside, 0) << "object " << i << ": pixels outside its region";
      const PixelRect& v = recs[i].viewport;
      EXPECT_TRUE(v.x0 % 2 == 0 && v.y0 % 2 == 0 && v.x1 % 2 == 0 && v.y1 % 2 == 0) << "regions sit on even pixels";
      EXPECT_TRUE(recs[i].inner.x0 - v.x0 >= 2 && recs[i].inner.x0 - v.x0 <= 3) << "a border of 2, plus one to be even";
      EXPECT_TRUE(v.y1 - recs[i].inner.y1 >= 2 && v.y1 - recs[i].inner.y1 <= 3);
    }
  }
  // The scatter must exercise both outcomes.
  EXPECT_GE(culled, 20);
  EXPECT_GE(seen, 20);
}

TEST(RttaParameterization, ProjectedBoxContainsItsObjectAcrossTheNearPlane) {
  // A wall on the right that starts in front of the camera and reaches behind it: its corners behind
  // the eye would project mirrored (w < 0) onto the left half if projected naively.
  std::vector<glm::vec3> wall;
  testing::addBox(wall, {2.0f, -1.0f, -5.0f}, {3.0f, 1.5f, 25.0f});
  const glm::mat4 vpm = mta::viewProjection(camera(), kParamW, kParamH);
  const Box3 box = boundsOf(wall);
  const std::vector<Record> recs = parameterize(std::span(&box, 1), vpm, {0, 0, kParamW, kParamH}, {.border = 0});
  ASSERT_TRUE(recs[0].visible());
  EXPECT_TRUE(recs[0].nearClipped);
  EXPECT_FALSE(recs[0].wholeViewport);
  const std::vector<uint8_t> mask = testing::coveredPixels(wall, vpm, kParamW, kParamH);
  int pixels = 0;
  for (int y = 0; y < kParamH; ++y)
    for (int x = 0; x < kParamW; ++x)
      if (mask[size_t(y) * kParamW + x]) {
        ++pixels;
        EXPECT_TRUE(recs[0].inner.contains(x, y)) << x << "," << y;
      }
  EXPECT_GT(pixels, 500);
  // The wall is on the right: its region does not reach the left half of the screen.
  EXPECT_GE(recs[0].inner.x0, kParamW / 2);
  EXPECT_EQ(recs[0].inner.x1, kParamW);  // it runs out of the right edge
}

TEST(RttaParameterization, ABoxEntirelyBehindTheCameraIsCulledAndWithoutCullingHasNoRegion) {
  std::vector<glm::vec3> b;
  testing::addBox(b, {-1.0f, -1.0f, 12.0f}, {1.0f, 1.0f, 14.0f});
  const Box3 box = boundsOf(b);
  const glm::mat4 vpm = mta::viewProjection(camera(), kParamW, kParamH);
  EXPECT_EQ(parameterize(std::span(&box, 1), vpm, {0, 0, kParamW, kParamH}, {})[0].culled, Culled::Frustum);
  // Without frustum culling (the paper's Table 1 runs) the near-plane clip leaves nothing in front:
  // the record falls back to the whole viewport, which is conservative, never wrong.
  const Record r = parameterize(std::span(&box, 1), vpm, {0, 0, kParamW, kParamH}, {.cull = false})[0];
  EXPECT_TRUE(r.visible());
  EXPECT_TRUE(r.wholeViewport);
}

TEST(RttaParameterization, AnEmptyObjectGetsNoRegionAndBadOptionsAreErrors) {
  const Box3 empty;
  const glm::mat4 vpm = mta::viewProjection(camera(), kParamW, kParamH);
  EXPECT_EQ(parameterize(std::span(&empty, 1), vpm, {0, 0, kParamW, kParamH}, {})[0].culled, Culled::Empty);
  EXPECT_THROW(parameterize(std::span(&empty, 1), vpm, {0, 0, kParamW, kParamH}, {.border = -1}), Error);
  EXPECT_THROW(parameterize(std::span(&empty, 1), vpm, {0, 0, 0, kParamH}, {}), Error);
}

}  // namespace
}  // namespace tessera::rtta
