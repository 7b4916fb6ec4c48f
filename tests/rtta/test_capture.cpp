// RTTA capture and compositing on the oracle (rtta/rtta_record.h), on hand-built box scenes.
#include <gtest/gtest.h>

#include <cstring>

#include "base/sha256.h"
#include "batching/batcher.h"
#include "mta/camera.h"
#include "raster/counters.h"
#include "raster/cpu_backend.h"
#include "rtta/rtta_record.h"
#include "rtta/shift_explain.h"
#include "tests/rtta/box_scene.h"

namespace tessera::rtta {
namespace {

constexpr uint32_t kCaptureW = 128, kCaptureH = 96;

RttaView view() {
  mta::Camera c;
  c.eye = {1.5, 2.5, 7.0};
  c.target = {0.5, 0.0, 0.0};
  c.nearPlane = 0.5;
  c.farPlane = 40.0;
  RttaView v;
  v.mvp = mta::viewProjection(c, kCaptureW, kCaptureH);
  v.eye = c.eye;
  v.width = kCaptureW;
  v.height = kCaptureH;
  return v;
}

struct Rendered {
  RttaFrame frame;
  std::unique_ptr<CpuBackend> be;
};
Rendered run(const RttaScene& s, const RttaOptions& o, int threads = 2) {
  Rendered r{recordRttaFrame(s, view(), o), std::make_unique<CpuBackend>(RenderOptions{.threads = threads})};
  r.be->execute(r.frame.list);
  return r;
}

const uint8_t* pixel(const Rendered& r, ResourceId tex, uint32_t layer, int x, int y) {
  return r.be->texture(tex)->texel(0, layer, uint32_t(x), uint32_t(y));
}

// A region equals its object rendered alone, shifted by whole pixels, except where the float
// displacement rounds a vertex to another sub-pixel or clipping cuts a triangle (shift_explain.h): every
// differing texel must lie where such a triangle may reach.
TEST(RttaCapture, EachRegionEqualsItsObjectRenderedAloneShiftedWhereNoVertexRounds) {
  const auto specs = testing::fiveBoxes();
  const RttaScene scene = testing::boxScene(specs, 4);
  const Rendered atlas = run(scene, {.mode = Mode::Rtta, .captureOnly = true});
  const ShiftExplanation why =
      explainShift(scene, atlas.frame.records, view().mvp, {0, 0, int(kCaptureW), int(kCaptureH)}, atlas.frame.atlas);
  int compared = 0, covered = 0, differing = 0, unexplained = 0, exactZone = 0;
  for (uint32_t k = 0; k < specs.size(); ++k) {
    const Record& r = atlas.frame.records[k];
    ASSERT_TRUE(r.visible()) << k;
    const Rendered alone = run(testing::boxScene({specs[k]}, 4), {.mode = Mode::Std});
    for (int y = r.viewport.y0; y < r.viewport.y1; ++y)
      for (int x = r.viewport.x0; x < r.viewport.x1; ++x) {
        const int ax = x + r.atlas.x0 - r.viewport.x0, ay = y + r.atlas.y0 - r.viewport.y0;
        const uint8_t* a = pixel(atlas, atlas.frame.captureColor, uint32_t(r.layer), ax, ay);
        const bool onScreen = x >= 0 && y >= 0 && x < int(kCaptureW) && y < int(kCaptureH);
        if (!onScreen) {
          EXPECT_EQ(a[3], 0) << "a border texel off the screen was written";
          continue;
        }
        ++compared;
        float depth = 1.0f;
        std::memcpy(&depth, pixel(alone, alone.frame.screenDepth, 0, x, y), 4);
        const uint8_t* s = pixel(alone, alone.frame.screen, 0, x, y);
        float z[2];
        std::memcpy(z, pixel(atlas, atlas.frame.captureDepth, uint32_t(r.layer), ax, ay), 8);
        const bool same = depth < 1.0f ? std::memcmp(a, s, 4) == 0 && z[0] == depth && z[1] == 1.0f : a[3] == 0 && z[1] == 0.0f;
        covered += depth < 1.0f;
        const bool explained = why.mask[size_t(y) * kCaptureW + size_t(x)] != 0;
        exactZone += !explained;
        if (!same) ++differing, unexplained += !explained;
        EXPECT_TRUE(same || explained) << "object " << k << " pixel " << x << "," << y << ": atlas " << int(a[0]) << ","
                                       << int(a[1]) << "," << int(a[2]) << "," << int(a[3]) << " alone " << int(s[0]) << ","
                                       << int(s[1]) << "," << int(s[2]) << "," << int(s[3]);
      }
  }
  EXPECT_EQ(unexplained, 0);
  EXPECT_GT(covered, 2000);
  EXPECT_GT(exactZone, 1000) << "too few pixels where the comparison is exact to mean anything";
  std::printf("[ rtta ] capture vs alone: %d pixels compared, %d covered, %d differ (all explained), %d in the exact zone; "
              "triangles %llu, rounded %llu, clipped %llu\n",
              compared, covered, differing, exactZone, (unsigned long long)why.triangles, (unsigned long long)why.rounded,
              (unsigned long long)why.clipped);
}

TEST(RttaCapture, NoFragmentLeavesItsRegionAndBordersKeepTheClearAlpha) {
  const RttaScene scene = testing::boxScene(testing::fiveBoxes(), 4);
  const Rendered atlas = run(scene, {.mode = Mode::Rtta, .params = {.border = 2}, .captureOnly = true});
  const AtlasSize ta = atlas.frame.atlas;
  int written = 0;
  for (int32_t l = 0; l < ta.layers; ++l)
    for (int y = 0; y < ta.height; ++y)
      for (int x = 0; x < ta.width; ++x) {
        const uint8_t* a = pixel(atlas, atlas.frame.captureColor, uint32_t(l), x, y);
        if (a[3] == 0) continue;
        ++written;
        bool inside = false;
        for (const Record& r : atlas.frame.records) {
          if (r.layer != l) continue;
          // Inside the region but off its border: the inner rectangle shifted into the atlas.
          const int ix = x - (r.atlas.x0 - r.viewport.x0), iy = y - (r.atlas.y0 - r.viewport.y0);
          inside = inside || r.inner.contains(ix, iy);
        }
        EXPECT_TRUE(inside) << "texel " << x << "," << y << " of layer " << l << " is outside every region's interior";
      }
  EXPECT_GT(written, 2000);
}

uint64_t differingPixels(const Rendered& a, ResourceId ta, const Rendered& b, ResourceId tb) {
  uint64_t n = 0;
  for (uint32_t y = 0; y < kCaptureH; ++y)
    for (uint32_t x = 0; x < kCaptureW; ++x)
      n += std::memcmp(pixel(a, ta, 0, int(x), int(y)), pixel(b, tb, 0, int(x), int(y)), 4) != 0;
  return n;
}

TEST(RttaComposite, DepthSpritesReproduceThePlainRendering) {
  const RttaScene scene = testing::boxScene(testing::fiveBoxes(), 4);
  const Rendered std_ = run(scene, {.mode = Mode::Std});
  const Rendered rtta = run(scene, {.mode = Mode::Rtta});
  const Rendered rtt = run(scene, {.mode = Mode::Rtt});
  // RTT layers are the objects rendered alone, and no two boxes touch (no depth ties between objects):
  // its composite is the plain rendering, every pixel.
  EXPECT_EQ(differingPixels(std_, std_.frame.screen, rtt, rtt.frame.screen), 0u);
  // RTTA's composite differs only where its capture may (shift_explain.h).
  const ShiftExplanation why =
      explainShift(scene, rtta.frame.records, view().mvp, {0, 0, int(kCaptureW), int(kCaptureH)}, rtta.frame.atlas);
  uint64_t differing = 0, unexplained = 0;
  for (uint32_t y = 0; y < kCaptureH; ++y)
    for (uint32_t x = 0; x < kCaptureW; ++x)
      if (std::memcmp(pixel(std_, std_.frame.screen, 0, int(x), int(y)), pixel(rtta, rtta.frame.screen, 0, int(x), int(y)), 4)) {
        ++differing;
        unexplained += why.mask[size_t(y) * kCaptureW + x] == 0;
      }
  EXPECT_EQ(unexplained, 0u) << differing << " differing pixels";
  std::printf("[ rtta ] depth composite vs STD: %llu of %u pixels differ, all where a displaced vertex rounds or clipping cuts\n",
              (unsigned long long)differing, kCaptureW * kCaptureH);
}

TEST(RttaComposite, TransparentAndGhostedDifferFromThePlainRenderingOnlyWhereObjectsAre) {
  const RttaScene scene = testing::boxScene(testing::fiveBoxes(), 4);
  const Rendered std_ = run(scene, {.mode = Mode::Std});
  for (Composite c : {Composite::Transparent, Composite::Ghosted}) {
    const Rendered comp = run(scene, {.mode = Mode::Rtta, .composite = c});
    uint64_t background = 0;
    for (uint32_t y = 0; y < kCaptureH; ++y)
      for (uint32_t x = 0; x < kCaptureW; ++x) {
        float z;
        std::memcpy(&z, pixel(std_, std_.frame.screenDepth, 0, int(x), int(y)), 4);
        if (z < 1.0f) continue;
        ++background;
        EXPECT_EQ(std::memcmp(pixel(std_, std_.frame.screen, 0, int(x), int(y)), pixel(comp, comp.frame.screen, 0, int(x), int(y)), 4), 0);
      }
    EXPECT_GT(background, 1000u);
    EXPECT_GT(differingPixels(std_, std_.frame.screen, comp, comp.frame.screen), 500u) << compositeName(c);
  }
}

TEST(RttaFrames, BytesAreIdenticalAtOneTwoAndSevenThreads) {
  const RttaScene scene = testing::boxScene(testing::fiveBoxes(), 4);
  std::string first;
  for (int threads : {1, 2, 7}) {
    const Rendered r = run(scene, {.mode = Mode::Rtta, .composite = Composite::Ghosted}, threads);
    const TextureData* t = r.be->texture(r.frame.screen);
    const TextureData* a = r.be->texture(r.frame.captureDepth);
    Sha256 h;
    h.update(t->levels[0]);
    h.update(a->levels[0]);
    const auto digest = h.finish();
    const std::string hex(digest.begin(), digest.end());
    if (first.empty()) first = hex;
    EXPECT_EQ(hex, first) << threads << " threads";
  }
}

TEST(RttaCapture, TabTexturingCapturesTheSameAtlasInOneDraw) {
  RttaScene scene = testing::boxScene(testing::fiveBoxes(), 4);
  const Rendered bind = run(scene, {.mode = Mode::Rtta, .captureOnly = true});
  batching::runAlgorithm1(scene.tab, batching::TabParams{});
  refreshTamIndices(scene);
  const Rendered tab = run(scene, {.mode = Mode::Rtta, .texturing = Texturing::Tab, .captureOnly = true});
  auto draws = [](const CommandList& cl) {
    int n = 0;
    for (const Command& c : cl.commands()) n += std::holds_alternative<Draw>(c);
    return n;
  };
  EXPECT_EQ(draws(bind.frame.list), 4) << "one draw per texture";
  EXPECT_EQ(draws(tab.frame.list), 1) << "four 32x32 textures share one array: one geometry batch";
  // The same texels: one array layer per texture, the same mip chains, opaque materials in the TAM.
  EXPECT_EQ(bind.be->texture(bind.frame.captureColor)->levels[0], tab.be->texture(tab.frame.captureColor)->levels[0]);
  EXPECT_EQ(bind.be->texture(bind.frame.captureDepth)->levels[0], tab.be->texture(tab.frame.captureDepth)->levels[0]);
}

TEST(RttaFrames, RttTakesOnePassPerObjectAndRttaOne) {
  const RttaScene scene = testing::boxScene(testing::fiveBoxes(), 4);
  const RttaFrame rtt = recordRttaFrame(scene, view(), {.mode = Mode::Rtt});
  const RttaFrame rtta = recordRttaFrame(scene, view(), {.mode = Mode::Rtta});
  auto targets = [](const CommandList& cl) {
    int n = 0;
    for (const Command& c : cl.commands()) n += std::holds_alternative<SetRenderTarget>(c);
    return n;
  };
  // Texture binds as a state-tracking renderer issues them, none while resources are created: STD binds
  // each of the 4 textures once (meshes are in texture order); RTTA the same 4 in its capture, the record
  // buffer, and the atlas colour and depth for the composite.
  const RttaFrame stdFrame = recordRttaFrame(scene, view(), {.mode = Mode::Std});
  EXPECT_EQ(countCommands(stdFrame.list).texture_binds, 4u);
  EXPECT_EQ(countCommands(rtta.list).texture_binds, 4u + 1u + 2u);
  EXPECT_EQ(targets(rtt.list), 5 + 1);   // one per object, then the screen
  EXPECT_EQ(targets(rtta.list), 1 + 1);  // the atlas, then the screen
  EXPECT_EQ(rtt.targetBytes, uint64_t(kCaptureW) * kCaptureH * 5 * (4 + 8 + 4));
  EXPECT_EQ(rtta.atlas.width, 256);      // smallest power of two >= 128 + 2
  EXPECT_EQ(rtta.targetBytes, uint64_t(256) * 128 * uint64_t(rtta.atlas.layers) * (4 + 8 + 4));
}

}  // namespace
}  // namespace tessera::rtta
