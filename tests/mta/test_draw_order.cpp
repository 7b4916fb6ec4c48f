// The draw order of an atlas tree frame (mta/draw_order.h): draws grouped by texture bind each texture
// once, draw every triangle exactly once, do not depend on anything but the plan, and give the frame
// of the leaf-by-leaf order wherever no two fragments tie in depth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <set>

#include "model/model.h"
#include "mta/build.h"
#include "mta/camera_path.h"
#include "mta/draw_order.h"
#include "mta/frame_recorder.h"
#include "mta/texture_cache.h"
#include "mta/tree_renderer.h"
#include "mta_test_scene.h"
#include "raster/counters.h"
#include "raster/cpu_backend.h"

namespace tessera::mta {
namespace {

using testing::addSquare;
using testing::smallTreeParams;
using testing::TempFile;

// A wall of 12 x 12 unit quads at z = 0 whose textures repeat every three quads, so that many leaves
// share each texture; in front of it (z = 0.5) a 5 x 5 layer of quads offset by half a quad, textures
// shifted by one, every fourth one untextured. With `decals`, eight quads lie on the wall itself
// (z = 0, over the centres of wall quads) with a fourth texture: they tie in depth with the wall.
Scene sharedTextureScene(bool decals) {
  Scene s;
  s.name = decals ? "shared_decals" : "shared";
  Geometry& g = s.geometry;
  g.layers.resize(1);
  constexpr int kTextures = 4;
  for (int t = 0; t < kTextures; ++t) {
    s.images.push_back(SceneImage{32, 32, "img" + std::to_string(t)});
    s.textures.push_back(SceneTexture{uint32_t(t), model::Wrap::Repeat, model::Wrap::Repeat});
  }
  auto quad = [&](float x0, float y0, float size, float z, int32_t texture) {
    addSquare(g, x0, y0, size, z, {texture});
  };
  for (int q = 0; q < 144; ++q) quad(float(q % 12), float(q / 12), 1.0f, 0.0f, q % 3);
  for (int q = 0; q < 25; ++q)
    quad(3.5f + float(q % 5), 3.5f + float(q / 5), 1.0f, 0.5f, q % 4 == 3 ? -1 : (q + 1) % 3);
  if (decals)
    for (int q = 0; q < 8; ++q) quad(1.25f + float(q), 1.25f + float((q * 5) % 8), 0.5f, 0.0f, 3);
  s.loadImage = [](uint32_t i) {
    model::Image img;
    img.width = img.height = 32;
    img.rgba.resize(32 * 32 * 4);
    for (uint32_t y = 0; y < 32; ++y)
      for (uint32_t x = 0; x < 32; ++x) {
        uint8_t* p = &img.rgba[(size_t(y) * 32 + x) * 4];
        p[0] = uint8_t(x * 7 + i * 71), p[1] = uint8_t(y * 5 + i * 97), p[2] = uint8_t((x ^ y) * 3 + i * 40),
        p[3] = 255;
      }
    return img;
  };
  return s;
}

struct SharedTree {
  TempFile file;
  std::unique_ptr<PagingFile> tree;
  RuntimeGeometry geometry;
  BlockIndex index;
  explicit SharedTree(bool decals) : file(decals ? "decals.mta" : "shared.mta") {
    BuildParams p = smallTreeParams();
    buildMta(sharedTextureScene(decals), p, file.path);
    tree = std::make_unique<PagingFile>(file.path);
    geometry = buildRuntimeGeometry(tree->meta());
    index = buildBlockIndex(tree->meta(), kRecordedLayers);
  }
};

SharedTree& sharedTree(bool decals) {
  static SharedTree plain(false), withDecals(true);
  return decals ? withDecals : plain;
}

// From far away (node atlases) to near, then along the wall close up (the nearest leaves with their original
// textures, the others with atlases).
std::vector<ViewParams> drawOrderViews(const MtaMeta& meta) {
  std::vector<ViewParams> out;
  for (int i = 0; i < 16; ++i) {
    ViewParams v;
    v.width = 128;
    v.height = 96;
    const double z = i < 8 ? 30.0 - 3.5 * i : 1.0, x = i < 8 ? 6.0 : 2.0 + 1.2 * (i - 8);
    v.camera.eye = {x, 5.0, z};
    v.camera.target = {x + 0.5, 6.0, 0.0};
    v.camera.tanHalfFovX = meta.params.tanHalfFov;
    v.camera.nearPlane = 0.05;
    v.camera.farPlane = 200.0;
    out.push_back(v);
  }
  return out;
}

FramePlan plan(const SharedTree& t, const ViewParams& v, RenderMode mode) {
  return planFrame(t.tree->meta(), t.geometry, t.index, makeViewContext(t.tree->meta(), v), mode,
                   [](uint32_t) { return true; });
}

struct Executed {
  FrameCounters counters;
  std::vector<ResourceId> bound;  // every texture bind, in order
  std::vector<uint8_t> color, depth;
  std::vector<uint8_t> ids;  // the id frame's attachment 0 (global triangle index per pixel)
};

const TextureData& attachment(const CpuBackend& b, const CommandList& cl, bool depth) {
  for (const Command& c : cl.commands())
    if (const auto* rt = std::get_if<SetRenderTarget>(&c))
      return *b.texture(depth ? rt->target.depth : rt->target.color[0]);
  throw Error("the frame sets no render target");
}

// Records and runs frames the way TreeRenderer does, one list for every frame. A backend keeps only
// memory from frame to frame (StoragePool: the previous frame's storage), so the id frames, which have
// no atlas textures, get a backend of their own: sharing one, every colour frame allocated its atlases
// afresh, and under ASan each fresh mapping is zeroed, faulted in and unmapped (CONTRIBUTING.md).
struct Runner {
  CpuBackend backend{RenderOptions{2, false}}, idBackend{RenderOptions{2, false}};
  RecordedFrame frame;

