// Rasterization rules of the oracle: fill convention, culling, clipping, layers, thread invariance.
#include <gtest/gtest.h>

#include <cmath>

#include <cstring>

#include "raster/fragops.h"
#include "raster/setup.h"
#include "tests/raster/render_helpers.h"
#include "tools/scenes/builder.h"
#include "tools/scenes/scenes.h"

using namespace tessera;
using namespace tessera::scenes;
using tessera::testing::renderList;

namespace {

// A W x H RGBA8 frame drawn with flat_color, additive blend of 0.25 per hit, ortho in pixels.
CommandList additiveFrame(int w, int h, const Mesh& m, RasterState rs = {}) {
  CommandList cl;
  RenderTarget t;
  t.color[0] = createTarget(cl, Format::RGBA8, w, h);
  cl.setRenderTarget(t);
  cl.setViewport({0, 0, w, h});
  cl.clearColor(0, {0, 0, 0, 0});
  const uint32_t n = bindMesh(cl, m);
  cl.useProgram(cl.createProgram("flat_color"));
  setMatrix(cl, 0, ortho(0, w, 0, h, -1, 1));
  setVec4(cl, 4, {0.25f, 0.25f, 0.25f, 0.25f});
  BlendState b;
  b.enabled = true;
  b.srcRgb = b.dstRgb = b.srcAlpha = b.dstAlpha = BlendFactor::One;
  cl.setBlendState(b);
  cl.setRasterState(rs);
  cl.drawIndexed(0, n);
  return cl;
}

Vertex v(float x, float y) { return {{x, y, 0}, {0, 0, 0, 0}, 0}; }

// Red channel of pixel (x, y) in GL window coordinates (y up) of a top-down RGBA8 image.
int red(const std::vector<uint8_t>& img, int w, int h, int x, int y) { return img[(size_t(h - 1 - y) * w + x) * 4]; }

}  // namespace

TEST(FillRule, TwoTrianglesSharingADiagonalCoverEveryPixelExactlyOnce) {
  Mesh m;
  m.triangle(v(0.5f, 0.5f), v(12.5f, 0.5f), v(12.5f, 12.5f));  // edges through pixel centres
  m.triangle(v(0.5f, 0.5f), v(12.5f, 12.5f), v(0.5f, 12.5f));
  const auto r = renderList(additiveFrame(16, 16, m), 1);
  int once = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const int c = red(r.images[0], 16, 16, x, y);
      ASSERT_TRUE(c == 0 || c == 64) << "pixel " << x << "," << y << " = " << c;
      once += c == 64;
    }
  // Centres on the left (x = 0.5) and bottom (y = 0.5) edges are in, right and top are out: 12 x 12.
  EXPECT_EQ(once, 144);
  EXPECT_EQ(red(r.images[0], 16, 16, 0, 0), 64);
  EXPECT_EQ(red(r.images[0], 16, 16, 12, 5), 0);
  EXPECT_EQ(red(r.images[0], 16, 16, 5, 12), 0);
}

TEST(FillRule, ClockwiseTrianglesFollowTheSameLeftBottomRule) {
  Mesh m;
  m.triangle(v(0.5f, 0.5f), v(0.5f, 8.5f), v(8.5f, 0.5f));  // clockwise
  const auto r = renderList(additiveFrame(16, 16, m), 1);
  EXPECT_EQ(red(r.images[0], 16, 16, 0, 0), 64);  // on the left and bottom edges: covered
  EXPECT_EQ(red(r.images[0], 16, 16, 4, 4), 0);   // on the hypotenuse (a right edge): not covered
  EXPECT_EQ(red(r.images[0], 16, 16, 3, 4), 64);
}

TEST(FillRule, FanSceneHasNoGapsAndNoDoubleHits) {
  const auto r = renderList(scenes::build("fill_fan", 128, 128), 2);
  size_t covered = 0;
  for (size_t i = 0; i < r.images[0].size(); i += 4) {
    ASSERT_TRUE(r.images[0][i] == 0 || r.images[0][i] == 64) << "pixel " << i / 4;
    covered += r.images[0][i] == 64;
  }
  // Fan A spans 58 px square with left/bottom inclusive: 58 * 58; fan B 58 x 58 on corners.
  EXPECT_EQ(covered, size_t(58 * 58 * 2));
}

TEST(Culling, ZeroAreaAfterSnappingProducesNothing) {
  Mesh m;
  m.triangle(v(1.0f, 1.0f), v(9.0f, 1.0f), v(5.0f, 1.001f));  // collapses to a line at 1/256 px
  const auto r = renderList(additiveFrame(16, 16, m), 1);
  EXPECT_EQ(r.stats.triangles_binned, 0u);
  EXPECT_EQ(r.stats.primitives_culled, 1u);
}

TEST(Culling, BackFacesAreDroppedOnlyWhenCullingIsEnabled) {
  Mesh m;
  m.triangle(v(0.5f, 0.5f), v(0.5f, 8.5f), v(8.5f, 0.5f));  // clockwise = back-facing
  RasterState rs;
  rs.cull = CullMode::Back;
  EXPECT_EQ(renderList(additiveFrame(16, 16, m, rs), 1).stats.triangles_binned, 0u);
  rs.cull = CullMode::Front;
  EXPECT_EQ(renderList(additiveFrame(16, 16, m, rs), 1).stats.triangles_binned, 1u);
}

