// Hierarchical Z (raster/rast.cpp, TriangleRasterizer::occluded): an 8x8 block whose covered pixels
// must all fail a LESS or LEQUAL depth test, by the triangle's least vertex depth against the block's
// largest stored depth, is not walked. The bytes and every counter must be those of the "reference"
// SIMD target, which walks every block; and the frames must actually skip blocks (StageTimes).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "raster/simd_targets.h"
#include "tests/raster/render_helpers.h"
#include "tools/scenes/builder.h"

namespace tessera::scenes {
using tessera::testing::expectSameCounters;
using tessera::testing::Rendered;
using tessera::testing::renderList;
using tessera::testing::SimdTargetGuard;

namespace {

// An odd size: two by two tiles, the right and top ones partial, so blocks reach past the last column
// and row (their largest stored depth must come from the pixels inside the target only).
constexpr int kOddWidth = 97, kOddHeight = 79;

// One draw of the frame: a rectangle in NDC, its depth running from zLeft to zRight (NDC) across it.
struct Layer {
  float x0, y0, x1, y1;
  float zLeft, zRight;
  CompareFunc func = CompareFunc::Less;
  bool write = true;
  bool textured = false;  // textured with an alpha cutoff, which may discard: the immediate walk
  bool clearDepthBefore = false;
};

// Each layer in its own colour (flat) or with its own texture (textured, alpha cutoff 0.5 on a
// checker whose light cells are opaque and dark cells transparent). The depth target starts cleared to
// 1, or with `depth` (kOddWidth x kOddHeight floats, row 0 first) uploaded.
CommandList frame(const std::vector<Layer>& layers, const std::vector<float>& depth = {}) {
  CommandList cl;
  RenderTarget t;
  t.color[0] = createTarget(cl, Format::RGBA8, kOddWidth, kOddHeight);
  t.depth = createTarget(cl, Format::D32F, kOddWidth, kOddHeight);
  cl.setRenderTarget(t);
  cl.setViewport({0, 0, kOddWidth, kOddHeight});
  cl.clearColor(0, {0.1f, 0.2f, 0.3f, 1});
  if (depth.empty()) {
    cl.clearDepth(1.0f);
  } else {
    std::vector<uint8_t> bytes(depth.size() * sizeof(float));
    std::memcpy(bytes.data(), depth.data(), bytes.size());
    cl.uploadTexture(t.depth, 0, 0, bytes);
  }
  Mesh m;
  for (const Layer& l : layers)
    m.quad({l.x0, l.y0, l.zLeft}, {l.x1, l.y0, l.zRight}, {l.x1, l.y1, l.zRight}, {l.x0, l.y1, l.zLeft}, {0, 0, 0, 0},
           {3, 0, 0, 0}, {3, 2, 0, 0}, {0, 2, 0, 0});
  bindMesh(cl, m);
  const ResourceId flat = cl.createProgram("flat_color"), textured = cl.createProgram("textured");
  const ResourceId tex =
      uploadTexture(cl, checker(16, 16, 4, {230, 120, 40, 255}, {20, 60, 200, 0}), true);
  for (size_t i = 0; i < layers.size(); ++i) {
    const Layer& l = layers[i];
    if (l.clearDepthBefore) cl.clearDepth(1.0f);
    DepthState d;
    d.test = true;
    d.func = l.func;
    d.write = l.write;
    cl.setDepthState(d);
    if (l.textured) {
      cl.useProgram(textured);
      setMatrix(cl, 0, glm::mat4(1.0f));
      setTexturedDefaults(cl);
      setVec4(cl, 8, {0, 0.5f, 0, 0});
      cl.bindTexture(0, tex);
    } else {
      cl.useProgram(flat);
      setMatrix(cl, 0, glm::mat4(1.0f));
      setVec4(cl, 4, {float(i % 3) / 2, float(i % 5) / 4, float(i % 7) / 6, 1});
    }
    cl.drawIndexed(6 * uint32_t(i), 6);
  }
  return cl;
}

// The frame on the best SIMD target at 1, 2 and 7 threads gives the reference target's bytes and
// counters; returns the blocks the best target skipped (the reference target skips none).
uint64_t expectReferenceBytes(const std::vector<Layer>& layers, const std::string& what,
                              const std::vector<float>& depth = {}) {
  const SimdTargetGuard guard;
  const CommandList cl = frame(layers, depth);
  simd::forceTarget("reference");
  const Rendered reference = renderList(cl, 1);
  EXPECT_EQ(reference.times.hizBlocksSkipped, 0u) << what << ": the reference target walks every block";
  simd::forceTarget("best");
  EXPECT_NE(simd::activeTarget(), "reference") << "this machine has no SIMD target: nothing to compare";
  uint64_t skipped = 0;
  for (int threads : {1, 2, 7}) {
    const Rendered r = renderList(cl, threads);
    EXPECT_EQ(r.hashes, reference.hashes) << what << ", " << threads << " threads";
    expectSameCounters(r.stats, reference.stats, what + ", " + std::to_string(threads) + " threads");
    if (threads == 1) skipped = r.times.hizBlocksSkipped;
    EXPECT_EQ(r.times.hizBlocksSkipped, skipped) << what << ": the skipped blocks depend on the thread count";
  }
  return skipped;
}

constexpr float kNear = -0.5f;  // NDC depth of the occluder (window 0.25)

}  // namespace

TEST(HierarchicalZ, LayersBehindAnOccluderAreSkippedWithTheReferenceBytesAndCounters) {
  const std::vector<Layer> layers = {
      {-1, -1, 1, 1, kNear, kNear},
      {-1, -1, 1, 1, 0.2f, 0.6f},                    // behind: skipped
      {-0.8f, -0.9f, 0.9f, 0.7f, -0.45f, 0.9f},      // just behind on its left: skipped too
      {-1, -1, 0.3f, 1, 0.1f, 0.1f, CompareFunc::LEqual},
      {-1, -1, 1, 1, -0.9f, 0.9f},                   // crosses the occluder: walked where in front
      {-1, -1, 1, 1, 0.5f, 0.5f, CompareFunc::Less, true, true},  // textured, may discard: skipped too
  };
  EXPECT_GT(expectReferenceBytes(layers, "layers behind"), 20u);
}

TEST(HierarchicalZ, ACoplanarLayerPassesUnderLEqualAndFailsUnderLess) {
  // At equal depth LEQUAL passes: the block's largest depth equals the layer's least, which LEQUAL
  // must not skip. The LESS layer after it at the same depth fails everywhere and is skipped.
  const std::vector<Layer> layers = {
      {-1, -1, 1, 1, kNear, kNear},
      {-1, -1, 1, 1, kNear, kNear, CompareFunc::LEqual},
      {-1, -1, 1, 1, kNear, kNear, CompareFunc::Less},
  };
  EXPECT_GT(expectReferenceBytes(layers, "coplanar"), 20u);
  // The LEQUAL layer's colour (layer 1) covers the target.
  const Rendered r = renderList(frame(layers), 2);
  ASSERT_EQ(r.images.size(), 1u);
  const size_t centre = (size_t(kOddHeight / 2) * kOddWidth + kOddWidth / 2) * 4;
  EXPECT_EQ(int(r.images[0][centre + 0]), 128);  // (1 % 3) / 2 = 0.5
  EXPECT_EQ(int(r.images[0][centre + 1]), 64);   // (1 % 5) / 4 = 0.25
}

TEST(HierarchicalZ, ASlopedCoplanarLayerIsWalkedAndItsTiesFollowTheFunction) {
  // A sloped layer drawn again on the same plane: its least vertex depth is below every block's
  // largest, so no block is skipped and every pixel's test is a tie, decided per quad by the walk (the
  // SIMD comparison of rast.cpp's depthPassMask, the scalar one under "reference"). LESS fails
  // everywhere, LEQUAL passes everywhere.
  for (const CompareFunc f : {CompareFunc::Less, CompareFunc::LEqual}) {
    const std::vector<Layer> layers = {
        {-1, -1, 1, 1, -0.6f, 0.7f},
        {-1, -1, 1, 1, -0.6f, 0.7f, f},
    };
    expectReferenceBytes(layers, f == CompareFunc::Less ? "sloped coplanar, LESS" : "sloped coplanar, LEQUAL");
    const Rendered r = renderList(frame(layers), 2);
    ASSERT_EQ(r.images.size(), 1u);
    const size_t centre = (size_t(kOddHeight / 2) * kOddWidth + kOddWidth / 2) * 4;
    // Layer 0 is (0, 0, 0), layer 1 (0.5, 0.25, 1/6): the second layer shows under LEQUAL only.
    EXPECT_EQ(int(r.images[0][centre + 0]), f == CompareFunc::LEqual ? 128 : 0);
    EXPECT_EQ(r.stats.fragments_depth_failed, f == CompareFunc::Less ? uint64_t(kOddWidth) * kOddHeight : 0u);
  }
}

TEST(HierarchicalZ, DepthThatOtherFunctionsOrAClearRaiseIsSeenByTheNextLessTest) {
  // A block's largest depth is remembered; a draw that writes farther depths (ALWAYS, GREATER) or a
  // depth clear must make it recomputed, or the next LESS layer would be skipped where it is visible.
  EXPECT_GT(expectReferenceBytes(
                {
                    {-1, -1, 1, 1, kNear, kNear},
                    {-1, -1, 1, 1, 0.2f, 0.2f},  // skipped: the bound is now known
                    {-1, -1, 0, 1, 0.8f, 0.8f, CompareFunc::Always},  // the left half now far
                    {-1, -1, 1, 1, 0.0f, 0.0f},  // visible on the left, skipped on the right
                    {-0.2f, -1, 1, 1, 0.9f, 0.9f, CompareFunc::Greater},  // farther on the right
                    {-1, -1, 1, 1, 0.3f, 0.3f},  // visible where GREATER wrote 0.9
                },
                "ALWAYS and GREATER writes"),
            20u);
  EXPECT_GT(expectReferenceBytes(
                {
                    {-1, -1, 1, 1, kNear, kNear},
                    {-1, -1, 1, 1, 0.2f, 0.2f},                            // skipped
                    {-1, -1, 1, 1, 0.4f, 0.4f, CompareFunc::Less, true, false, true},  // after a clear: visible
                    {-1, -1, 1, 1, 0.6f, 0.6f},                            // behind it: skipped
                },
                "a depth clear"),
            20u);
}

TEST(HierarchicalZ, ALayerThatDoesNotWriteDepthLeavesTheBoundValid) {
  EXPECT_GT(expectReferenceBytes(
                {
                    {-1, -1, 1, 1, 0.0f, 0.0f},
                    {-1, -1, 1, 1, kNear, kNear, CompareFunc::Less, false},  // in front, no depth write
                    {-1, -1, 1, 1, -0.2f, -0.2f},  // in front of the written depth: visible
                    {-1, -1, 1, 1, 0.5f, 0.5f},    // skipped
                },
                "no depth write"),
            20u);
}

TEST(HierarchicalZ, StoredNaNDepthsFailEveryTestAndDoNotHideTheRestOfTheBlock) {
  // A depth target uploaded with NaNs among 0.9 and 0.35 in 4x4 cells: a NaN fails LESS and LEQUAL
  // whatever arrives, so a block's bound is its largest other depth. A bound that let a NaN replace
  // the larger depths seen before it would hide the layer at 0.5 where 0.9 is stored.
  std::vector<float> depth(size_t(kOddWidth) * kOddHeight);
  for (int y = 0; y < kOddHeight; ++y)
    for (int x = 0; x < kOddWidth; ++x)
      depth[size_t(y) * kOddWidth + size_t(x)] = (x * 7 + y * 3) % 5 == 0 ? std::numeric_limits<float>::quiet_NaN()
                                          : (x / 4 + y / 4) % 2 ? 0.9f : 0.35f;
  EXPECT_GT(expectReferenceBytes(
                {
                    {-1, -1, 1, 1, 0.0f, 0.0f},                          // window 0.5: passes at 0.9 only
                    {-1, -1, 1, 1, 0.0f, 0.0f, CompareFunc::LEqual},     // equal where written
                    {-1, -1, 1, 1, 0.2f, 0.2f, CompareFunc::LEqual},     // window 0.6: skipped
                },
                "stored NaNs", depth),
            20u);
}

}  // namespace tessera::scenes
