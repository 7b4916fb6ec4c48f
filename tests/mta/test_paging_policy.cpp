// The memory manager's policy of §4.6 on a small tree: the order in which resident blocks are removed,
// which layers are requested, cancelled background loads, and that a frame loads only what it draws.
#include <gtest/gtest.h>

#include <algorithm>
#include <condition_variable>
#include <mutex>
#include <set>

#include "mta/build.h"
#include "mta/tree_renderer.h"
#include "mta_test_scene.h"
#include "wall_tree_file.h"

namespace tessera::mta {
namespace {

using testing::gridScene;
using testing::smallTreeParams;
using testing::TempFile;

using testing::fixture;

LoadBudget wholeBlocks(uint64_t perFrame) {
  LoadBudget b;
  b.kind = LoadBudget::Kind::Blocks;
  b.perFrame = perFrame;
  return b;
}

uint32_t atlasBlock(const MtaMeta& m, uint32_t node, uint32_t layer = 0) {
  return m.trees[0].atlasBlocks[size_t(node) * m.layerCount + layer];
}

// The original-texture blocks of a leaf's images.
std::vector<uint32_t> originalBlocks(const MtaMeta& m, uint32_t leaf) {
  std::set<uint32_t> s;
  const Node& n = m.trees[0].nodes[leaf];
  for (uint32_t k = 0; k < n.imageCount; ++k) {
    const ImageRecord& r = m.images[m.trees[0].leafImages[n.imageFirst + k]];
    for (uint32_t p = 0; p < r.pieceCount; ++p) s.insert(m.pieces[r.firstPiece + p].block);
  }
  return {s.begin(), s.end()};
}

TEST(PagingPolicy, UnusedBlocksKeepTheirLastDistanceAndLevelSoDescendantsAreEvictedBeforeAncestors) {
  const MtaMeta& m = fixture().tree->meta();
  const std::vector<Node>& nodes = m.trees[0].nodes;
  // A leaf at least three levels down and the path to it below the (pinned) root: path[k] at level k + 1.
  uint32_t leaf = 0;
  while (leaf < nodes.size() && !(nodes[leaf].leaf() && nodes[leaf].level >= 3)) ++leaf;
  ASSERT_LT(leaf, nodes.size()) << "the fixture should have a leaf at level 3 or deeper";
  std::vector<uint32_t> path;
  for (int32_t n = int32_t(leaf); n > 0; n = nodes[uint32_t(n)].parent) path.insert(path.begin(), uint32_t(n));
  ASSERT_EQ(path.size(), nodes[leaf].level);
  const std::vector<uint32_t> originals = originalBlocks(m, leaf);
  ASSERT_FALSE(originals.empty());

  // Frame 1 (hand-made priorities, as the usage traversal gives them for an eye near the leaf): the path
  // is Needed with distances growing downwards, the leaf at its parent's distance (so the level decides
  // between them), the leaf's originals Parent needed at the leaf's distance one level below it.
  std::vector<BlockPriority> frame1(m.blocks.size());
  frame1[atlasBlock(m, 0)] = {Usage::Needed, 0.0, 0};
  uint64_t frame1Bytes = 0;
  for (size_t k = 0; k < path.size(); ++k) {
    const double d = double(std::min(k + 1, path.size() - 1));
    frame1[atlasBlock(m, path[k])] = {Usage::Needed, d, nodes[path[k]].level};
    frame1Bytes += m.blocks[atlasBlock(m, path[k])].size;
  }
  const double leafDistance = double(path.size() - 1);
  for (uint32_t b : originals) frame1[b] = {Usage::ParentNeeded, leafDistance, nodes[leaf].level + 1}, frame1Bytes += m.blocks[b].size;

  // Frame 2: the camera has left; other leaves' atlases fill the whole capacity, so every block of frame 1
  // is removed, lowest priority first: the originals (deepest level), the leaf (its parent's distance, one
  // level deeper), then the path upwards. Without the kept distances all of them would tie at an infinite
  // distance and go by block index, which removes ancestors (written after their children) first.
  const uint64_t atlas = m.blocks[atlasBlock(m, 0)].size;
  const uint64_t slots = (frame1Bytes + atlas - 1) / atlas;
  std::vector<BlockPriority> frame2(m.blocks.size());
  frame2[atlasBlock(m, 0)] = {Usage::Needed, 50.0, 0};
  uint64_t others = 0;
  for (uint32_t i = 1; i < nodes.size() && others < slots; ++i) {
    if (!nodes[i].leaf() || i == leaf) continue;
    frame2[atlasBlock(m, i)] = {Usage::Needed, 50.0 + i, nodes[i].level};
    ++others;
  }
  ASSERT_EQ(others, slots);

  ResidencyOptions ro;
  ro.capacityBytes = atlas + slots * atlas;
  ro.budget = wholeBlocks(UINT64_MAX);
  ro.maxQueue = UINT32_MAX;
  Residency res(*fixture().tree, ro);
  EXPECT_EQ(res.update(frame1).neededMissing, 0u);
  for (uint32_t b : originals) ASSERT_TRUE(res.resident(b));
  const ResidencyFrameStats& s = res.update(frame2);

  std::vector<uint32_t> expected(originals.rbegin(), originals.rend());  // equal priority: higher index first
  for (size_t k = path.size(); k-- > 0;) expected.push_back(atlasBlock(m, path[k]));
  EXPECT_EQ(s.evictionOrder, expected);
  EXPECT_EQ(s.neededMissing, 0u);
  // The kept priorities themselves.
  const BlockPriority& parent = res.priority(atlasBlock(m, path[path.size() - 2]));
  EXPECT_EQ(parent.usage, Usage::Unused);
  EXPECT_EQ(parent.distance, leafDistance);
  EXPECT_EQ(parent.level, nodes[leaf].level - 1);
  EXPECT_EQ(res.priority(atlasBlock(m, leaf)).level, nodes[leaf].level);
  EXPECT_EQ(res.priority(originals[0]).level, nodes[leaf].level + 1);
  EXPECT_EQ(res.priority(originals[0]).distance, leafDistance);
}

// Cameras facing a wall in the plane z = 0 centred on (cx, cy): from `far` away to `close`, then along it.
std::vector<Camera> wallPath(const MtaMeta& m, double cx, double cy, double far, double close, double pan) {
  std::vector<Camera> cams;
  for (int i = 0; i < 24; ++i) {
    const double t = i / 23.0;
    Camera c;
    const double x = cx + (t < 0.5 ? 0.0 : pan * (t - 0.5) * 2.0), z = t < 0.5 ? far + (close - far) * t * 2.0 : close;
    c.eye = {x, cy, z};
    c.target = {x, cy, 0.0};
    c.tanHalfFovX = m.params.tanHalfFov;
    c.nearPlane = 0.01;
    c.farPlane = 200.0;
    cams.push_back(c);
  }
  return cams;
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

TEST(PagingPolicy, NoBlockOfALayerThatNothingDrawsIsEverRequestedOrLoaded) {
  // Two layers; a renderer drawing layer 0 alone (the memory manager and the traversals driven as
  // TreeRenderer drives them, with drawn layers {0}: the recorder itself draws both since layer 1 is
  // drawn, test_layer_drawing.cpp).
  TempFile file("layers.mta");
  BuildParams p = smallTreeParams();
  buildMta(gridScene(8, 8, 32, 2.0f, true), p, file.path);
  const PagingFile f(file.path);
  const MtaMeta& m = f.meta();
  ASSERT_EQ(m.layerCount, 2u);
  // Images that only layer 1 uses: the per-triangle textures of the second layer.
  std::set<uint32_t> layer0Images, layer1Only;
  for (const Tree& t : m.trees)
    for (uint32_t k = 0; k < t.geometry.triangleCount(); ++k)
      if (t.geometry.layers[0].texture[k] >= 0) layer0Images.insert(m.textures[t.geometry.layers[0].texture[k]].image);
  for (const Tree& t : m.trees)
    for (uint32_t k = 0; k < t.geometry.triangleCount(); ++k)
      if (t.geometry.layers[1].texture[k] >= 0 && !layer0Images.count(m.textures[t.geometry.layers[1].texture[k]].image))
        layer1Only.insert(m.textures[t.geometry.layers[1].texture[k]].image);
  ASSERT_FALSE(layer1Only.empty());
  auto layer1Block = [&](uint32_t b) {
    const BlockInfo& bi = m.blocks[b];
    return bi.kind == BlockKind::Atlas ? bi.layer != 0 : layer1Only.count(bi.node) != 0;
  };

  RendererOptions o = unlimited(256);
  o.residency.drawnLayers = LayerMask(1);
  Residency residency(f, o.residency);
  const BlockIndex layer0 = buildBlockIndex(m, LayerMask(1));
  const RuntimeGeometry g = buildRuntimeGeometry(m);
  TreeRenderer viewer(f, o);  // for its ViewParams only
  const std::vector<Camera> cams = wallPath(m, 4.0, 4.0, 20.0, 0.4, 3.0);
  uint64_t loaded = 0, originalsDrawn = 0;
  for (size_t i = 0; i < cams.size(); ++i) {
    const ViewContext ctx = makeViewContext(m, viewer.view(cams[i]));
    const ResidencyFrameStats st = residency.update(usagePriorities(m, layer0, ctx));
    for (uint32_t b : st.loadOrder) EXPECT_FALSE(layer1Block(b)) << "frame " << i << " loaded block " << b;
    loaded += st.loadOrder.size();
    EXPECT_EQ(st.neededMissing, 0u);
    originalsDrawn += planFrame(m, g, layer0, ctx, RenderMode::AtlasTree, [&](uint32_t b) { return residency.resident(b); })
                          .originalLeaves;
  }
  EXPECT_GT(loaded, 0u);
  EXPECT_GT(originalsDrawn, 0u) << "the path should come close enough to draw original textures";
  for (uint32_t b = 0; b < m.blocks.size(); ++b) EXPECT_FALSE(layer1Block(b) && residency.resident(b)) << "block " << b;

  // The renderer, which draws layer 1 too (kRecordedLayers), requests and loads its blocks over the same
  // views: the set follows the layers drawn.
  ASSERT_EQ(kRecordedLayers & LayerMask(2), LayerMask(2));
  TreeRenderer r(f, unlimited(256));
  bool atlas1 = false, original1 = false;
  for (const Camera& c : cams)
    for (uint32_t b : r.renderFrame(c).residency.loadOrder)
      if (layer1Block(b)) (m.blocks[b].kind == BlockKind::Atlas ? atlas1 : original1) = true;
  EXPECT_TRUE(atlas1);
  EXPECT_TRUE(original1);
}

TEST(PagingPolicy, AViewThatNeedsOneFacadeImageLoadsOnlyThatImagesBytes) {
  // Four facades side by side whose 32 x 32 images (3072 bytes each) cannot share a 64² atlas with their
  // borders, so no leaf holds two facades; several of the images would fit one 4 · 64² byte block.
  TempFile file("facades.mta");
  BuildParams p = smallTreeParams(1.0);
  p.encoding = BlockEncoding::Raw;  // the bytes of one image are its texels (S3TC: test_s3tc_blocks.cpp)
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

// A reader the test holds: the loader thread waits inside it until the test opens the gate.
struct Gate {
  std::mutex mu;
  std::condition_variable cv;
  bool open = false;
  std::set<uint32_t> entered;
};

TEST(PagingPolicy, ATimedLoadThatLeavesTheIdealSetIsDroppedInsteadOfInstalled) {
  const PagingFile& f = *fixture().tree;
  const MtaMeta& m = f.meta();
  const std::vector<Node>& nodes = m.trees[0].nodes;
  ASSERT_GE(nodes.size(), 3u);
  const uint32_t x = atlasBlock(m, 1), y = atlasBlock(m, 2), root = atlasBlock(m, 0);
  auto gate = std::make_shared<Gate>();
  ResidencyOptions ro;
  ro.capacityBytes = uint64_t(1) << 30;
  ro.budget.kind = LoadBudget::Kind::Time;
  ro.budget.slotMs = 1.0;
  ro.blockReader = [gate, &f](uint32_t b) {
    std::unique_lock<std::mutex> lk(gate->mu);
    gate->entered.insert(b);
    gate->cv.notify_all();
    gate->cv.wait(lk, [&] { return gate->open; });
    return f.readBlock(b);
  };
  Residency res(f, ro);
  const uint64_t rootBytes = m.blocks[root].size;
  ASSERT_EQ(res.bytesResident(), rootBytes);

  // Frame 1: x and y are Needed; both go to the loader (two in flight), which starts reading x and waits.
  std::vector<BlockPriority> want(m.blocks.size());
  want[root] = {Usage::Needed, 0.0, 0};
  want[x] = {Usage::Needed, 1.0, 1};
  want[y] = {Usage::Needed, 2.0, 1};
  EXPECT_EQ(res.update(want).blocksLoaded, 0u);
  {
    std::unique_lock<std::mutex> lk(gate->mu);
    gate->cv.wait(lk, [&] { return gate->entered.count(x) != 0; });
    EXPECT_EQ(gate->entered.count(y), 0u) << "the loader reads one block at a time";
  }
  EXPECT_EQ(res.bytesResident(), rootBytes + m.blocks[x].size + m.blocks[y].size);  // both reserved

  // Frame 2: the camera turned away. y had not been started: taken back at once. x is being read: its
  // bytes stay reserved until the read ends, then it is dropped.
  std::vector<BlockPriority> away(m.blocks.size());
  away[root] = {Usage::Needed, 0.0, 0};
  EXPECT_EQ(res.update(away).loadsCancelled, 2u);
  EXPECT_EQ(res.bytesResident(), rootBytes + m.blocks[x].size);
  {
    std::lock_guard<std::mutex> lk(gate->mu);
    gate->open = true;
  }
  gate->cv.notify_all();
  res.waitForLoader();
  const ResidencyFrameStats& s3 = res.update(away);
  EXPECT_EQ(s3.blocksLoaded, 0u);
  EXPECT_FALSE(res.resident(x));
  EXPECT_FALSE(res.resident(y));
  EXPECT_EQ(res.bytesResident(), rootBytes);
  {
    std::lock_guard<std::mutex> lk(gate->mu);
    EXPECT_EQ(gate->entered.count(y), 0u) << "a block taken back must not be read";
  }

  // Wanted again, x is loaded normally.
  res.update(want);
  res.waitForLoader();
  res.update(want);
  EXPECT_TRUE(res.resident(x));
}

}  // namespace
}  // namespace tessera::mta
