// The LOD probe (raster/lod_probe.h) and the comparison of two LOD maps (verify/lod_compare.h is tested
// here too: it only needs the maps). Expected values are worked out by hand from GL 4.6 §8.14.1.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "base/error.h"
#include "raster/cpu_backend.h"
#include "raster/lod_probe.h"
#include "raster/sample.h"
#include "tests/raster/render_helpers.h"
#include "tools/scenes/scene_common.h"
#include "tools/scenes/scenes.h"
#include "verify/lod_compare.h"

namespace tessera {
namespace {

using scenes::Mesh;

// A 32x32 target; each quad covers [x0, x0 + 32) x [0, 32) in pixels with s, t running 0..1 over it, so
// one pixel step is 1/32 in s (and t): with a texture of `size` texels, rho = size / 32.
struct QuadSpec {
  uint32_t size;  // texture side
  float z;        // eye-space z (ortho near -1, far 1: larger z is nearer)
};

CommandList quadsFrame(std::initializer_list<QuadSpec> quads, bool depthTest, int width = 32) {
  CommandList cl;
  scenes::beginFrame(cl, width, 32, depthTest, {0, 0, 0, 1});
  cl.useProgram(cl.createProgram("textured"));
  scenes::setMatrix(cl, 0, scenes::ortho(0, width, 0, 32, -1, 1));
  scenes::setTexturedDefaults(cl);
  SamplerState tri;
  tri.minFilter = Filter::LinearMipmapLinear;
  cl.bindSampler(0, cl.createSampler(tri));
  if (depthTest) {
    DepthState d;
    d.test = true;
    cl.setDepthState(d);
  }
  for (const QuadSpec& q : quads) {
    Mesh m;
    m.quad({0, 0, q.z}, {32, 0, q.z}, {32, 32, q.z}, {0, 32, q.z}, {0, 0, 0, 0}, {1, 0, 0, 0}, {1, 1, 0, 0}, {0, 1, 0, 0});
    const uint32_t n = scenes::bindMesh(cl, m);
    cl.bindTexture(0, scenes::uploadTexture(cl, scenes::checker(q.size, q.size, 4, {255, 0, 0, 255}, {0, 0, 255, 255}), true));
    cl.drawIndexed(0, n);
  }
  return cl;
}

void expectEveryQuadPixel(const LodMap& m, uint32_t size, int32_t lambda8, double rho2) {
  for (int32_t y = 0; y < 32; ++y)
    for (int32_t x = 0; x < 32; ++x) {
      const LodPixel& px = m.at(x, y);
      ASSERT_EQ(px.count, 1) << x << "," << y;
      EXPECT_EQ(px.look[0].width, size);
      EXPECT_EQ(px.look[0].height, size);
      EXPECT_EQ(px.look[0].unit, 0);
      EXPECT_EQ(px.look[0].grad, 0);
      EXPECT_GT(px.look[0].levels, 0);
      EXPECT_EQ(px.look[0].lambda8, lambda8) << x << "," << y;
      EXPECT_EQ(px.look[0].rho2, rho2) << x << "," << y;
    }
}

TEST(LodProbe, SixtyFourTexelsOverThirtyTwoPixelsGiveRhoTwoAndLambdaOne) {
  // rho = 64 / 32 = 2, rho^2 = 4 (exact: s = (x + 1/2) / 32 at pixel centres), lambda = log2 2 = 1 = 256.
  const LodMap m = lodMap(quadsFrame({{64, 0.0f}}, false), 1);
  ASSERT_EQ(m.width, 32);
  ASSERT_EQ(m.height, 32);
  expectEveryQuadPixel(m, 64, 256, 4.0);
}

TEST(LodProbe, EightTexelsOverThirtyTwoPixelsMagnifyWithLambdaMinusTwo) {
  // rho = 8 / 32 = 1/4, rho^2 = 1/16, lambda = -2 = -512 (no clamp: minLod is -1000 by default).
  expectEveryQuadPixel(lodMap(quadsFrame({{8, 0.0f}}, false), 1), 8, -512, 1.0 / 16.0);
}

TEST(LodProbe, PixelsNoFragmentWroteHaveNoLookup) {
  const LodMap m = lodMap(quadsFrame({{64, 0.0f}}, false, 48), 1);
  ASSERT_EQ(m.width, 48);
  for (int32_t y = 0; y < 32; ++y)
    for (int32_t x = 32; x < 48; ++x) EXPECT_EQ(m.at(x, y).count, 0) << x << "," << y;
  EXPECT_EQ(m.at(31, 31).count, 1);
}

TEST(LodProbe, TheLastFragmentWrittenToAPixelGivesItsRecord) {
  // Without depth test the second quad (64 texels, lambda 1) overwrites the first (128 texels, lambda 2).
  expectEveryQuadPixel(lodMap(quadsFrame({{128, 0.0f}, {64, 0.0f}}, false), 1), 64, 256, 4.0);
}

TEST(LodProbe, AFragmentFailingTheDepthTestLeavesTheVisibleRecord) {
  // The near quad (z = 0.5, 64 texels) is drawn first; the far one (z = -0.5, 128 texels) is shaded
  // nowhere because every pixel fails LESS, so the record stays the near quad's lambda 1.
  expectEveryQuadPixel(lodMap(quadsFrame({{64, 0.5f}, {128, -0.5f}}, true), 1), 64, 256, 4.0);
}

TEST(LodProbe, AColourClearAfterADrawLeavesNoLookupBehind) {
  CommandList cl = quadsFrame({{64, 0.0f}}, false);
  cl.clearColor(0, {0, 0, 0, 1});
  const LodMap m = lodMap(cl, 2);
  for (const LodPixel& px : m.pixels) ASSERT_EQ(px.count, 0);
}

TEST(LodProbe, ProbingChangesNeitherTheImageNorTheCounters) {
  const CommandList list = scenes::build("city_block", 160, 120);
  const testing::Rendered plain = testing::renderList(list, 2);
  RenderOptions o;
  o.threads = 2;
  o.lodProbe = true;
  CpuBackend b(o);
  b.execute(list, "probed");
  const PresentedImage p = b.presented().at(0);
  EXPECT_EQ(imageSha256(*b.texture(p.texture), p.level, p.layer), plain.hashes.at(0));
  EXPECT_EQ(b.stats().quads_shaded, plain.stats.quads_shaded);
  EXPECT_EQ(b.stats().pixels_written, plain.stats.pixels_written);
  EXPECT_EQ(b.stats().fragments_depth_failed, plain.stats.fragments_depth_failed);
  EXPECT_NE(b.lodMap(p), nullptr);
}

TEST(LodProbe, RecordsAreTheSameAtOneTwoAndEightThreads) {
  const CommandList list = scenes::build("city_block", 160, 120);
  const LodMap m1 = lodMap(list, 1), m2 = lodMap(list, 2), m8 = lodMap(list, 8);
  uint64_t withLookup = 0;
  for (size_t i = 0; i < m1.pixels.size(); ++i) {
    withLookup += m1.pixels[i].count != 0;
    ASSERT_EQ(m1.pixels[i], m2.pixels[i]) << i;
    ASSERT_EQ(m1.pixels[i], m8.pixels[i]) << i;
  }
  EXPECT_GT(withLookup, 1000u);  // the facades are textured
}

TEST(LodProbe, TextureArrayLookupsAreRecordedAsTextureGradOnTheirArrayUnit) {
  // texture_array: texelFetch of the TAM on unit 0 (no LOD, not recorded), then textureGrad on an
  // array on units 1-3.
  const LodMap m = lodMap(scenes::build("texture_array", 256, 256), 2);
  uint64_t recorded = 0;
  for (const LodPixel& px : m.pixels) {
    if (px.count == 0) continue;
    ++recorded;
    ASSERT_EQ(px.count, 1);
    EXPECT_EQ(px.look[0].grad, 1);
    EXPECT_GE(px.look[0].unit, 1);
    EXPECT_LE(px.look[0].unit, 3);
  }
  EXPECT_GT(recorded, 1000u);
}

TEST(LodCompare, AFrameComparedWithItselfHasNoDifferences) {
  const LodMap m = lodMap(scenes::build("city_block", 160, 120), 2);
  const verify::LodComparison c = verify::compareLodMaps(m, m);
  EXPECT_EQ(c.differing, 0u);
  EXPECT_GT(c.pixelsWithLookups, 1000u);
  EXPECT_EQ(c.count[int(verify::LodDiff::Same)], uint64_t(160 * 120));
}

TEST(LodCompare, ATextureTwiceTheSizeDiffersByExactlyOneLevelAtItsPixels) {
  // Right half: 64 texels (lambda 1) in A, 128 texels (lambda 2) in B. Left 16 columns: no quad.
  const LodMap a = lodMap(quadsFrame({{64, 0.0f}}, false, 48), 1);
  const LodMap b = lodMap(quadsFrame({{128, 0.0f}}, false, 48), 1);
  const verify::LodComparison c = verify::compareLodMaps(a, b);
  EXPECT_EQ(c.differing, 32u * 32u);
  EXPECT_EQ(c.count[int(verify::LodDiff::TextureSize)], 32u * 32u);
  for (int32_t y = 0; y < 32; ++y)
    for (int32_t x = 0; x < 32; ++x) EXPECT_EQ(c.delta8[size_t(y) * 48 + size_t(x)], 256);
}

TEST(LodCompare, ALookupInOnlyOneFrameIsReportedAsSuch) {
  LodMap a{2, 1, std::vector<LodPixel>(2)}, b = a;
  a.pixels[0].count = 1;
  a.pixels[0].look[0] = LodLookup{64, 64, 1, 256, 0, 2, 0, 4.0};
  b.pixels[1] = a.pixels[0];
  const verify::LodComparison c = verify::compareLodMaps(a, b);
  EXPECT_EQ(c.reason[0], verify::LodDiff::OnlyInA);
  EXPECT_EQ(c.reason[1], verify::LodDiff::OnlyInB);
}

TEST(LodCompare, SameSizeDifferentLambdaIsALambdaDifferenceAndADifferentUnitIsNot) {
  LodMap a{2, 1, std::vector<LodPixel>(2)}, b = a;
  a.pixels[0].count = a.pixels[1].count = 1;
  a.pixels[0].look[0] = a.pixels[1].look[0] = LodLookup{64, 64, 1, 256, 0, 2, 0, 4.0};
  b.pixels = a.pixels;
  b.pixels[0].look[0].lambda8 = 300;
  b.pixels[1].look[0].unit = 3;
  const verify::LodComparison c = verify::compareLodMaps(a, b);
  EXPECT_EQ(c.reason[0], verify::LodDiff::Lambda);
  EXPECT_EQ(c.delta8[0], 44);
  EXPECT_EQ(c.reason[1], verify::LodDiff::Same);
  EXPECT_EQ(c.unitDiffers, 1u);
  EXPECT_EQ(c.maxAbsDelta8, 44);
}

TEST(LodCompare, MapsOfDifferentSizesAreAnErrorNamingBoth) {
  const LodMap a{2, 1, std::vector<LodPixel>(2)}, b{1, 1, std::vector<LodPixel>(1)};
  try {
    verify::compareLodMaps(a, b, "a.tframe", "b.tframe");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a.tframe is 2x1 but b.tframe is 1x1"), std::string::npos) << e.what();
  }
}

}  // namespace
TEST(LodProbe, AProbeBackendReusedOverFramesGivesTheMapsOfANewOne) {
  // lodMap(probe, list, out) reuses the backend's storage and out's pixels from frame to frame
  // (tab render probes every frame so); each map must still be the one a new backend records.
  const std::vector<CommandList> frames = {scenes::build("city_block", 160, 120), quadsFrame({{64, 0.0f}}, false),
                                           scenes::build("texture_array", 96, 64), scenes::build("city_block", 160, 120)};
  RenderOptions o;
  o.threads = 2;
  o.lodProbe = true;
  CpuBackend probe(o);
  LodMap out;
  for (size_t i = 0; i < frames.size(); ++i) {
    lodMap(probe, frames[i], out);
    const LodMap fresh = lodMap(frames[i], 2);
    EXPECT_EQ(out.width, fresh.width) << i;
    EXPECT_EQ(out.height, fresh.height) << i;
    EXPECT_TRUE(out.pixels == fresh.pixels) << "frame " << i;
  }
  EXPECT_THROW(lodMap(*std::make_unique<CpuBackend>(RenderOptions{1}), frames[0], out), Error);
}

}  // namespace tessera
