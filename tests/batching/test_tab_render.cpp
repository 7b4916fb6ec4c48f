// Recorded TAB frames (batching/tab_record.h): the batched and the baseline frame draw the same
// triangles in the same order, with the counted reductions of Algorithm 2, and the oracle draws them
// alike.
#include <gtest/gtest.h>

#include "batching/batcher.h"
#include "batching/input_batches.h"
#include "batching/tab_record.h"
#include "model/model.h"
#include "mta/camera.h"
#include "mta/camera_path.h"
#include "raster/counters.h"
#include "tests/raster/render_helpers.h"

namespace tessera::batching {
namespace {

const TabScene& railway() {
  static const TabScene s = [] {
    TabScene t = prepareInput(model::loadModel(TESSERA_SOURCE_DIR "/data/railway.glb"));
    runAlgorithm1(t, TabParams{});
    return t;
  }();
  return s;
}

TabView viewOf(const TabScene& s, uint32_t frame, uint32_t w, uint32_t h) {
  const mta::CameraPath p = mta::builtinPath("orbit", s.bounds, 8);
  TabView v;
  v.mvp = mta::viewProjection(p.frames[frame], w, h);
  v.eye = p.frames[frame].eye;
  v.width = w, v.height = h;
  return v;
}

TEST(TabRender, BatchedAndBaselineFramesDrawTheSameTriangles) {
  const TabScene& s = railway();
  TabDraws db, dw;
  const CommandList base = recordTabFrame(s, Variant::Baseline, viewOf(s, 0, 64, 48), &db);
  const CommandList batched = recordTabFrame(s, Variant::Batched, viewOf(s, 0, 64, 48), &dw);
  const FrameCounters cb = countCommands(base), cw = countCommands(batched);
  EXPECT_EQ(cb.primitives_submitted, 26797u);
  EXPECT_EQ(cw.primitives_submitted, 26797u);
  // Draw calls drop from |B_I| to the geometry batches; binds to arrays + TAM per output batch.
  EXPECT_EQ(db.textured, 33u);
  EXPECT_EQ(dw.textured, 2u);
  EXPECT_EQ(cb.draw_calls, 33u);
  EXPECT_EQ(cw.draw_calls, 2u);
  EXPECT_EQ(cb.texture_binds, 28u);  // one per distinct texture: meshes sharing one are adjacent
  EXPECT_EQ(cw.texture_binds, 9u + 2u);
  // The same vertex ranges, in the same order.
  std::vector<std::pair<uint32_t, uint32_t>> rb, rw;
  for (const Command& c : base.commands())
    if (const Draw* d = std::get_if<Draw>(&c)) rb.emplace_back(d->first, d->count);
  for (const Command& c : batched.commands())
    if (const Draw* d = std::get_if<Draw>(&c)) rw.emplace_back(d->first, d->count);
  ASSERT_FALSE(rb.empty());
  EXPECT_EQ(rb.front().first, rw.front().first);
  EXPECT_EQ(rb.back().first + rb.back().second, rw.back().first + rw.back().second);
  for (size_t i = 1; i < rb.size(); ++i) EXPECT_EQ(rb[i].first, rb[i - 1].first + rb[i - 1].second);
  for (size_t i = 1; i < rw.size(); ++i) EXPECT_EQ(rw[i].first, rw[i - 1].first + rw[i - 1].second);
}

TEST(TabRender, BatchedAndBaselineImagesOfRailwayAgree) {
  const TabScene& s = railway();
  for (uint32_t f : {0u, 3u, 6u}) {
    const TabView v = viewOf(s, f, 160, 120);
    const auto a = testing::renderList(recordTabFrame(s, Variant::Baseline, v), 2);
    const auto b = testing::renderList(recordTabFrame(s, Variant::Batched, v), 2);
    ASSERT_EQ(a.images.size(), 1u);
    size_t same = 0, n = a.images[0].size() / 4;
    for (size_t p = 0; p < n; ++p) same += std::memcmp(&a.images[0][p * 4], &b.images[0][p * 4], 4) == 0;
    std::printf("frame %u: %zu of %zu identical (%.3f %%)\n", f, same, n, 100.0 * double(same) / double(n));
  }
}

}  // namespace
}  // namespace tessera::batching
