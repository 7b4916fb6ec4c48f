// The Embree visibility oracle against the CPU oracle: every mismatching pixel of an ID frame must be
// explained by the edge bound or the depth bound of docs/visibility.md, and a corrupted oracle image
// must not be.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <iostream>

#include "tools/scenes/builder.h"
#include "tools/scenes/scenes.h"
#include "verify/visibility.h"

namespace tessera::verify {

namespace {

void print(const char* what, const VisibilityResult& r) {
  std::cout << what << ": " << visibilityToJson(r).dump() << "\n";
}

// An ID frame: two R32UI targets + depth, cleared to the background, object_id bound.
struct IdFrame {
  CommandList cl;
  int w, h;
  IdFrame(int width, int height) : w(width), h(height) {
    RenderTarget t;
    t.color[0] = scenes::createTarget(cl, Format::R32UI, w, h);
    t.color[1] = scenes::createTarget(cl, Format::R32UI, w, h);
    t.depth = scenes::createTarget(cl, Format::D32F, w, h);
    cl.setRenderTarget(t);
    cl.setViewport({0, 0, w, h});
    cl.clearColorUint(0, {0xffffffffu, 0, 0, 0});
    cl.clearColorUint(1, {0xffffffffu, 0, 0, 0});
    cl.clearDepth(1.0f);
    cl.useProgram(cl.createProgram("object_id"));
  }
  void depth(CompareFunc f) {
    DepthState ds;
    ds.test = true;
    ds.func = f;
    cl.setDepthState(ds);
  }
};

// Pixels whose 5x5 neighbourhood carries one (object, primitive) pair of a building: far from every
// edge, so changing them cannot be explained.
std::vector<size_t> interiorPixels(const IdImages& ids, size_t wanted) {
  std::vector<size_t> out;
  for (int32_t y = 2; y + 2 < ids.height && out.size() < wanted; y += 7)
    for (int32_t x = 2; x + 2 < ids.width && out.size() < wanted; x += 5) {
      const size_t p = size_t(y) * size_t(ids.width) + size_t(x);
      if (ids.object[p] == 0 || ids.object[p] == 0xffffffffu) continue;
      bool uniform = true;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const size_t q = size_t(y + dy) * size_t(ids.width) + size_t(x + dx);
          uniform = uniform && ids.object[q] == ids.object[p] && ids.primitive[q] == ids.primitive[p];
        }
      if (uniform) out.push_back(p);
    }
  return out;
}

}  // namespace

class CityIds : public ::testing::TestWithParam<std::pair<int, int>> {};

TEST_P(CityIds, EveryMismatchIsExplainedByTheEdgeOrDepthBound) {
  const auto [w, h] = GetParam();
  const VisibilityResult r = castVisibility(scenes::build("city_ids", w, h));
  print(("city_ids " + std::to_string(w) + "x" + std::to_string(h)).c_str(), r);
  EXPECT_EQ(r.pixels, uint64_t(w) * uint64_t(h));
  EXPECT_EQ(r.unexplained, 0u) << visibilityToJson(r)["first_unexplained"].dump(1);
  EXPECT_EQ(r.matching + r.explainedEdge + r.explainedDepthTie + r.explainedReference + r.unexplained, r.pixels);
  EXPECT_GT(r.exactMatchPercent, 99.0);
  EXPECT_EQ(r.depthOutOfTolerance, 0u);
  // Every edge explanation stays within what snapping can do, not just within edgeEpsilon.
  EXPECT_LE(r.maxEdgeDistanceUsed, kMaxSnapDisplacement);
  EXPECT_GT(r.triangles, 10000u);
}

INSTANTIATE_TEST_SUITE_P(DefaultAnd640x480, CityIds, ::testing::Values(std::pair{320, 240}, std::pair{640, 480}),
                         [](const auto& param) {
                           return std::to_string(param.param.first) + "x" + std::to_string(param.param.second);
                         });

