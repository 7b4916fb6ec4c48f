// The node-transform helpers of model/loaders.h keep the summation orders the stored positions were
// always computed with; GLM's own operators would give other bits in these cases.
#include <gtest/gtest.h>

#include <cmath>

#include "model/loaders.h"

namespace tessera::model::detail {
namespace {

TEST(NodeTransform, ComposingGivesPositiveZeroWhereEveryProductIsNegativeZero) {
  // Entry (column 1, row 0) of parent * child is Σk parent[k][0] · child[1][k] = four products
  // (-1) · 0 = -0. GLM's product sums them to -0; the loaders' sum starts from +0.0 and gives +0.
  glm::dmat4 parent(1.0), child(1.0);
  for (int k = 0; k < 4; ++k) parent[k][0] = -1.0, child[1][k] = 0.0;
  ASSERT_TRUE(std::signbit((parent * child)[1][0]));  // what compose must not give
  const glm::dmat4 r = compose(parent, child);
  EXPECT_EQ(r[1][0], 0.0);
  EXPECT_FALSE(std::signbit(r[1][0]));
  EXPECT_EQ(r[0][0], -1.0);  // a non-zero entry is GLM's sum: (-1) · 1 plus three -0 products
}

TEST(NodeTransform, PointsAreSummedLeftToRightBeforeTheTranslation) {
  // x' = ((m00 · 1 + m10 · 0) + m20 · 1) + m30 with m00 = T = 2^53 + 2^29 (a float rounding tie) and
  // m20 = m30 = 1: T + 1 rounds to T (ties to even in double), then T + 1 again to T, and float(T) is
  // 2^53 (ties to even). GLM's m * vec4 would add T + (1 + 1) = T + 2 exactly, which rounds up in float.
  const double t = 9007199254740992.0 + 536870912.0;
  glm::dmat4 m(1.0);
  m[0][0] = t, m[2][0] = 1.0, m[3][0] = 1.0;
  EXPECT_EQ(transformPoint(m, {1.0f, 0.0f, 1.0f}).x, 9007199254740992.0f);
  EXPECT_EQ(float((m * glm::dvec4(1.0, 0.0, 1.0, 1.0)).x), 9007200328482816.0f);  // 2^53 + 2^30: not this
}

TEST(NodeTransform, NormalsUseTheCofactorMatrixAndKeepTheirSideUnderAMirror) {
  // Scale (2, 1, 1): the inverse transpose scales x by 1/2, so (1, 1, 0) becomes (1/2, 1, 0) / |.|.
  glm::dmat4 m(1.0);
  m[0][0] = 2.0;
  const glm::vec3 n = transformNormal(m, {1.0f, 1.0f, 0.0f});
  EXPECT_FLOAT_EQ(n.x, float(0.5 / std::sqrt(1.25)));
  EXPECT_FLOAT_EQ(n.y, float(1.0 / std::sqrt(1.25)));
  EXPECT_EQ(n.z, 0.0f);
  // A mirror in x (determinant -1) flips the normal's x like the geometry, and det3 reports it.
  glm::dmat4 mirror(1.0);
  mirror[0][0] = -1.0;
  EXPECT_EQ(det3(mirror), -1.0);
  const glm::vec3 f = transformNormal(mirror, {1.0f, 0.0f, 0.0f});
  EXPECT_EQ(f.x, -1.0f);
  EXPECT_EQ(f.y, 0.0f);
  EXPECT_EQ(f.z, 0.0f);
}

}  // namespace
}  // namespace tessera::model::detail
