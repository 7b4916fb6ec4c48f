// The Embree visibility oracle against the CPU oracle: every mismatching pixel of an ID frame must be
// explained by the edge bound or the depth bound of docs/visibility.md, and a corrupted oracle image
// must not be.
#include <gtest/gtest.h>

#include <iostream>

#include "tools/scenes/builder.h"
#include "tools/scenes/scenes.h"
#include "verify/visibility.h"

using namespace tessera;
using namespace tessera::verify;

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
  EXPECT_LE(r.maxEdgeDistanceUsed, r.edgeEpsilon);
  EXPECT_GT(r.triangles, 10000u);
}

INSTANTIATE_TEST_SUITE_P(DefaultAnd640x480, CityIds,
                         ::testing::Values(std::pair{320, 240}, std::pair{640, 480}),
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

TEST(Visibility, NearPlaneCrossingTrianglesAreClippedLikeTheOracle) {
  IdFrame f(200, 150);
  scenes::Mesh mesh;
  // A ground triangle reaching far behind the eye and a wall that the near plane cuts diagonally.
  mesh.triangle({{-30, -20, 0}, {0, 0, 0, 0}, 1}, {{30, -20, 0}, {0, 0, 0, 0}, 1}, {{0, 40, 0}, {0, 0, 0, 0}, 1});
  mesh.quad({-3, -4, 0}, {2, 6, 0}, {2, 6, 3}, {-3, -4, 3}, {}, {}, {}, {}, 2);
  mesh.quad({1, 8, 0}, {4, 8, 0}, {4, 8, 2}, {1, 8, 2}, {}, {}, {}, {}, 3);
  const uint32_t n = scenes::bindMesh(f.cl, mesh);
  const scenes::Mat4 vp = scenes::perspective(70.0, 200.0 / 150.0, 0.5, 60.0) *
                          scenes::lookAt({0, -2, 1.2f}, {0.5f, 10, 0.5f}, {0, 0, 1});
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
      mesh.quad({-0.8f, -0.7f, 0.1f}, {0.9f, -0.6f, 0.3f}, {0.7f, 0.8f, -0.2f}, {-0.6f, 0.5f, 0.0f}, {}, {}, {}, {}, id);
    scenes::bindMesh(f.cl, mesh);
    scenes::setMatrix(f.cl, 0, scenes::Mat4::identity());
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
  scenes::setMatrix(f.cl, 0, scenes::Mat4::identity());
  f.depth(CompareFunc::Greater);
  f.cl.drawIndexed(0, 6);
  try {
    castVisibility(f.cl);
    FAIL() << "GREATER must be refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("depth function"), std::string::npos) << e.what();
  }
  EXPECT_THROW(castVisibility(scenes::build("city_block", 64, 48)), Error);  // not an ID program
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
