// Flushes for memory (raster/cpu_backend.cpp, kSceneTriangles; RenderOptions::sceneTriangles): a frame
// is rasterized whenever its scene holds that many set-up triangles, in as many scenes as it needs, and
// a draw cut between scenes continues in the next one with a copy of its state. Nothing may show where
// the frame was cut: rasterized after every draw, every built-in scene gives the bytes, the counters
// and (in provenance mode) the intervals, classes and candidates of the frame as one scene; and a
// draw of 40,000 triangles cut between scenes keeps its uniforms and its tile counts, and an upload
// of the texture it samples still waits for all of its triangles.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "raster/cpu_backend.h"
#include "tests/raster/provenance_compare.h"
#include "tests/raster/render_helpers.h"
#include "tools/scenes/builder.h"
#include "tools/scenes/scene_common.h"
#include "tools/scenes/scenes.h"
#include "tools/scenes/sweep_scenes.h"

namespace tessera::scenes {
namespace {

constexpr uint32_t kOneScene = UINT32_MAX;  // no flush for memory: the frame is one scene
constexpr uint32_t kEveryDraw = 1;          // rasterized after every draw, and after every slice of one
constexpr uint32_t kCut = 16384;            // a draw of 40,000 triangles in three scenes

std::unique_ptr<CpuBackend> renderWithBound(const CommandList& cl, uint32_t bound, bool provenance, int threads) {
  RenderOptions o{threads, provenance, {}, 8};
  o.sceneTriangles = bound;
  auto b = std::make_unique<CpuBackend>(o);
  b->execute(cl, "scene_flush");
  return b;
}

// Every texture the list creates, its values and (in provenance mode) its records, and every counter.
void expectSameFrame(const CommandList& cl, const CpuBackend& whole, const CpuBackend& cut, const std::string& what) {
  EXPECT_TRUE(whole.stats() == cut.stats()) << what << ": the counters differ";
  for (const Command& c : cl.commands()) {
    const auto* ct = std::get_if<CreateTexture>(&c);
    if (!ct) continue;
    const TextureData *a = whole.texture(ct->id), *b = cut.texture(ct->id);
    ASSERT_TRUE(a && b) << what;
    ASSERT_EQ(a->levels, b->levels) << what << ", texture " << ct->id << ": values differ";
    ASSERT_EQ(bool(a->prov), bool(b->prov)) << what << ", texture " << ct->id;
    if (a->prov) testing::expectSameProvenance(*a->prov, *b->prov, what + ", texture " + std::to_string(ct->id));
  }
}

class SceneFlush : public ::testing::TestWithParam<std::string> {};

TEST_P(SceneFlush, RasterizedAfterEveryDrawASceneGivesTheWholeFramesBytesCountersAndProvenance) {
  const SceneInfo* info = find(GetParam());
  ASSERT_NE(info, nullptr);
  const CommandList cl = build(info->name, info->width, info->height);
  for (const bool provenance : {false, true}) {
    const auto whole = renderWithBound(cl, kOneScene, provenance, 2);
    const auto cut = renderWithBound(cl, kEveryDraw, provenance, 2);
    expectSameFrame(cl, *whole, *cut, GetParam() + (provenance ? " (provenance)" : ""));
    EXPECT_GE(cut->stageTimes().scenes, whole->stageTimes().scenes);
  }
}

INSTANTIATE_TEST_SUITE_P(AllScenes, SceneFlush, ::testing::ValuesIn([] {
                           std::vector<std::string> names;
                           for (const auto& s : all()) names.emplace_back(s.name);
                           return names;
                         }()),
                         [](const auto& param) { return param.param; });

// One flat-coloured triangle, then 40,000 textured triangles of about one pixel in one draw over a
// 256 x 256 target (three scenes at a bound of 16,384), then the draw's texture uploaded again with
// other texels, then one more triangle drawn with it. The upload must wait for every triangle of the
// cut draw, the last scene's too.
CommandList cutTexturedFrame() {
  constexpr int kW = 256, kTris = 40000;
  CommandList cl;
  beginFrame(cl, kW, kW, false, {0, 0, 0, 1});
  const RgbaImage before = checker(4, 4, 1, {250, 20, 20, 255}, {20, 250, 20, 255});
  const RgbaImage after = checker(4, 4, 1, {20, 20, 250, 255}, {250, 250, 20, 255});
  const ResourceId tex = uploadTexture(cl, before, false);
  Mesh m;
  for (int i = 0; i < kTris; ++i) {
    const float x = float(i % kW), y = float(i / kW), s = float(i % 4) / 4.0f + 0.125f;
    m.triangle({{x + 0.2f, y + 0.2f, 0}, {s, 0.125f, 0, 0}, 0}, {{x + 1.3f, y + 0.2f, 0}, {s, 0.125f, 0, 0}, 0},
               {{x + 0.2f, y + 1.3f, 0}, {s, 0.375f, 0, 0}, 0});
  }
  m.triangle({{0, 200, 0}, {0, 0, 0, 0}, 0}, {{256, 200, 0}, {1, 0, 0, 0}, 0}, {{0, 256, 0}, {0, 1, 0, 0}, 0});
  bindMesh(cl, m);
  // First a draw of another state, so that the cut draw's state is not the scene's first.
  cl.useProgram(cl.createProgram("flat_color"));
  setMatrix(cl, 0, ortho(0, kW, 0, kW, -1, 1));
  setVec4(cl, 4, {0.5f, 0.25f, 0.75f, 1});
  cl.drawIndexed(3 * kTris, 3);
  cl.useProgram(cl.createProgram("textured"));
  setMatrix(cl, 0, ortho(0, kW, 0, kW, -1, 1));
  setTexturedDefaults(cl);
  cl.bindTexture(0, tex);
  cl.drawIndexed(0, 3 * kTris);
  cl.uploadTexture(tex, 0, 0, after.rgba);
  cl.drawIndexed(3 * kTris, 3);
  return cl;
}

TEST(SceneFlush, ADrawCutBetweenScenesKeepsItsUniformsAndCounters) {
  // 40,000 one-pixel triangles in one flat_color draw (its colour is a uniform): a bound of 16,384
  // set-up triangles cuts it into three scenes; a bound of 1 after every slice (16,384 triangles, or
  // 8,192 at one thread); the default bound at one thread after every 8,192, and not at all with more
  // threads.
  const CommandList cl = buildTinyTris(256, 256, 40000);
  const auto whole = renderWithBound(cl, kOneScene, false, 1);
  EXPECT_EQ(whole->stageTimes().scenes, 1u);
  for (const int threads : {1, 2, 7})
    for (const uint32_t bound : {kCut, kEveryDraw, 0u}) {
      const auto cut = renderWithBound(cl, bound, false, threads);
      const uint64_t scenes = bound == kCut ? 3 : threads == 1 ? 5 : bound == kEveryDraw ? 3 : 1;
      EXPECT_EQ(cut->stageTimes().scenes, scenes) << "bound " << bound << ", " << threads << " threads";
      expectSameFrame(cl, *whole, *cut, "bound " + std::to_string(bound) + ", " + std::to_string(threads) + " threads");
    }
  EXPECT_EQ(whole->stats().triangles_binned, 40000u);
}

TEST(SceneFlush, AnUploadWaitsForEveryTriangleOfADrawCutBetweenScenes) {
  const CommandList cl = cutTexturedFrame();
  const auto whole = renderWithBound(cl, kOneScene, false, 2);
  EXPECT_EQ(whole->stageTimes().scenes, 2u);  // the upload reads the texture the draw samples
  for (const uint32_t bound : {kCut, kEveryDraw}) {
    const auto cut = renderWithBound(cl, bound, false, 2);
    // kCut: the cut draw's first two slices (the flat triangle in the first), the third before the
    // upload, the last triangle. A bound of 1 gives the flat triangle a scene of its own.
    EXPECT_EQ(cut->stageTimes().scenes, bound == kEveryDraw ? 5u : 4u) << "bound " << bound;
    expectSameFrame(cl, *whole, *cut, "bound " + std::to_string(bound));
  }
}

}  // namespace
}  // namespace tessera::scenes
