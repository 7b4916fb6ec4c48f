// Size estimation (incl. degenerate cases), required area with repetition and border, packing.
#include <gtest/gtest.h>

#include <cmath>

#include "mta/packing.h"
#include "mta/params.h"
#include "mta/size_estimation.h"

namespace tessera::mta {
namespace {

TEST(SizeEstimation, UnitSquareMappedToOneMetreGivesFProjTexels) {
  const glm::vec3 v[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const glm::vec2 t[3] = {{0, 0}, {1, 0}, {0, 1}};
  const TexelSize s = triangleTexelSize(v, t, 100.0);
  EXPECT_DOUBLE_EQ(s.w, 100.0);
  EXPECT_DOUBLE_EQ(s.h, 100.0);
  EXPECT_FALSE(s.constant);
}

TEST(SizeEstimation, AnisotropicAndShearedMappingsUseTheWorldImageOfEachTextureAxis) {
  // u spans 4 m along x, v spans 2 m along z: s_world = (4,0,0), t_world = (0,0,2).
  const glm::vec3 v[3] = {{0, 0, 0}, {4, 0, 0}, {0, 0, 2}};
  const glm::vec2 t[3] = {{0, 0}, {1, 0}, {0, 1}};
  const TexelSize s = triangleTexelSize(v, t, 10.0);
  EXPECT_DOUBLE_EQ(s.w, 40.0);
  EXPECT_DOUBLE_EQ(s.h, 20.0);
  // Texcoords (0,0), (1,1), (0,1) on a right triangle: Tex^-1((1,0)) = (1, -1) -> s_world = v1 - v2.
  const glm::vec3 w[3] = {{0, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const glm::vec2 u[3] = {{0, 0}, {1, 1}, {0, 1}};
  const TexelSize r = triangleTexelSize(w, u, 1.0);
  EXPECT_DOUBLE_EQ(r.w, 1.0);
  EXPECT_DOUBLE_EQ(r.h, 1.0);
}

TEST(SizeEstimation, RepetitionDoesNotChangeTheRequiredAreaOnlyThePerRepeatSize) {
  const glm::vec3 v[3] = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}};
  const glm::vec2 t1[3] = {{0, 0}, {1, 0}, {0, 1}};
  const glm::vec2 t1000[3] = {{0, 0}, {1000, 0}, {0, 1000}};
  const TexelSize a = triangleTexelSize(v, t1, 5.0), b = triangleTexelSize(v, t1000, 5.0);
  EXPECT_NEAR(a.w, b.w * 1000.0, 1e-9);
  TexRect ra, rb;
  for (int k = 0; k < 3; ++k) ra.add(t1[k]), rb.add(t1000[k]);
  const AreaRequirement qa = requiredArea(a, ra, 1u << 20, 1u << 20, 0), qb = requiredArea(b, rb, 1u << 20, 1u << 20, 0);
  EXPECT_EQ(qa.innerW, qb.innerW);
  EXPECT_EQ(qa.innerW, 50u);
}

TEST(SizeEstimation, DegenerateCasesFollowTheThesis) {
  const glm::vec3 v[3] = {{0, 0, 0}, {3, 0, 0}, {0, 4, 0}};
  const glm::vec2 same[3] = {{0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}};
  const TexelSize c = triangleTexelSize(v, same, 7.0);
  EXPECT_TRUE(c.constant);
  EXPECT_EQ(c.w, 1.0);
  // Collinear texcoords: longest texture edge (0,0)-(0.5,0) belongs to v0-v2 (|v| = 4): 4 / 0.5 = 8 per unit.
  const glm::vec2 line[3] = {{0, 0}, {0.25f, 0}, {0.5f, 0}};
  const TexelSize l = triangleTexelSize(v, line, 2.0);
  EXPECT_FALSE(l.constant);
  EXPECT_DOUBLE_EQ(l.w, 16.0);
  EXPECT_DOUBLE_EQ(l.h, 16.0);
  // World-degenerate triangles are ignored.
  const glm::vec3 flat[3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const glm::vec2 t[3] = {{0, 0}, {1, 0}, {0, 1}};
  EXPECT_TRUE(triangleTexelSize(flat, t, 1.0).ignored);
}

TEST(SizeEstimation, ProjectionFactorUsesDeterministicTanAndTau) {
  BuildParams p;
  p.fovDegrees = 90.0;
  p.screenWidth = 1000;
  EXPECT_NEAR(p.effectiveTanHalfFov(), 1.0, 1e-15);
  EXPECT_NEAR(projectionFactor(p, 10.0), 50.0, 1e-12);
  p.tau = 2.0;
  EXPECT_NEAR(projectionFactor(p, 10.0), 25.0, 1e-12);
  p.tanHalfFov = 0.5;
  EXPECT_DOUBLE_EQ(projectionFactor(p, 10.0), 50.0);
}

TEST(RequiredArea, PartialUseAndRepetitionScaleTheAreaAndTheBorderEnlargesTheSourceAboutItsCentre) {
  TexelSize s{100.0, 50.0, false, false};
  TexRect part;  // a quarter of the texture in u, half in v
  part.add({0.25f, 0.5f});
  part.add({0.5f, 1.0f});
  AreaRequirement r = requiredArea(s, part, 1024, 1024, 8);
  EXPECT_EQ(r.innerW, 25u);
  EXPECT_EQ(r.innerH, 25u);
  EXPECT_EQ(r.w, 41u);
  EXPECT_EQ(r.h, 41u);
  EXPECT_NEAR(0.5 * (r.source.u0 + r.source.u1), 0.375, 1e-15);
  EXPECT_NEAR(r.source.width(), 0.25 * 41.0 / 25.0, 1e-15);  // same texel density in the border
  TexRect rep;  // (0,0)-(3,2): 6 repetitions
  rep.add({0, 0});
  rep.add({3, 2});
  r = requiredArea(s, rep, 1024, 1024, 8);
  EXPECT_EQ(r.innerW, 300u);
  EXPECT_EQ(r.innerH, 100u);
  // The per-repeat size is capped by the image: 100 texels wanted from a 64-wide image.
  r = requiredArea(s, rep, 64, 1024, 0);
  EXPECT_EQ(r.innerW, 192u);
  // Constant textures take 1x1 plus border.
  r = requiredArea(TexelSize{1, 1, true, false}, rep, 64, 64, 8);
  EXPECT_EQ(r.w, 17u);
}

TEST(Packing, PlacementsNeverOverlapAndStayInsideTheAtlas) {
  std::vector<PackRect> rects;
  uint32_t seed = 12345;
  for (int i = 0; i < 300; ++i) {
    seed = seed * 1664525u + 1013904223u;
    rects.push_back(PackRect{1 + (seed >> 8) % 40, 1 + (seed >> 20) % 40});
  }
  const PackResult r = packAtlas(rects, 512);
  ASSERT_TRUE(r.ok);
  std::vector<uint8_t> used(512 * 512, 0);
  uint64_t area = 0;
  for (size_t i = 0; i < rects.size(); ++i) {
    ASSERT_LE(r.placements[i].x + rects[i].w, 512u);
    ASSERT_LE(r.placements[i].y + rects[i].h, 512u);
    for (uint32_t y = 0; y < rects[i].h; ++y)
      for (uint32_t x = 0; x < rects[i].w; ++x) {
        uint8_t& u = used[(r.placements[i].y + y) * 512 + r.placements[i].x + x];
        ASSERT_EQ(u, 0) << "overlap at rect " << i;
        u = 1;
      }
    area += uint64_t(rects[i].w) * rects[i].h;
  }
  EXPECT_EQ(r.usedTexels, area);
  EXPECT_DOUBLE_EQ(r.coverage(), double(area) / (512.0 * 512.0));
  const PackResult again = packAtlas(rects, 512);
  for (size_t i = 0; i < rects.size(); ++i) EXPECT_EQ(again.placements[i].x, r.placements[i].x);
}

TEST(Packing, FailsWhenTheRectanglesCannotFit) {
  std::vector<PackRect> rects(5, PackRect{256, 256});
  EXPECT_FALSE(packAtlas(rects, 512).ok);
  rects.resize(4);
  const PackResult r = packAtlas(rects, 512);
  EXPECT_TRUE(r.ok);
  EXPECT_DOUBLE_EQ(r.coverage(), 1.0);
  EXPECT_FALSE(packAtlas(std::vector<PackRect>{{513, 1}}, 512).ok);
}

}  // namespace
}  // namespace tessera::mta