  Executed run(const PagingFile& file, const RuntimeGeometry& geometry, TextureCache& textures, const FramePlan& p,
               const ViewParams& v) {
    RecordParams rp;
    rp.width = v.width;
    rp.height = v.height;
    Executed e;
    recordFrame(file.meta(), geometry, p, v, textures, rp, frame);
    e.counters = countCommands(frame.list);
    for (const Command& c : frame.list.commands())
      if (const auto* b = std::get_if<BindTexture>(&c)) e.bound.push_back(b->texture);
    backend.execute(frame.list);
    e.color = attachment(backend, frame.list, false).levels[0];
    e.depth = attachment(backend, frame.list, true).levels[0];
    rp.idFrame = true;
    recordFrame(file.meta(), geometry, p, v, textures, rp, frame);
    idBackend.execute(frame.list);
    e.ids = attachment(idBackend, frame.list, false).levels[0];
    return e;
  }
};

Executed execute(const SharedTree& t, const FramePlan& p, const ViewParams& v) {
  TextureCache textures(*t.tree, nullptr);
  return Runner().run(*t.tree, t.geometry, textures, p, v);
}

FramePlan grouped(FramePlan p) {
  groupDrawsByTexture(p);
  return p;
}

// How often each global triangle is drawn.
std::vector<uint32_t> drawnTimes(const FramePlan& p, uint32_t triangles) {
  std::vector<uint32_t> n(triangles, 0);
  for (const PlannedDraw& d : p.draws)
    for (uint32_t k = 0; k < d.count; ++k) ++n.at(d.first + k);
  return n;
}

PlannedDraw draw(DrawSource s, uint32_t node, int32_t texture, uint32_t first, uint32_t count) {
  return PlannedDraw{s, 0, node, texture, first, count};
}

bool same(const PlannedDraw& a, const PlannedDraw& b) {
  return a.source == b.source && a.tree == b.tree && a.node == b.node && a.texture == b.texture && a.first == b.first &&
         a.count == b.count;
}

bool sameDraws(const FramePlan& a, const FramePlan& b) {
  return std::equal(a.draws.begin(), a.draws.end(), b.draws.begin(), b.draws.end(), same);
}

uint32_t pixelId(const std::vector<uint8_t>& ids, size_t pixel) {
  uint32_t v = 0;
  std::memcpy(&v, &ids[pixel * 4], 4);
  return v;
}

TEST(DrawOrder, AHandMadePlanIsGroupedByTextureInOrderOfFirstUseAndContiguousRangesOfATextureMerge) {
  // Leaf 3: texture 1 on [0, 2), texture 2 on [2, 3); node 5's atlas on [3, 9); leaf 9: texture 2 on
  // [9, 11), texture 0 on [11, 12); leaf 10: texture 0 on [12, 14), texture 1 on [14, 15); untextured
  // [20, 22) and [22, 23) last.
  FramePlan p;
  p.draws = {draw(DrawSource::Original, 3, 1, 0, 2),    draw(DrawSource::Original, 3, 2, 2, 1),
             draw(DrawSource::Atlas, 5, -1, 3, 6),      draw(DrawSource::Original, 9, 2, 9, 2),
             draw(DrawSource::Original, 9, 0, 11, 1),   draw(DrawSource::Original, 10, 0, 12, 2),
             draw(DrawSource::Original, 10, 1, 14, 1),  draw(DrawSource::Untextured, 0, -1, 20, 2),
             draw(DrawSource::Untextured, 0, -1, 22, 1)};
  groupDrawsByTexture(p);
  // Texture 1 first (both of its draws), then texture 2, the atlas, texture 0 (leaf 9's [11, 12) and leaf
  // 10's [12, 14) are contiguous: one draw, named after leaf 9), the untextured triangles (one draw).
  const std::vector<PlannedDraw> want = {
      draw(DrawSource::Original, 3, 1, 0, 2),    draw(DrawSource::Original, 10, 1, 14, 1),
      draw(DrawSource::Original, 3, 2, 2, 1),    draw(DrawSource::Original, 9, 2, 9, 2),
      draw(DrawSource::Atlas, 5, -1, 3, 6),      draw(DrawSource::Original, 9, 0, 11, 3),
      draw(DrawSource::Untextured, 0, -1, 20, 3)};
  ASSERT_EQ(p.draws.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i)
    EXPECT_TRUE(same(p.draws[i], want[i]))
        << "draw " << i << ": source " << int(p.draws[i].source) << " texture " << p.draws[i].texture << " ["
        << p.draws[i].first << ", +" << p.draws[i].count << ")";
}

TEST(DrawOrder, OriginalDrawsAreGroupedByTheirPairOfLayerTexturesSoDifferentLightMapsNeverMerge) {
  // Leaf 3: base texture 1 with light map 5 on [0, 2), with light map 6 on [2, 4); leaf 4: texture 1 with
  // light map 5 on [4, 5), contiguous with nothing of its pair before it.
  auto lit = [](uint32_t node, int32_t texture1, uint32_t first, uint32_t count) {
    PlannedDraw d = draw(DrawSource::Original, node, 1, first, count);
    d.texture1 = texture1;
    return d;
  };
  FramePlan p;
  p.draws = {lit(3, 5, 0, 2), lit(3, 6, 2, 2), lit(4, 5, 4, 1)};
  groupDrawsByTexture(p);
  // (1, 5) first, both of its draws apart (not contiguous), then (1, 6); keyed by texture 1 alone, the
  // first two would have merged into one draw with light map 5 over [0, 4).
  ASSERT_EQ(p.draws.size(), 3u);
  const uint32_t first[3] = {0, 4, 2};
  const int32_t light[3] = {5, 5, 6};
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(p.draws[i].first, first[i]) << "draw " << i;
    EXPECT_EQ(p.draws[i].texture1, light[i]) << "draw " << i;
  }
}

TEST(DrawOrder, GroupingIsAFunctionOfThePlanAndDrawsEveryTriangleExactlyOnce) {
  const SharedTree& t = sharedTree(false);
  size_t framesReordered = 0;
  for (RenderMode mode : {RenderMode::AtlasTree, RenderMode::Original, RenderMode::Dummy})
    for (const ViewParams& v : drawOrderViews(t.tree->meta())) {
      const FramePlan leafByLeaf = plan(t, v, mode);
      const FramePlan g = grouped(leafByLeaf);
      EXPECT_EQ(drawnTimes(g, t.geometry.triangleCount()), drawnTimes(leafByLeaf, t.geometry.triangleCount()));
      for (uint32_t n : drawnTimes(g, t.geometry.triangleCount())) ASSERT_LE(n, 1u);
      EXPECT_EQ(g.trianglesDrawn, leafByLeaf.trianglesDrawn);
      // The same plan again (a fresh traversal), and the grouped plan grouped again: the same draws.
      const FramePlan again = grouped(plan(t, v, mode)), twice = grouped(g);
      ASSERT_EQ(again.draws.size(), g.draws.size());
      ASSERT_EQ(twice.draws.size(), g.draws.size());
      for (size_t i = 0; i < g.draws.size(); ++i) {
        EXPECT_TRUE(same(again.draws[i], g.draws[i])) << "draw " << i;
        EXPECT_TRUE(same(twice.draws[i], g.draws[i])) << "draw " << i;
      }
      framesReordered += !sameDraws(g, leafByLeaf);
    }
  EXPECT_GT(framesReordered, 5u) << "the scene should make the grouping reorder draws";
}

TEST(DrawOrder, EachTextureIsBoundOnceAFrameSoBindsAreAtMostAtlasNodesPlusDistinctOriginalTextures) {
  const SharedTree& t = sharedTree(false);
  size_t framesOverTheBoundBefore = 0, framesWithOriginals = 0;
  for (RenderMode mode : {RenderMode::AtlasTree, RenderMode::Original})
    for (const ViewParams& v : drawOrderViews(t.tree->meta())) {
      const FramePlan leafByLeaf = plan(t, v, mode);
      std::set<int32_t> originals;
      bool white = false;
      for (const PlannedDraw& d : leafByLeaf.draws) {
        if (d.source == DrawSource::Original) originals.insert(d.texture);
        white |= d.source == DrawSource::Untextured;
      }
      // Each scene texture of this scene has its own image, so distinct textures are distinct binds.
      const uint64_t bound = leafByLeaf.atlasNodes + originals.size() + (white ? 1 : 0);
      const Executed before = execute(t, leafByLeaf, v), after = execute(t, grouped(leafByLeaf), v);
      EXPECT_LE(after.counters.texture_binds, bound) << renderModeName(mode);
      const std::set<ResourceId> distinct(after.bound.begin(), after.bound.end());
      EXPECT_EQ(distinct.size(), after.bound.size()) << "a texture was bound twice in one frame";
      EXPECT_EQ(after.counters.texture_binds, after.bound.size());
      EXPECT_LE(after.counters.draw_calls, before.counters.draw_calls);
      framesOverTheBoundBefore += before.counters.texture_binds > bound;
      framesWithOriginals += originals.size() > 1;
    }
  EXPECT_GT(framesWithOriginals, 5u);
  EXPECT_GT(framesOverTheBoundBefore, 5u) << "leaf by leaf, the scene should bind shared textures again";
}

TEST(DrawOrder, WithoutDepthTiesTheGroupedFrameIsByteIdenticalToTheLeafByLeafFrame) {
  const SharedTree& t = sharedTree(false);
  size_t reordered = 0, coveredPixels = 0;
  for (RenderMode mode : {RenderMode::AtlasTree, RenderMode::Original})
    for (const ViewParams& v : drawOrderViews(t.tree->meta())) {
      const FramePlan leafByLeaf = plan(t, v, mode), g = grouped(leafByLeaf);
      if (sameDraws(g, leafByLeaf)) continue;
      ++reordered;
      const Executed before = execute(t, leafByLeaf, v), after = execute(t, g, v);
      EXPECT_EQ(after.color, before.color) << renderModeName(mode);
      EXPECT_EQ(after.depth, before.depth);
      EXPECT_EQ(after.ids, before.ids);
      for (size_t i = 0; i < after.ids.size() / 4; ++i) coveredPixels += pixelId(after.ids, i) != 0xffffffffu;
    }
  EXPECT_GT(reordered, 5u);
  EXPECT_GT(coveredPixels, 50000u) << "the frames should show the scene";
}

// Depth is the least of a pixel's fragments in any order, so the depth buffers must be equal, and a
// pixel's colour may differ only where the winning triangle differs: both winners then have the pixel's
// final depth, a tie. Returns the pixels whose colour differs.
size_t colourChangesAtDepthTiesOnly(const Executed& before, const Executed& after, const std::string& what) {
  EXPECT_EQ(after.depth, before.depth) << what << ": the depth buffer changed";
  size_t changed = 0, unexplained = 0;
  for (size_t p = 0; p < after.color.size() / 4; ++p) {
    const bool colour = !std::equal(&after.color[p * 4], &after.color[p * 4] + 4, &before.color[p * 4]);
    changed += colour;
    unexplained += colour && pixelId(after.ids, p) == pixelId(before.ids, p);
  }
  EXPECT_EQ(unexplained, 0u) << what << ": pixels changed colour with the same triangle on top";
  return changed;
}

TEST(DrawOrder, WhereFragmentsTieInDepthOnlyTheWinnerCanChangeAndTheDepthBufferNever) {
  // With decals lying on the wall, the winner of a tied pixel is the first fragment drawn at that depth,
  // so the order can change it.
  const SharedTree& t = sharedTree(true);
  size_t reordered = 0, colourChanged = 0;
  for (RenderMode mode : {RenderMode::AtlasTree, RenderMode::Original})
    for (const ViewParams& v : drawOrderViews(t.tree->meta())) {
      const FramePlan leafByLeaf = plan(t, v, mode), g = grouped(leafByLeaf);
      if (sameDraws(g, leafByLeaf)) continue;
      ++reordered;
      colourChanged += colourChangesAtDepthTiesOnly(execute(t, leafByLeaf, v), execute(t, g, v), renderModeName(mode));
    }
  EXPECT_GT(reordered, 5u);
  EXPECT_GT(colourChanged, 0u) << "the decals should tie with the wall somewhere the order changed";
}

// railway.glb as the goldens and the issue measured it (d_min 5, the thesis path, 60 frames), at 320x240
// with the CLI's default capacity and budget: every frame binds each texture once, and every pixel that
// the grouping changes is a depth tie.
TEST(DrawOrder, OnRailwayEachTextureIsBoundOnceAndOnlyPixelsWhereTrianglesTieInDepthChange) {
  const std::string model = std::string(TESSERA_SOURCE_DIR) + "/data/railway.glb";
  ASSERT_TRUE(std::filesystem::exists(model)) << model << " is missing";  // part of the repository
  TempFile tree("railway.mta");
  BuildParams bp;
  bp.dMin = 5.0;
  buildMta(sceneFromModel(std::make_shared<const model::Model>(model::loadModel(model))), bp, tree.path);
  const PagingFile file(tree.path);
  RendererOptions o;
  o.width = 320;
  o.height = 240;
  o.threads = 2;
  o.residency.capacityBytes = uint64_t(100) << 20;
  o.residency.budget = LoadBudget::parse("8MiB", "budget");
  o.groupBinds = false;  // the renderer's plan is the leaf-by-leaf one; both orders are recorded below
  TreeRenderer renderer(file, o);
  TextureCache textures(file, nullptr);
  Runner runner;
  size_t reordered = 0, bindsSaved = 0, colourChanged = 0;
  for (const Camera& c : builtinPathOverTree("thesis", file.meta(), 60).frames) {
    const FrameResult r = renderer.renderFrame(c);
    const FramePlan g = grouped(r.plan);
    if (sameDraws(g, r.plan)) continue;
    ++reordered;
    const ViewParams v = renderer.view(c);
    const Executed before = runner.run(file, renderer.geometry(), textures, r.plan, v),
                   after = runner.run(file, renderer.geometry(), textures, g, v);
    EXPECT_EQ(before.color, r.image) << "frame " << r.frame << ": the test records the frame as the renderer does";
    const std::set<ResourceId> distinct(after.bound.begin(), after.bound.end());
    EXPECT_EQ(distinct.size(), after.bound.size()) << "frame " << r.frame << ": a texture was bound twice";
    bindsSaved += before.counters.texture_binds - after.counters.texture_binds;
    colourChanged += colourChangesAtDepthTiesOnly(before, after, "frame " + std::to_string(r.frame));
  }
  EXPECT_GT(reordered, 30u);
  EXPECT_GT(bindsSaved, 1000u) << "leaf by leaf, railway binds its shared textures again and again";
  // Not asserted: how many tied pixels railway has depends on the build (12 at 320x240 when written; 138 at
  // 640x480, docs/mta-render.md). The decal scene above makes sure that ties are met and checked.
  RecordProperty("pixels_changed_at_depth_ties", std::to_string(colourChanged));
}

}  // namespace
}  // namespace tessera::mta