TEST(Visibility, CorruptedOracleIdsAreUnexplained) {
  const CommandList list = scenes::build("city_ids", 320, 240);
  IdImages oracle = renderOracleIds(list);
  const std::vector<size_t> victims = interiorPixels(oracle, 30);
  ASSERT_EQ(victims.size(), 30u);
  // Three kinds of damage: wrong object, wrong primitive, a hole (background).
  for (size_t i = 0; i < victims.size(); ++i) {
    const size_t p = victims[i];
    if (i % 3 == 0) oracle.object[p] = oracle.object[p] % 256 + 1;
    if (i % 3 == 1) oracle.primitive[p] += 1000;
    if (i % 3 == 2) oracle.object[p] = oracle.primitive[p] = 0xffffffffu;
  }
  const VisibilityResult r = compareVisibility(list, oracle);
  EXPECT_EQ(r.unexplained, victims.size());
  ASSERT_FALSE(r.firstUnexplained.empty());
  const size_t first = *std::min_element(victims.begin(), victims.end());
  EXPECT_EQ(size_t(r.firstUnexplained[0].y) * 320 + size_t(r.firstUnexplained[0].x), first);
  EXPECT_FALSE(r.firstUnexplained[0].reason.empty());
  EXPECT_GT(r.firstUnexplained[0].edgeDistance, r.edgeEpsilon);
}

TEST(Visibility, IdsShiftedByOnePixelAtSilhouettesAreUnexplained) {
  // The edge bound must stay tight: copying the right neighbour's ids across an edge moves that edge
  // by a whole pixel, far more than edgeEpsilon.
  const CommandList list = scenes::build("city_ids", 320, 240);
  IdImages oracle = renderOracleIds(list);
  const IdImages original = oracle;
  size_t changed = 0;
  for (size_t p = 0; p + 1 < original.object.size() && changed < 200; p += 3) {
    if (p % 320 == 319 || original.object[p] == 0xffffffffu || original.object[p + 1] == 0xffffffffu) continue;
    if (original.object[p] == original.object[p + 1] && original.primitive[p] == original.primitive[p + 1]) continue;
    oracle.object[p] = original.object[p + 1], oracle.primitive[p] = original.primitive[p + 1];
    ++changed;
  }
  ASSERT_EQ(changed, 200u);
  const VisibilityResult r = compareVisibility(list, oracle);
  // A pixel centre may by chance lie within 1/256 px of the neighbour's triangle: allow 2 %.
  EXPECT_GE(r.unexplained, changed * 98 / 100);
}

TEST(Visibility, AFartherTriangleShownInFrontIsUnexplained) {
  IdFrame f(64, 64);
  scenes::Mesh mesh;
  mesh.quad({-0.9f, -0.9f, 0.5f}, {0.5f, -0.9f, 0.5f}, {0.5f, 0.5f, 0.5f}, {-0.9f, 0.5f, 0.5f}, {}, {}, {}, {}, 1);
  mesh.quad({-0.5f, -0.5f, 0.0f}, {0.9f, -0.5f, 0.0f}, {0.9f, 0.9f, 0.0f}, {-0.5f, 0.9f, 0.0f}, {}, {}, {}, {}, 2);
  scenes::bindMesh(f.cl, mesh);
  scenes::setMatrix(f.cl, 0, glm::mat4(1.0f));
  f.depth(CompareFunc::Less);
  f.cl.drawIndexed(0, 12);
  IdImages oracle = renderOracleIds(f.cl);
  const size_t centre = 24 * 64 + 40;  // in the overlap: object 2 is nearer
  ASSERT_EQ(oracle.object[centre], 2u);
  oracle.object[centre] = 1, oracle.primitive[centre] = 0;  // the triangle of quad 1 behind it
  const VisibilityResult r = compareVisibility(f.cl, oracle);
  EXPECT_EQ(r.unexplained, 1u);
  ASSERT_EQ(r.firstUnexplained.size(), 1u);
  EXPECT_NE(r.firstUnexplained[0].reason.find("nearer"), std::string::npos) << r.firstUnexplained[0].reason;
}

TEST(Visibility, CoplanarQuadsWithOtherDiagonalsAreDepthTies) {
  // The same plane drawn twice, split along different diagonals: the oracle's float depths of the two
  // differ by rounding only, so which one wins is a depth tie at every pixel.
  for (CompareFunc func : {CompareFunc::Less, CompareFunc::LEqual}) {
    IdFrame f(80, 60);
    scenes::Mesh mesh;
    const glm::vec3 p[4] = {{-0.9f, -0.8f, 0.3f}, {0.8f, -0.9f, -0.2f}, {0.9f, 0.85f, 0.4f}, {-0.85f, 0.9f, 0.9f}};
    // Make the fourth corner coplanar with the first three: p3 = p0 + p2 - p1.
    const glm::vec3 q3 = p[0] + p[2] - p[1];
    mesh.quad(p[0], p[1], p[2], q3, {}, {}, {}, {}, 1);
    mesh.quad(p[1], p[2], q3, p[0], {}, {}, {}, {}, 2);
    scenes::bindMesh(f.cl, mesh);
    scenes::setMatrix(f.cl, 0,
                      scenes::mul(scenes::perspective(60.0, 80.0 / 60.0, 0.5, 10.0),
                                  scenes::lookAt({0.2f, -0.3f, 2.5f}, {0, 0, 0}, {0, 1, 0})));
    f.depth(func);
    f.cl.drawIndexed(0, 12);
    const VisibilityResult r = castVisibility(f.cl);
    print(func == CompareFunc::Less ? "coplanar LESS" : "coplanar LEQUAL", r);
    EXPECT_EQ(r.unexplained, 0u) << visibilityToJson(r)["first_unexplained"].dump(1);
    EXPECT_GT(r.explainedDepthTie, 0u);
  }
}