TEST(Clipping, ATriangleCrossingTheNearPlaneIsClippedNotDropped) {
  const auto r = renderList(scenes::build("clip_planes", 192, 192), 1);
  EXPECT_GT(r.stats.primitives_clipped, 0u);
  EXPECT_GT(r.stats.pixels_written, 0u);
}

TEST(Snapping, RoundsHalfToEven) {
  EXPECT_EQ(detail::roundHalfEven(0.5), 0);
  EXPECT_EQ(detail::roundHalfEven(1.5), 2);
  EXPECT_EQ(detail::roundHalfEven(2.5), 2);
  EXPECT_EQ(detail::roundHalfEven(-0.5), 0);
  EXPECT_EQ(detail::roundHalfEven(-1.5), -2);
  EXPECT_EQ(detail::roundHalfEven(2.4999), 2);
}

TEST(Fragops, Unorm8ConversionRoundsHalfToEvenAndClampsNaN) {
  EXPECT_EQ(detail::toUnorm8(0.5), 128);         // 127.5 -> 128 (even)
  EXPECT_EQ(detail::toUnorm8(1.5 / 255.0), 2);   // 1.5 -> 2
  EXPECT_EQ(detail::toUnorm8(2.5 / 255.0), 2);   // 2.5 -> 2
  EXPECT_EQ(detail::toUnorm8(-1.0), 0);
  EXPECT_EQ(detail::toUnorm8(7.0), 255);
  EXPECT_EQ(detail::toUnorm8(std::nan("")), 0);
}

TEST(Fragops, BlendClampsUnormSourcesAndAppliesEveryEquation) {
  BlendState b;
  b.enabled = true;
  b.srcRgb = b.srcAlpha = BlendFactor::SrcAlpha;
  b.dstRgb = b.dstAlpha = BlendFactor::OneMinusSrcAlpha;
  const float src[4] = {2.0f, 0.5f, 0.0f, 0.25f};
  const double dst[4] = {0.0, 1.0, 1.0, 1.0};
  double out[4];
  detail::blend(b, true, src, dst, out);
  EXPECT_DOUBLE_EQ(out[0], 0.25);  // src clamped to 1
  EXPECT_DOUBLE_EQ(out[1], 0.5 * 0.25 + 0.75);
  b.eqRgb = BlendEq::Min;
  detail::blend(b, true, src, dst, out);
  EXPECT_DOUBLE_EQ(out[1], 0.5);
  b.eqRgb = BlendEq::ReverseSubtract;
  detail::blend(b, true, src, dst, out);
  EXPECT_DOUBLE_EQ(out[2], 0.75);
}

TEST(Fragops, DepthFunctionsCompareAsGLDefines) {
  using detail::depthPasses;
  EXPECT_TRUE(depthPasses(CompareFunc::Less, 0.25f, 0.5f));
  EXPECT_FALSE(depthPasses(CompareFunc::Less, 0.5f, 0.5f));
  EXPECT_TRUE(depthPasses(CompareFunc::LEqual, 0.5f, 0.5f));
  EXPECT_TRUE(depthPasses(CompareFunc::Equal, 0.5f, 0.5f));
  EXPECT_TRUE(depthPasses(CompareFunc::GEqual, 0.5f, 0.5f));
  EXPECT_FALSE(depthPasses(CompareFunc::Never, 0.0f, 1.0f));
  EXPECT_TRUE(depthPasses(CompareFunc::Always, 1.0f, 0.0f));
}

TEST(Layers, LayeredTargetReceivesEveryObjectInItsOwnLayer) {
  CommandList cl = scenes::build("layered_target", 256, 128);
  const auto r = renderList(cl, 2);
  ASSERT_EQ(r.images.size(), 1u);
  // Both halves of the presented image show a layer with rendered boxes (not just the clear colour).
  auto differs = [&](int x0, int x1) {
    size_t n = 0;
    for (int y = 0; y < 128; ++y)
      for (int x = x0; x < x1; ++x) n += r.images[0][(size_t(y) * 256 + x) * 4] != 51;
    return n;
  };
  EXPECT_GT(differs(0, 128), 1000u);
  EXPECT_GT(differs(128, 256), 1000u);
}

// The oracle's central promise: the same frame gives the same bytes for any thread count.
class ThreadInvariance : public ::testing::TestWithParam<std::string> {};

TEST_P(ThreadInvariance, SceneBytesAreIdenticalAtOneTwoAndSevenThreads) {
  const SceneInfo* info = scenes::find(GetParam());
  ASSERT_NE(info, nullptr);
  const CommandList cl = scenes::build(info->name, info->width, info->height);
  const auto one = renderList(cl, 1);
  const auto two = renderList(cl, 2);
  const auto seven = renderList(cl, 7);
  EXPECT_EQ(one.hashes, two.hashes);
  EXPECT_EQ(one.hashes, seven.hashes);
  EXPECT_EQ(one.stats.pixels_written, seven.stats.pixels_written);
  EXPECT_EQ(one.stats.fragments_shaded, seven.stats.fragments_shaded);
  // Repeated runs are identical too.
  EXPECT_EQ(one.hashes, renderList(cl, 1).hashes);
}

INSTANTIATE_TEST_SUITE_P(AllScenes, ThreadInvariance, ::testing::ValuesIn([] {
                           std::vector<std::string> names;
                           for (const auto& s : scenes::all()) names.emplace_back(s.name);
                           return names;
                         }()),
                         [](const auto& param) { return param.param; });
