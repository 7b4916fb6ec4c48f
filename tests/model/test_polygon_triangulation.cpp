// Polygon triangulation (model/polygon_triangulation.h): the triangles Assimp made for simple polygons,
// a cover of concave outlines without overlap, and bounded work on hostile polygons.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "model/polygon_triangulation.h"

namespace tessera::model::detail {
namespace {

// Twice the signed area in the xy plane.
double area2(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  return double(b.x - a.x) * double(c.y - a.y) - double(b.y - a.y) * double(c.x - a.x);
}

double polygonArea2(const std::vector<glm::vec3>& p) {
  double s = 0.0;
  for (size_t i = 0; i < p.size(); ++i) {
    const glm::vec3 &a = p[i], &b = p[(i + 1) % p.size()];
    s += double(a.x) * double(b.y) - double(b.x) * double(a.y);
  }
  return s;
}

// Even-odd rule: is (x, y) inside the outline?
bool inside(const std::vector<glm::vec3>& p, double x, double y) {
  bool in = false;
  for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
    if ((p[i].y > y) != (p[j].y > y) && x < (p[j].x - p[i].x) * (y - p[i].y) / (p[j].y - p[i].y) + p[i].x) in = !in;
  return in;
}

// A comb, counter-clockwise: a bar [0, 2t - 1] x [0, 1] with t teeth [2k, 2k + 1] x [1, 3] on top,
// 4t corners, area 2t - 1 + 2t.
std::vector<glm::vec3> comb(int teeth) {
  std::vector<glm::vec3> p{{0, 0, 0}, {float(2 * teeth - 1), 0, 0}};
  for (int k = teeth - 1; k >= 0; --k) {
    p.push_back({float(2 * k + 1), 3, 0});
    p.push_back({float(2 * k), 3, 0});
    if (k > 0) p.push_back({float(2 * k), 1, 0}), p.push_back({float(2 * k - 1), 1, 0});
  }
  return p;
}

TEST(PolygonTriangulation, AConvexPentagonBecomesTheFanAroundItsLastCorner) {
  const std::vector<glm::vec3> p{{2, 0, 0}, {3, 2, 0}, {1, 3, 0}, {-1, 2, 0}, {0, 0, 0}};
  std::vector<uint32_t> out;
  uint64_t work = 1000;
  EXPECT_TRUE(triangulatePolygon(p, out, work));
  // Ears are clipped from corner 0 with corner 4 before it: (4, 0, 1), (4, 1, 2), then the last three.
  EXPECT_EQ(out, (std::vector<uint32_t>{4, 0, 1, 4, 1, 2, 2, 3, 4}));
}

TEST(PolygonTriangulation, AConvexQuadIsSplitFromCornerZero) {
  const std::vector<glm::vec3> p{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  std::vector<uint32_t> out;
  uint64_t work = 0;  // quads need no search
  EXPECT_TRUE(triangulatePolygon(p, out, work));
  EXPECT_EQ(out, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
}

TEST(PolygonTriangulation, AConcaveQuadIsSplitAlongTheDiagonalFromItsReflexCorner) {
  // A dart: corner 2 at (1, 0.5) points into the quad; the diagonal 0-2 would leave it.
  const std::vector<glm::vec3> p{{0, 0, 0}, {2, 0, 0}, {1, 0.5f, 0}, {0, 2, 0}};
  std::vector<uint32_t> out;
  uint64_t work = 0;
  EXPECT_TRUE(triangulatePolygon(p, out, work));
  EXPECT_EQ(out, (std::vector<uint32_t>{2, 3, 0, 2, 0, 1}));
}

TEST(PolygonTriangulation, ACombIsCoveredExactlyByCounterClockwiseTriangles) {
  const std::vector<glm::vec3> p = comb(5);
  ASSERT_EQ(p.size(), 20u);
  ASSERT_EQ(polygonArea2(p), 2.0 * (9.0 + 5 * 2.0));  // bar 9 x 1, five teeth 1 x 2 above it
  std::vector<uint32_t> out;
  uint64_t work = 1000000;
  EXPECT_TRUE(triangulatePolygon(p, out, work));
  ASSERT_EQ(out.size(), 3 * (p.size() - 2));
  double sum = 0.0;
  for (size_t i = 0; i < out.size(); i += 3) {
    const glm::vec3 &a = p[out[i]], &b = p[out[i + 1]], &c = p[out[i + 2]];
    const double t = area2(a, b, c);
    EXPECT_GE(t, 0.0) << "triangle " << i / 3;
    sum += t;
    if (t > 0.0) {
      EXPECT_TRUE(inside(p, (double(a.x) + b.x + c.x) / 3, (double(a.y) + b.y + c.y) / 3)) << "triangle " << i / 3;
    }
  }
  // Triangles inside the outline with the outline's total area cannot overlap.
  EXPECT_EQ(sum, polygonArea2(p));
}

TEST(PolygonTriangulation, AnLWhoseReflexCornerTouchesAClippedDiagonalIsNotFoldedOver) {
  // The first ear, (5, 0, 1), has the reflex corner 3 = (1, 1) on its diagonal; clipping it leaves an
  // outline that touches itself there, and Assimp's next ears made a clockwise triangle that overlaps
  // the others. The cover must be exact: every triangle counter-clockwise, areas adding up to 3.
  const std::vector<glm::vec3> p{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  std::vector<uint32_t> out;
  uint64_t work = 1000;
  EXPECT_TRUE(triangulatePolygon(p, out, work));
  ASSERT_EQ(out.size(), 12u);
  double sum = 0.0;
  for (size_t i = 0; i < out.size(); i += 3) {
    const double t = area2(p[out[i]], p[out[i + 1]], p[out[i + 2]]);
    EXPECT_GE(t, 0.0) << "triangle " << i / 3;
    sum += t;
  }
  EXPECT_EQ(sum, 6.0);
}

TEST(PolygonTriangulation, AClockwisePolygonGivesClockwiseTriangles) {
  std::vector<glm::vec3> p = comb(3);
  std::reverse(p.begin(), p.end());
  std::vector<uint32_t> out;
  uint64_t work = 1000000;
  EXPECT_TRUE(triangulatePolygon(p, out, work));
  double sum = 0.0;
  for (size_t i = 0; i < out.size(); i += 3) {
    const double t = area2(p[out[i]], p[out[i + 1]], p[out[i + 2]]);
    EXPECT_LE(t, 0.0);
    sum += t;
  }
  EXPECT_EQ(sum, polygonArea2(p));
  EXPECT_LT(sum, 0.0);
}

TEST(PolygonTriangulation, AnExhaustedWorkBudgetFansTheRestInsteadOfSearchingOn) {
  const std::vector<glm::vec3> p = comb(50);
  std::vector<uint32_t> out;
  uint64_t work = 5;
  EXPECT_FALSE(triangulatePolygon(p, out, work));
  EXPECT_EQ(work, 0u);
  EXPECT_EQ(out.size(), 3 * (p.size() - 2));  // every corner is still used: a fan of what was left
  for (uint32_t i : out) EXPECT_LT(i, p.size());
}

}  // namespace
}  // namespace tessera::model::detail