TEST(Visibility, RandomTriangleSoupsUnderEverySupportedStateAreExplained) {
  // Clip-space triangles (some behind the eye), several draws with LESS / LEQUAL, every cull mode and
  // winding, viewports hanging off the target, scissors, a clear depth below 1.
  for (uint64_t seed = 1; seed <= 24; ++seed) {
    scenes::Rng rng{seed * 7919};
    const int w = 40 + int(rng.below(160)), h = 30 + int(rng.below(120));
    IdFrame f(w, h);
    f.cl.clearDepth(rng.below(4) == 0 ? 0.7f : 1.0f);
    std::vector<scenes::Vertex> verts;
    const uint32_t tris = 50 + rng.below(250);
    for (uint32_t i = 0; i < tris * 3; ++i) {
      scenes::Vertex v{};
      const float wc = rng.below(10) == 0 ? -0.5f + rng.unit() : 0.3f + 2.0f * rng.unit();
      v.attr[0] = (rng.unit() * 3.0f - 1.5f) * wc;
      v.attr[1] = (rng.unit() * 3.0f - 1.5f) * wc;
      v.attr[2] = (rng.unit() * 2.4f - 1.2f) * wc;
      v.attr[3] = wc;
      v.id = i / 3 % 97;
      verts.push_back(v);
    }
    f.cl.bindVertexBuffer(f.cl.createBuffer(
        BufferKind::Vertex, {reinterpret_cast<const uint8_t*>(verts.data()), verts.size() * sizeof(scenes::Vertex)}));
    VertexLayout layout;  // the 4-component attribute slot carries the clip-space position
    layout.stride = sizeof(scenes::Vertex);
    layout.attribs[0] = {0, 4, AttribType::F32, uint32_t(offsetof(scenes::Vertex, attr))};
    layout.attribs[1] = {2, 1, AttribType::U32, uint32_t(offsetof(scenes::Vertex, id))};
    f.cl.setVertexLayout(layout);
    scenes::setMatrix(f.cl, 0, glm::mat4(1.0f));
    for (uint32_t first = 0; first < tris * 3;) {
      f.depth(rng.below(2) ? CompareFunc::Less : CompareFunc::LEqual);
      f.cl.setRasterState({CullMode(rng.below(3)), rng.below(2) == 0, 0});
      f.cl.setViewport(
          {int(rng.below(20)) - 10, int(rng.below(20)) - 10, w - int(rng.below(20)), h + int(rng.below(20)) - 10});
      f.cl.setScissor(
          {rng.below(3) == 0, {int(rng.below(uint32_t(w / 2))), int(rng.below(uint32_t(h / 2))), w / 2, h / 2}});
      const uint32_t count = std::min(tris * 3 - first, 3 * (1 + rng.below(tris)));
      f.cl.draw(first, count);
      first += count;
    }
    const VisibilityResult r = castVisibility(f.cl);
    EXPECT_EQ(r.unexplained, 0u) << "seed " << seed << ": " << visibilityToJson(r)["first_unexplained"].dump(1);
    EXPECT_LE(r.maxEdgeDistanceUsed, kMaxSnapDisplacement) << "seed " << seed;
    EXPECT_EQ(r.depthOutOfTolerance, 0u) << "seed " << seed;
    EXPECT_GT(r.triangles, 0u) << "seed " << seed << ": no triangle reached Embree, so nothing was compared";
  }
}

