// RTTA packing and transforms (rtta/packing.h, rtta/transform.h).
#include <gtest/gtest.h>

#include <algorithm>

#include "base/error.h"
#include "rtta/packing.h"
#include "rtta/parameterize.h"
#include "rtta/record_buffer.h"
#include "rtta/transform.h"

namespace tessera::rtta {
namespace {

std::vector<Record> randomRegions(int n, int maxW, int maxH, uint64_t seed) {
  std::vector<Record> r(n);
  for (int i = 0; i < n; ++i) {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    const int w = 1 + int((seed >> 20) % uint64_t(maxW)), h = 1 + int((seed >> 40) % uint64_t(maxH));
    const int x = int((seed >> 8) % 200), y = int((seed >> 30) % 150);
    r[i].id = uint32_t(i);
    r[i].world = {{0, 0, 0}, {1, 1, 1}};
    r[i].inner = {x, y, x + w, y + h};
    r[i].viewport = borderedRegion(r[i].inner, 1);
  }
  return r;
}

TEST(RttaPacking, RegionsNeverOverlapStayInsideTheAtlasAndKeepTheirSize) {
  std::vector<Record> recs = randomRegions(300, 120, 90, 7);
  recs[5].culled = Culled::Frustum;
  const AtlasSize ta = atlasPackaging(recs, 256, 256);
  EXPECT_EQ(ta.width, 256);
  EXPECT_GT(ta.layers, 1);
  EXPECT_EQ(recs[5].layer, -1);
  for (const Record& r : recs) {
    if (!r.visible()) continue;
    ASSERT_GE(r.layer, 0);
    ASSERT_LT(r.layer, ta.layers);
    EXPECT_EQ(r.atlas.width(), r.viewport.width());
    EXPECT_EQ(r.atlas.height(), r.viewport.height());
    EXPECT_GE(r.atlas.x0, 0);
    EXPECT_GE(r.atlas.y0, 0);
    EXPECT_LE(r.atlas.x1, ta.width);
    EXPECT_LE(r.atlas.y1, ta.height);
    EXPECT_EQ((r.atlas.x0 - r.viewport.x0) % 2, 0) << "the shift must be even (2x2 quads)";
    EXPECT_EQ((r.atlas.y0 - r.viewport.y0) % 2, 0);
  }
  // Regions include their border, so disjoint regions mean no border texel is shared either.
  for (size_t i = 0; i < recs.size(); ++i)
    for (size_t j = i + 1; j < recs.size(); ++j) {
      const PixelRect &a = recs[i].atlas, &b = recs[j].atlas;
      if (recs[i].layer < 0 || recs[i].layer != recs[j].layer) continue;
      const bool overlap = a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
      EXPECT_FALSE(overlap) << i << " and " << j << " overlap in layer " << recs[i].layer;
    }
}

TEST(RttaPacking, TheResultDependsOnlyOnTheRecordsNotOnTheirOrder) {
  std::vector<Record> a = randomRegions(100, 60, 60, 11);
  std::vector<Record> b = a;
  std::reverse(b.begin(), b.end());
  atlasPackaging(a, 128, 128);
  atlasPackaging(b, 128, 128);
  for (const Record& rb : b) {
    EXPECT_EQ(a[rb.id].atlas, rb.atlas);
    EXPECT_EQ(a[rb.id].layer, rb.layer);
  }
}

TEST(RttaPacking, ShelvesFillRowsLeftToRightTallestFirst) {
  // Three regions 60x40, 50x30 and 40x20 in a 100x100 atlas: the tallest opens the first shelf, the
  // second does not fit beside it (60 + 50 > 100) and opens a shelf at y = 40, the third fits beside it.
  std::vector<Record> r(3);
  const int sizes[3][2] = {{40, 20}, {60, 40}, {50, 30}};
  for (int i = 0; i < 3; ++i) r[i].id = uint32_t(i), r[i].world = {{0, 0, 0}, {1, 1, 1}}, r[i].viewport = {0, 0, sizes[i][0], sizes[i][1]};
  const AtlasSize ta = atlasPackaging(r, 100, 100);
  EXPECT_EQ(ta.layers, 1);
  EXPECT_EQ(r[1].atlas, (PixelRect{0, 0, 60, 40}));
  EXPECT_EQ(r[2].atlas, (PixelRect{0, 40, 50, 70}));
  EXPECT_EQ(r[0].atlas, (PixelRect{50, 40, 90, 60}));
}

TEST(RttaPacking, MoreThan2048LayersIsAnErrorNamingTheLimit) {
  std::vector<Record> recs = randomRegions(2049, 1, 1, 3);
  for (Record& r : recs) r.viewport = {0, 0, 64, 64};
  try {
    atlasPackaging(recs, 64, 64);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("2048 layers"), std::string::npos) << e.what();
  }
}

TEST(RttaPacking, AnAtlasSmallerThanTheViewportPlusItsBorderIsRefused) {
  // 1024 + 2 border = [-1, 1025), aligned to even pixels: [-2, 1026), 1028 wide.
  EXPECT_NO_THROW(validateAtlas(1028, 1028, {0, 0, 1024, 1024}, 1));
  EXPECT_THROW(validateAtlas(1026, 1028, {0, 0, 1024, 1024}, 1), Error);
  EXPECT_NO_THROW(validateAtlas(1024, 1024, {0, 0, 1024, 1024}, 0));
  EXPECT_THROW(validateAtlas(1025, 1026, {0, 0, 1020, 1020}, 0), Error) << "odd sizes are refused";
  EXPECT_THROW(validateAtlas(0, 1024, {0, 0, 16, 16}, 0), Error);
  EXPECT_THROW(validateAtlas(32768, 1024, {0, 0, 16, 16}, 0), Error);
}

TEST(RttaTransform, InverseMapsTheAtlasRegionOntoTheViewportRegion) {
  std::vector<Record> recs = randomRegions(50, 100, 80, 5);
  // Power-of-two viewport and atlas: every NDC value below is a short dyadic number, so the
  // identities hold exactly in double too.
  const Rect vp{0, 0, 256, 128};
  const AtlasSize ta = atlasPackaging(recs, 512, 512);
  EXPECT_EQ(computeTransforms(recs, ta, vp), 0u) << "power-of-two atlas: every coefficient is exact";
  for (const Record& r : recs) {
    // Corners: T maps the screen-NDC corners of B_viewport exactly onto the atlas-NDC corners of B_atlas.
    for (int k = 0; k < 4; ++k) {
      const double wx = (k & 1) ? r.viewport.x1 : r.viewport.x0, wy = (k & 2) ? r.viewport.y1 : r.viewport.y0;
      const double ax = (k & 1) ? r.atlas.x1 : r.atlas.x0, ay = (k & 2) ? r.atlas.y1 : r.atlas.y0;
      const double sx = windowToNdc(wx, vp.x, vp.w), sy = windowToNdc(wy, vp.y, vp.h);
      EXPECT_EQ(double(r.T.a) * sx + double(r.T.tx), windowToNdc(ax, 0, ta.width));
      EXPECT_EQ(double(r.T.d) * sy + double(r.T.ty), windowToNdc(ay, 0, ta.height));
      double bx = 0, by = 0;
      inverseApply(r.T, windowToNdc(ax, 0, ta.width), windowToNdc(ay, 0, ta.height), bx, by);
      EXPECT_EQ(bx, sx);
      EXPECT_EQ(by, sy);
    }
  }
}

TEST(RttaTransform, ANonPowerOfTwoAtlasIsReportedAsInexact) {
  std::vector<Record> recs = randomRegions(20, 50, 50, 9);
  const AtlasSize ta = atlasPackaging(recs, 300, 300);
  EXPECT_GT(computeTransforms(recs, ta, {0, 0, 256, 200}), 0u);
}

TEST(RttaRecordBuffer, TwoTexelsPerIdAndACulledObjectHasNoLayer) {
  std::vector<Record> recs = randomRegions(3, 10, 10, 1);
  recs[1].culled = Culled::OffScreen;
  const AtlasSize ta = atlasPackaging(recs, 64, 64);
  computeTransforms(recs, ta, {0, 0, 64, 64});
  const std::vector<float> buf = encodeRecordBuffer(recs);
  ASSERT_EQ(buf.size(), 24u);
  EXPECT_EQ(buf[0], recs[0].T.a);
  EXPECT_EQ(buf[4], recs[0].T.tx);
  EXPECT_EQ(buf[6], float(recs[0].layer));
  EXPECT_EQ(buf[8 + 6], -1.0f);
  std::swap(recs[0], recs[2]);
  EXPECT_THROW(encodeRecordBuffer(recs), Error);
}

}  // namespace
}  // namespace tessera::rtta
