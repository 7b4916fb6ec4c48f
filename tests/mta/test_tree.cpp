// Split balance and non-emptiness, critical triangles, contiguous ranges, texture matrices.
#include <gtest/gtest.h>

#include <cmath>

#include "mta/critical.h"
#include "mta/split.h"
#include "mta/tree_build.h"
#include "mta_test_scene.h"

namespace tessera::mta {
namespace {

using testing::gridScene;

std::vector<uint32_t> all(const Geometry& g) {
  std::vector<uint32_t> v(g.triangleCount());
  for (uint32_t i = 0; i < v.size(); ++i) v[i] = i;
  return v;
}

TEST(Split, FourNonEmptyChildrenWithBalancedAreaAlongTheTwoLargestAxes) {
  const Scene s = gridScene(16, 4);
  const auto tris = all(s.geometry);
  const auto axes = splitAxes(s.geometry, tris);
  EXPECT_EQ(axes[0], 0);
  EXPECT_EQ(axes[1], 1);
  const auto groups = splitTriangles(s.geometry, tris);
  double total = 0.0;
  for (uint32_t t : tris) total += triangleArea(s.geometry, t);
  size_t count = 0;
  for (const auto& gr : groups) {
    ASSERT_FALSE(gr.empty());
    double a = 0.0;
    for (uint32_t t : gr) a += triangleArea(s.geometry, t);
    EXPECT_NEAR(a, total / 4.0, 0.5 + 1e-9);  // within one triangle's area of a quarter
    count += gr.size();
  }
  EXPECT_EQ(count, tris.size());
}

TEST(Split, SmallSetsNeverProduceEmptyChildrenAndZeroAreaFallsBackToCounts) {
  const Scene s = gridScene(2, 1);
  for (size_t n = 2; n <= 4; ++n) {
    std::vector<uint32_t> tris;
    for (uint32_t i = 0; i < n; ++i) tris.push_back(i);
    const auto groups = splitTriangles(s.geometry, tris);
    size_t nonEmpty = 0, total = 0;
    for (const auto& g : groups) nonEmpty += !g.empty(), total += g.size();
    EXPECT_EQ(nonEmpty, n == 4 ? 4u : n);
    EXPECT_EQ(total, n);
  }
  Geometry flat = s.geometry;
  for (glm::vec3& p : flat.positions) p.y = 0.0f;  // every triangle degenerate: area 0
  const auto groups = splitTriangles(flat, all(flat));
  EXPECT_FALSE(groups[0].empty());
  EXPECT_FALSE(groups[1].empty());
}

BuildParams treeParams() {
  BuildParams p;
  p.atlasSize = 64;
  p.border = 2;
  p.tanHalfFov = 0.5;
  p.screenWidth = 256;
  return p;
}

TEST(Critical, FewCriticalTrianglesAreSplitUntilNoneIsCritical) {
  Scene s = gridScene(4, 1);
  // One big quad (triangles 0, 1): 40 x 40 units.
  for (int k = 0; k < 6; ++k) {
    s.geometry.positions[k].x *= 40.0f;
    s.geometry.positions[k].y *= 40.0f;
  }
  BuildParams p = treeParams();
  p.criticalThreshold = 0.5;
  CriticalReport rep;
  const double d = 10.0;
  const Geometry g = handleCriticalTriangles(s, p, d, rep);
  EXPECT_EQ(rep.criticalAtRequested, 2u);
  EXPECT_EQ(rep.criticalAfterRaise, 2u);
  EXPECT_EQ(rep.dMinUsed, d);
  EXPECT_GT(rep.trianglesAdded, 0u);
  EXPECT_EQ(g.triangleCount(), s.geometry.triangleCount() + rep.trianglesAdded);
  const double fProj = projectionFactor(p, rep.dMinUsed);
  double area = 0.0, areaIn = 0.0;
  for (uint32_t t = 0; t < g.triangleCount(); ++t) {
    EXPECT_FALSE(isCritical(triangleRequirement(s, g, t, fProj, p.border), p.atlasSize)) << t;
    area += triangleArea(g, t);
  }
  for (uint32_t t = 0; t < s.geometry.triangleCount(); ++t) areaIn += triangleArea(s.geometry, t);
  EXPECT_NEAR(area, areaIn, 1e-6 * areaIn);
}

TEST(Critical, ManyCriticalTrianglesRaiseDMinToTheThreshold) {
  const Scene s = gridScene(4, 4);
  BuildParams p = treeParams();
  p.criticalThreshold = 0.25;
  CriticalReport rep;
  const Geometry g = handleCriticalTriangles(s, p, 0.05, rep);  // every triangle is critical at 5 cm
  EXPECT_EQ(rep.criticalAtRequested, 32u);
  EXPECT_GT(rep.dMinUsed, 0.05);
  EXPECT_LE(rep.criticalAfterRaise, 8u);
  // At the raised d_min with threshold 0 nothing may remain critical after splitting.
  p.criticalThreshold = 0.0;
  const Geometry g0 = handleCriticalTriangles(s, p, 0.05, rep);
  EXPECT_EQ(rep.criticalAfterRaise, 0u);
  EXPECT_EQ(g0.triangleCount(), 32u);
}

void checkTree(const Scene& s, const Tree& tree, const BuildParams& p) {
  ASSERT_FALSE(tree.nodes.empty());
  EXPECT_EQ(tree.nodes[0].triangleCount, tree.geometry.triangleCount());
  for (size_t i = 0; i < tree.nodes.size(); ++i) {
    const Node& n = tree.nodes[i];
    if (n.leaf()) {
      EXPECT_GT(n.triangleCount, 0u);
      EXPECT_EQ(n.minDistance, tree.nodes.back().minDistance == 0 ? 0 : n.minDistance);
      continue;
    }
    uint32_t next = n.firstTriangle;
    float maxChild = 0.0f;
    for (int q = 0; q < 4; ++q) {
      if (n.children[q] < 0) continue;
      const Node& c = tree.nodes[n.children[q]];
      EXPECT_EQ(c.firstTriangle, next) << "node " << i << " child " << q;  // §4.8.1: contiguous, in order
      EXPECT_EQ(c.level, n.level + 1);
      next += c.triangleCount;
      maxChild = std::max(maxChild, c.minDistance);
    }
    EXPECT_EQ(next, n.firstTriangle + n.triangleCount);
    // Equal unless a leaf child's need was capped by an image's size (then d_min · cap factor counts).
    EXPECT_GE(n.minDistance, 2.0f * maxChild);
  }
  // Texture matrix round trip for every vertex and every node on its path: root coords scaled by 2^k
  // fall inside R(N), and frac() gives the node-local coordinate.
  for (size_t i = 0; i < tree.nodes.size(); ++i) {
    const Node& n = tree.nodes[i];
    for (uint32_t t = n.firstTriangle; t < n.firstTriangle + n.triangleCount; ++t) {
      if (tree.geometry.layers[0].texture[t] < 0) continue;
      for (int k = 0; k < 3; ++k) {
        const glm::vec2 r = tree.atlasUV[t * 3 + k];
        const double sx = double(r.x) * n.textureScale() - n.cellX, sy = double(r.y) * n.textureScale() - n.cellY;
        ASSERT_GE(sx, -1e-6) << "node " << i;
        ASSERT_LE(sx, 1.0 + 1e-6) << "node " << i;
        ASSERT_GE(sy, -1e-6);
        ASSERT_LE(sy, 1.0 + 1e-6);
        if (sx > 1e-6 && sx < 1.0 - 1e-6) {
          EXPECT_NEAR(toLocal(r.x, n.level), sx, 1e-6);
        }
        if (n.leaf()) {  // inside the texture's area of the leaf atlas
          const AtlasEntry* e = nullptr;
          for (const AtlasEntry& x : n.entries)
            if (x.texture == tree.geometry.layers[0].texture[t]) e = &x;
          ASSERT_NE(e, nullptr);
          const double px = sx * p.atlasSize, py = sy * p.atlasSize;
          EXPECT_GE(px, e->x + p.border - 1e-3);
          EXPECT_LE(px, e->x + e->w - p.border + 1e-3);
          EXPECT_GE(py, e->y + p.border - 1e-3);
          EXPECT_LE(py, e->y + e->h - p.border + 1e-3);
        }
      }
    }
  }
  (void)s;
}

TEST(Tree, EveryNodeIsAContiguousRangeAndTextureMatricesRoundTripInADeepTree) {
  const Scene s = gridScene(32, 32, 32, 2.0f);
  BuildParams p = treeParams();
  CriticalReport rep;
  const double d = 3.0;
  const Geometry g = handleCriticalTriangles(s, p, d, rep);
  const auto tris = all(g);
  const Tree tree = buildTree(s, g, tris, 0, p, rep.dMinUsed);
  EXPECT_GE(tree.depth(), 5u);
  checkTree(s, tree, p);
  // Deterministic: the same input gives the same tree.
  const Tree again = buildTree(s, g, tris, 0, p, rep.dMinUsed);
  ASSERT_EQ(again.nodes.size(), tree.nodes.size());
  for (size_t i = 0; i < tree.atlasUV.size(); ++i) ASSERT_EQ(again.atlasUV[i].x, tree.atlasUV[i].x);
}

TEST(Tree, ASceneThatFitsOneAtlasIsASingleLeafAndRepeatOffsetsDoNotGrowTheArea) {
  const Scene s = gridScene(2, 2, 32, 1.0f);
  BuildParams p = treeParams();
  const auto tris = all(s.geometry);
  const Tree tree = buildTree(s, s.geometry, tris, 0, p, 1000.0);
  ASSERT_EQ(tree.nodes.size(), 1u);
  ASSERT_EQ(tree.nodes[0].entries.size(), 4u);
  for (const AtlasEntry& e : tree.nodes[0].entries) {
    // Texcoords at offset q were shifted back to [0, 1]: A_tex (the source's centre) is that of one repeat.
    EXPECT_DOUBLE_EQ(0.5 * (e.source.u0 + e.source.u1), 0.5);
  }
  checkTree(s, tree, p);
}

}  // namespace
}  // namespace tessera::mta
