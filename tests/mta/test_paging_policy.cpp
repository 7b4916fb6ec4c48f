// The memory manager's policy of §4.6 on a small tree: a frame loads only what it draws.
#include <gtest/gtest.h>

#include <algorithm>
#include <condition_variable>
#include <mutex>
#include <set>

#include "mta/build.h"
#include "mta/tree_renderer.h"
#include "mta_test_scene.h"

namespace tessera::mta {
namespace {

using testing::gridScene;
using testing::TempFile;

LoadBudget wholeBlocks(uint64_t perFrame) {
  LoadBudget b;
  b.kind = LoadBudget::Kind::Blocks;
  b.perFrame = perFrame;
  return b;
}

RendererOptions unlimited(uint32_t width) {
  RendererOptions o;
  o.width = width;
  o.height = width * 3 / 4;
  o.threads = 2;
  o.residency.capacityBytes = uint64_t(1) << 32;
  o.residency.budget = wholeBlocks(UINT64_MAX);
  o.residency.maxQueue = UINT32_MAX;
  return o;
}

TEST(PagingPolicy, AViewThatNeedsOneFacadeImageLoadsOnlyThatImagesBytes) {
  // Four facades side by side whose 32 x 32 images (3072 bytes each) cannot share a 64² atlas with their
  // borders, so no leaf holds two facades; several of the images would fit one 4 · 64² byte block.
  TempFile file("facades.mta");
  BuildParams p;
  p.atlasSize = 64;
  p.border = 2;
  p.dMin = 1.0;
  p.screenWidth = 256;
  p.threads = 2;
  buildMta(gridScene(4, 1, 32, 1.0f), p, file.path);
  const PagingFile f(file.path);
  const MtaMeta& m = f.meta();
  // Close in front of facade 1 (x in [1, 2]): the others are outside the frustum.
  Camera c;
  c.eye = {1.5, 0.5, 0.3};
  c.target = {1.5, 0.5, 0.0};
  c.tanHalfFovX = m.params.tanHalfFov;
  c.nearPlane = 0.01;
  c.farPlane = 100.0;
  TreeRenderer r(f, unlimited(256));
  const FrameResult fr = r.renderFrame(c);
  ASSERT_GE(fr.plan.originalLeaves, 1u);  // the facade's leaves (its two triangles may be two leaves)
  std::set<uint32_t> drawn;
  for (const PlannedDraw& d : fr.plan.draws)
    if (d.source == DrawSource::Original) drawn.insert(m.textures[uint32_t(d.texture)].image);
  ASSERT_EQ(drawn, std::set<uint32_t>{1u});
  uint64_t originalBytes = 0;
  for (uint32_t b : fr.residency.loadOrder)
    if (m.blocks[b].kind == BlockKind::Original) {
      EXPECT_EQ(m.blocks[b].node, 1u) << "block " << b << " holds image " << m.blocks[b].node;
      originalBytes += m.blocks[b].size;
    }
  // Over-fetch 0: every original byte read is a texel of the one image drawn.
  EXPECT_EQ(originalBytes, uint64_t(m.images[1].width) * m.images[1].height * m.images[1].channels);
}

}  // namespace
}  // namespace tessera::mta
