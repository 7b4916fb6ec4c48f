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
#include "raster/lod_probe.h"
#include "tests/raster/render_helpers.h"
#include "verify/lod_compare.h"

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

TEST(TabRender, BatchedAndBaselineImagesOfRailwayAreIdenticalWithTheSameLambdaAtEveryPixel) {
  // Same triangles, same order, same texels, same material arithmetic: the two programs agree to the
  // bit on these frames. texarray_batch rounds its quad differences to float, textured takes them in
  // double; by Sterbenz's lemma the float difference is exact unless a quad's texcoords straddle 0, and
  // even then it moves lambda only next to a 1/256 rounding boundary (docs/tab.md, "Baseline and batched").
  const TabScene& s = railway();
  for (uint32_t f : {0u, 3u, 6u}) {
    const TabView v = viewOf(s, f, 160, 120);
    const CommandList lb = recordTabFrame(s, Variant::Baseline, v), lw = recordTabFrame(s, Variant::Batched, v);
    const auto a = testing::renderList(lb, 2);
    const auto b = testing::renderList(lw, 2);
    ASSERT_EQ(a.images.size(), 1u);
    EXPECT_EQ(a.hashes[0], b.hashes[0]) << "frame " << f;
    const verify::LodComparison c = verify::compareLodMaps(lodMap(lb, 2), lodMap(lw, 2));
    EXPECT_GT(c.pixelsWithLookups, 1000u);
    EXPECT_EQ(c.differing, 0u) << "frame " << f;
    EXPECT_EQ(c.unitDiffers, c.pixelsWithLookups) << "the batched frame samples arrays on units 1..8";
  }
}

}  // namespace
}  // namespace tessera::batching
