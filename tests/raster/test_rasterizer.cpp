// Rasterization rules of the oracle: fill convention, culling, clipping, layers, thread invariance.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>

#include "raster/fragops.h"
#include "raster/setup.h"
#include "raster/simd_targets.h"
#include "tests/raster/render_helpers.h"
#include "tools/scenes/builder.h"
#include "tools/scenes/scenes.h"

namespace tessera::scenes {
using tessera::testing::renderList;

namespace {

// A W x H RGBA8 frame drawn with flat_color, additive blend of 0.25 per hit, ortho in pixels unless
// another matrix is given.
CommandList additiveFrame(int w, int h, const Mesh& m, RasterState rs = {}, std::optional<glm::mat4> matrix = {}) {
  CommandList cl;
  RenderTarget t;
  t.color[0] = createTarget(cl, Format::RGBA8, w, h);
  cl.setRenderTarget(t);
  cl.setViewport({0, 0, w, h});
  cl.clearColor(0, {0, 0, 0, 0});
  const uint32_t n = bindMesh(cl, m);
  cl.useProgram(cl.createProgram("flat_color"));
  setMatrix(cl, 0, matrix ? *matrix : ortho(0, w, 0, h, -1, 1));
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

// clip_planes at 192 x 192, derived from tools/scenes/scene_clip_planes.cpp:
// - 96 primitives: the disc's 64 fan triangles and the floor's 16 quads = 32 triangles.
// - Disc (left viewport 96 x 192, ortho -1..1): rim vertex k is 0.9 (cos, sin)(2 pi k / 64); the
//   centre is inside all three planes (distances 0.55, 0.6, 0.5), so no disc triangle is trivially
//   outside. Rim vertex k is outside x <= 0.55 for k in [-9, 9] (cos > 0.611), outside y >= -0.6 for
//   k in [-24, -8] (sin < -2/3), outside 0.7 (x + y) <= 0.5 for k in [-1, 17]: k in [-24, 17], 42
//   vertices (the closest call, k = 18, is inside by 0.005). Only the 21 triangles with both rim
//   vertices in 18..39 are untouched: 43 disc triangles are clipped, none culled.
// - Floor (right viewport, perspective 75 deg, near 0.5, eye at the origin looking along
//   (0, -0.3, -1)): quad 0 spans z = 1 .. -1 and so crosses the near plane (view depth 0.5 at
//   z = -0.22): its 2 triangles are clipped; every other vertex is in front of the near plane, within
//   the far plane (depth <= 30 < 40) and inside the 16 w guard band (|x_ndc| <= 4.2): not clipped.
//   Quad 0's first triangle, (-2, z = 1), (2, 1), (2, -1), is the part x >= -2 z; after near clipping
//   it keeps z in [-1, -0.22], where x >= -2 z puts it at x_ndc = x / depth * cot(37.5 deg) / 0.5
//   >= 2.3: entirely right of the viewport, so it bins nothing and is culled (its twin x <= -2 z fills
//   the bottom of the view).
//   Far quads shrink below a pixel: the window rows of quad i's ends z = 1 - 2i and -1 - 2i are
//   9: 125.65..126.47, 12: 127.68..128.14, 14: 128.54..128.88, 15: 128.88..129.18; none of these
//   contains a pixel centre (k + 0.5, nearest miss 0.03 px), so their 8 triangles cover no row and
//   are culled. Quads 10, 11 and 13 (126.47..127.13, 127.13..127.68, 128.14..128.54) each contain one.
// So: 45 clipped, 1 + 8 = 9 culled.
TEST(Clipping, ClipPlanesAndTheNearPlaneClipAndCullTheDerivedPrimitives) {
  const auto r = renderList(scenes::build("clip_planes", 192, 192), 1);
  EXPECT_EQ(r.stats.primitives_assembled, 96u);
  EXPECT_EQ(r.stats.primitives_clipped, 45u);
  EXPECT_EQ(r.stats.primitives_culled, 9u);
}

// The left viewport maps pixel centre (px + 0.5, py + 0.5) to NDC x = (px + 0.5) / 48 - 1,
// y = (py + 0.5) / 96 - 1. A pixel whose centre is at least 2 px inside the disc and inside all three
// planes must show the disc's colour (blue >= 0.5 everywhere on it); one at least 2 px beyond the rim
// or outside any plane must keep the clear colour. Distances in pixels: plane 0 (0.55 - x) * 48,
// plane 1 (y + 0.6) * 96, plane 2 (0.5 - 0.7 x - 0.7 y) / (0.7 sqrt(1/48^2 + 1/96^2)); the rim is at
// NDC radius 0.9 (vertices) and at least 0.9 cos(pi / 64) between them, and one NDC unit is at least
// 48 px. The floor in the right viewport: rows below window y 28.6 show quad 0, the triangle pair cut
// by the near plane, whose colour there is R + G = 0.5 and B = 0.3 .. 0.356 (B runs from 0.7 at z = 1
// to 0.3 at z = -1, and the bottom row sees z = -0.72); rows from 131 up are above the farthest floor
// row (129.2) and stay clear.
TEST(Clipping, PixelsTwoPixelsInsideEveryPlaneAreDrawnAndTwoPixelsOutsideAnyPlaneAreNot) {
  const auto r = renderList(scenes::build("clip_planes", 192, 192), 2);
  const auto& img = r.images[0];
  auto px = [&](int x, int y, int c) { return int(img[(size_t(191 - y) * 192 + x) * 4 + c]); };
  auto isClear = [&](int x, int y) {
    return px(x, y, 0) == 0 && px(x, y, 1) == 0 && px(x, y, 2) == 0 && px(x, y, 3) == 255;
  };
  const double plane2Scale = 0.7 * std::sqrt(1.0 / (48.0 * 48.0) + 1.0 / (96.0 * 96.0));
  const double innerRim = 0.9 * std::cos(3.14159265358979323846 / 64.0);
  int drawn = 0, notDrawn = 0;
  int outsideOnly[3] = {0, 0, 0};  // pixels in the disc and inside the other planes, outside this one
  for (int y = 0; y < 192; ++y)
    for (int x = 0; x < 96; ++x) {
      const double nx = (x + 0.5) / 48.0 - 1.0, ny = (y + 0.5) / 96.0 - 1.0;
      const double d[3] = {(0.55 - nx) * 48.0, (ny + 0.6) * 96.0, (0.5 - 0.7 * nx - 0.7 * ny) / plane2Scale};
      const double radius = std::sqrt(nx * nx + ny * ny);
      const bool inDisc = (innerRim - radius) * 48.0 >= 2.0, outDisc = (radius - 0.9) * 48.0 >= 2.0;
      const bool inPlanes = d[0] >= 2.0 && d[1] >= 2.0 && d[2] >= 2.0;
      const bool outPlane = d[0] <= -2.0 || d[1] <= -2.0 || d[2] <= -2.0;
      if (inDisc && inPlanes) {
        ++drawn;
        ASSERT_GE(px(x, y, 2), 127) << "disc pixel " << x << "," << y << " missing";
        ASSERT_EQ(px(x, y, 3), 255) << x << "," << y;
      } else if (outDisc || outPlane) {
        ++notDrawn;
        ASSERT_TRUE(isClear(x, y)) << "pixel " << x << "," << y << " outside the disc or a clip plane was drawn";
        for (int k = 0; k < 3; ++k)
          if (inDisc && d[k] <= -2.0 && d[(k + 1) % 3] >= 2.0 && d[(k + 2) % 3] >= 2.0) ++outsideOnly[k];
      }
    }
  EXPECT_GT(drawn, 2000);
  EXPECT_GT(notDrawn, 2000);
  for (int k = 0; k < 3; ++k) EXPECT_GT(outsideOnly[k], 50) << "plane " << k << " cuts off a visible part of the disc";
  // Right viewport: the near-clipped floor quad fills the bottom rows; the sky above the floor is clear.
  for (int x = 96; x < 192; ++x) {
    for (int y = 0; y <= 26; ++y) {
      ASSERT_FALSE(isClear(x, y)) << "the near-clipped floor quad is missing at " << x << "," << y;
      ASSERT_GE(px(x, y, 0) + px(x, y, 1), 126) << x << "," << y;
      ASSERT_LE(px(x, y, 0) + px(x, y, 1), 129) << x << "," << y;
      ASSERT_GE(px(x, y, 2), 76) << x << "," << y;
      ASSERT_LE(px(x, y, 2), 92) << x << "," << y;
    }
    for (int y = 131; y < 192; ++y) ASSERT_TRUE(isClear(x, y)) << "sky pixel " << x << "," << y << " was drawn";
  }
}

// w = 0 passes every clip plane only at the clip-space origin (x = y = z = w = 0), where the vertex has
// no window position: GL leaves such a primitive undefined, and the oracle drops it unclipped
// (raster/window_simd.h, kVertexNoWindow). The matrix maps (x, y, 0) to clip (x, y, 0, x + y), so the
// vertex at the object origin lands on the clip origin and the other two at NDC (1, 0) and (0, 1).
TEST(Clipping, AnUnclippedTriangleWithAVertexAtTheClipOriginIsCulled) {
  Mesh m;
  m.triangle(v(0.0f, 0.0f), v(1.0f, 0.0f), v(0.0f, 1.0f));
  glm::mat4 toOrigin(0.0f);  // column-major: column c is the image of axis c
  toOrigin[0] = {1.0f, 0.0f, 0.0f, 1.0f};
  toOrigin[1] = {0.0f, 1.0f, 0.0f, 1.0f};
  const CommandList cl = additiveFrame(16, 16, m, {}, toOrigin);
  const tessera::testing::SimdTargetGuard guard;  // the best target again, however the test ends
  for (const std::string& target : simd::availableTargets()) {  // the kernel's records and the reference's
    simd::forceTarget(target);
    const auto r = renderList(cl, 1);
    EXPECT_EQ(r.stats.primitives_assembled, 1u) << target;
    EXPECT_EQ(r.stats.primitives_clipped, 0u) << target;
    EXPECT_EQ(r.stats.primitives_culled, 1u) << target;
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) ASSERT_EQ(red(r.images[0], 16, 16, x, y), 0) << target << ": " << x << "," << y;
  }
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

namespace {
// layered_target (tools/scenes/scene_layered_target.cpp): box i (i = 0..3, colour a_i = (80 + 50 i,
// 220 - 40 i, 120 + 30 (i & 1)) checkered with (40, 40, 40)) is recorded to layer i / 2 of the 128 x
// 128 atlas, displaced to x' = 0.5 x - 0.5 w (even i: left half) or + 0.5 w (odd i: right half), and
// clipped on its undisplaced position to the screen, so it lands in atlas columns [0, 64) or
// [64, 128) of its layer. Pass 2 shows layer 0 in presented columns 0..127 and layer 1 in 128..255,
// one texel per pixel (NEAREST, texel centres on pixel centres): object i's region is presented
// columns [64 i, 64 i + 64). Filtering only mixes a_i with the dark grey, so every pixel an object
// covers is (40, 40, 40) + alpha (a_i - (40, 40, 40)) up to rounding; the clear colour is
// (0.2, 0.2, 0.25) = (51, 51, 64).
constexpr int kLayeredClear[3] = {51, 51, 64};
std::array<int, 3> boxColour(int i) { return {80 + 50 * i, 220 - 40 * i, 120 + 30 * (i & 1)}; }

// On object i's colour line (40, 40, 40) + alpha (a_i - (40, 40, 40)) with alpha >= minAlpha, within
// 4 LSB per channel. With minAlpha = 0.25 only that object can produce the pixel (the four lines are
// far apart there; near the grey end they meet).
bool fitsObject(const uint8_t* p, int i, double minAlpha) {
  const auto a = boxColour(i);
  double num = 0, den = 0;
  for (int c = 0; c < 3; ++c) num += double(p[c] - 40) * (a[c] - 40), den += double(a[c] - 40) * (a[c] - 40);
  const double alpha = num / den;
  if (alpha < minAlpha) return false;
  for (int c = 0; c < 3; ++c)
    if (std::fabs(double(p[c]) - (40.0 + alpha * (a[c] - 40))) > 4.0) return false;
  return true;
}
bool isLayeredClear(const uint8_t* p) {
  return p[0] == kLayeredClear[0] && p[1] == kLayeredClear[1] && p[2] == kLayeredClear[2] && p[3] == 255;
}

// The presented-image rectangle (columns, GL rows; inclusive) that object i can reach: its box's 8
// corners through the scene's MVP, clipped to NDC [-1, 1] as its clip distances do, displaced, plus
// 1 px. The projected box lies inside the hull of its projected corners.
std::array<int, 4> objectBounds(int i) {
  const glm::vec3 centres[4] = {{-0.6f, -0.3f, 0}, {0.5f, 0.4f, -0.5f}, {0.1f, 0.0f, 0.6f}, {-0.2f, 0.6f, -1.0f}};
  const glm::mat4 mvp = mul(perspective(60.0, 1.0, 0.1, 20.0), lookAt({1.2f, 1.5f, 3.0f}, {0, 0, 0}, {0, 1, 0}));
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  for (int k = 0; k < 8; ++k) {
    const double p[4] = {centres[i].x + ((k & 1) ? 0.45 : -0.45), centres[i].y + ((k & 2) ? 0.45 : -0.45),
                         centres[i].z + ((k & 4) ? 0.45 : -0.45), 1.0};
    double c[4] = {0, 0, 0, 0};
    for (int row = 0; row < 4; ++row)
      for (int col = 0; col < 4; ++col) c[row] += double(mvp[col][row]) * p[col];
    EXPECT_GT(c[3], 0.0) << "object " << i << " corner " << k << " behind the eye";
    const double nx = std::clamp(c[0] / c[3], -1.0, 1.0), ny = std::clamp(c[1] / c[3], -1.0, 1.0);
    x0 = std::min(x0, nx), x1 = std::max(x1, nx), y0 = std::min(y0, ny), y1 = std::max(y1, ny);
  }
  const double shift = (i & 1) ? 0.5 : -0.5;
  auto col = [&](double nx) { return (0.5 * nx + shift + 1.0) * 64.0 + (i / 2) * 128.0; };
  auto row = [&](double ny) { return (ny + 1.0) * 64.0; };
  return {int(std::floor(col(x0))) - 1, int(std::ceil(col(x1))) + 1, int(std::floor(row(y0))) - 1,
          int(std::ceil(row(y1))) + 1};
}
}  // namespace

TEST(Layers, EveryObjectOfTheLayeredTargetLandsInItsOwnLayerAndHalfAndNowhereElse) {
  const auto r = renderList(scenes::build("layered_target", 256, 128), 2);
  ASSERT_EQ(r.images.size(), 1u);
  const auto& img = r.images[0];
  std::array<std::array<int, 4>, 4> bounds;
  for (int i = 0; i < 4; ++i) {
    bounds[size_t(i)] = objectBounds(i);
    // The derivation itself: each object's reach stays inside its own 64-column region.
    EXPECT_GE(bounds[size_t(i)][0], 64 * i - 1) << "object " << i;
    EXPECT_LE(bounds[size_t(i)][1], 64 * i + 64) << "object " << i;
  }
  int fits[4] = {0, 0, 0, 0};
  for (int yTop = 0; yTop < 128; ++yTop)
    for (int x = 0; x < 256; ++x) {
      const int y = 127 - yTop;  // GL row
      const uint8_t* p = &img[(size_t(yTop) * 256 + x) * 4];
      const int region = x / 64;
      const auto& b = bounds[size_t(region)];
      const bool reach = x >= b[0] && x <= b[1] && y >= b[2] && y <= b[3];
      if (!reach) {
        ASSERT_TRUE(isLayeredClear(p)) << "pixel " << x << "," << y << " outside object " << region
                                       << "'s reach is not the clear colour";
        continue;
      }
      for (int k = 0; k < 4; ++k) {
        if (k == region) continue;
        ASSERT_FALSE(fitsObject(p, k, 0.25))
            << "object " << k << " appears at " << x << "," << y << ", in object " << region << "'s region";
      }
      fits[region] += fitsObject(p, region, 0.25);
      ASSERT_TRUE(fitsObject(p, region, 0.0) || isLayeredClear(p))
          << "pixel " << x << "," << y << " = " << int(p[0]) << "," << int(p[1]) << "," << int(p[2])
          << " is neither object " << region << "'s colour (with its dark cells) nor the clear colour";
    }
  // Each box covers some 40 x 40 px, half of its checker cells in its own colour.
  for (int i = 0; i < 4; ++i) EXPECT_GT(fits[i], 300) << "object " << i << " is missing from its region";
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

}  // namespace tessera::scenes