TEST(Visibility, NearPlaneCrossingTrianglesAreClippedLikeTheOracle) {
  IdFrame f(200, 150);
  scenes::Mesh mesh;
  // A ground triangle reaching far behind the eye and a wall that the near plane cuts diagonally.
  mesh.triangle({{-30, -20, 0}, {0, 0, 0, 0}, 1}, {{30, -20, 0}, {0, 0, 0, 0}, 1}, {{0, 40, 0}, {0, 0, 0, 0}, 1});
  mesh.quad({-3, -4, 0}, {2, 6, 0}, {2, 6, 3}, {-3, -4, 3}, {}, {}, {}, {}, 2);
  mesh.quad({1, 8, 0}, {4, 8, 0}, {4, 8, 2}, {1, 8, 2}, {}, {}, {}, {}, 3);
  const uint32_t n = scenes::bindMesh(f.cl, mesh);
  const glm::mat4 vp = scenes::mul(scenes::perspective(70.0, 200.0 / 150.0, 0.5, 60.0),
                                   scenes::lookAt({0, -2, 1.2f}, {0.5f, 10, 0.5f}, {0, 0, 1}));
  scenes::setMatrix(f.cl, 0, vp);
  f.depth(CompareFunc::Less);
  f.cl.drawIndexed(0, n);
  const VisibilityResult r = castVisibility(f.cl);
  print("near plane", r);
  EXPECT_GT(r.primitivesClipped, 0u);
  EXPECT_EQ(r.unexplained, 0u) << visibilityToJson(r)["first_unexplained"].dump(1);
  EXPECT_GT(r.exactMatchPercent, 99.0);
  // The ground must really be there: most pixels show an object, not the background.
  uint64_t background = 0;
  for (uint32_t id : r.embree.object) background += id == 0xffffffffu;
  EXPECT_LT(background, r.pixels / 2);
}

TEST(Visibility, ExactDepthTiesResolveLikeTheDepthFunction) {
  for (CompareFunc func : {CompareFunc::Less, CompareFunc::LEqual}) {
    IdFrame f(96, 64);
    scenes::Mesh mesh;
    for (uint32_t id : {1u, 2u})  // the same quad twice, only the id differs
      mesh.quad({-0.8f, -0.7f, 0.1f}, {0.9f, -0.6f, 0.3f}, {0.7f, 0.8f, -0.2f}, {-0.6f, 0.5f, 0.0f}, {}, {}, {}, {},
                id);
    scenes::bindMesh(f.cl, mesh);
    scenes::setMatrix(f.cl, 0, glm::mat4(1.0f));
    f.depth(func);
    f.cl.drawIndexed(0, 6);
    f.cl.drawIndexed(6, 6);
    const VisibilityResult r = castVisibility(f.cl);
    EXPECT_EQ(r.matching, r.pixels) << "func " << int(func);
    const uint32_t expected = func == CompareFunc::Less ? 1u : 2u;
    EXPECT_EQ(r.embree.object[32 * 96 + 48], expected);
  }
}

TEST(Visibility, UnsupportedStateIsAClearError) {
  IdFrame f(32, 32);
  scenes::Mesh mesh;
  mesh.quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {}, {}, {}, {}, 1);
  scenes::bindMesh(f.cl, mesh);
  scenes::setMatrix(f.cl, 0, glm::mat4(1.0f));
  f.depth(CompareFunc::Greater);
  f.cl.drawIndexed(0, 6);
  try {
    castVisibility(f.cl);
    FAIL() << "GREATER must be refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("depth function"), std::string::npos) << e.what();
  }
  // A frame drawn with other programs is no longer refused: it is rewritten (test_visibility_rewrite.cpp).
  VisibilityOptions bogus;
  bogus.isas = {"sse9"};  // Embree would silently run SSE2 for this name
  EXPECT_THROW(castVisibility(scenes::build("city_ids", 32, 24), bogus), Error);
}

TEST(Visibility, JsonIsDeterministicAndComplete) {
  const CommandList list = scenes::build("city_ids", 160, 120);
  VisibilityOptions one;
  one.threads = 1;
  const nlohmann::json a = visibilityToJson(castVisibility(list, one));
  const nlohmann::json b = visibilityToJson(castVisibility(list));
  EXPECT_EQ(a.dump(), b.dump());
  for (const char* key : {"pixels", "matching", "exact_match_percent", "explained_edge", "explained_depth_tie",
                          "unexplained", "first_unexplained", "background_mismatches", "embree"})
    EXPECT_TRUE(a.contains(key)) << key;
  EXPECT_FALSE(a["embree"]["version"].get<std::string>().empty());
  EXPECT_FALSE(a["embree"]["isa"].get<std::string>().empty());
}

}  // namespace tessera::verify
