// The atlas tree at run time: the memory manager's invariants over a whole path (§4.6), the rendering
// traversal's fallback (Figure 30), the comparison runs, determinism, and the texel guarantee.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <variant>

#include "mta/build.h"
#include "mta/texel_ratio.h"
#include "mta/tree_renderer.h"
#include "raster/bc_decode.h"
#include "raster/cpu_backend.h"
#include "base/sha256.h"
#include "mta_test_scene.h"
#include "wall_tree_file.h"

namespace tessera::mta {
namespace {

using testing::gridScene;
using testing::smallTreeParams;
using testing::TempFile;

using testing::fixture;
using testing::rawFixture;

// Approach the wall from far away, then pan along it close up, then pull back.
std::vector<Camera> path() {
  std::vector<Camera> cams;
  for (int i = 0; i < 48; ++i) {
    Camera c;
    const double t = i / 47.0;
    double x = 6.0, z = 40.0 - 38.0 * (t < 0.5 ? 2 * t : 1.0);
    if (t >= 0.5) x = 1.0 + 10.0 * (t - 0.5) * 2.0;
    if (i > 40) z = 2.0 + 4.0 * (i - 40);
    c.eye = {x, 6.0, z};
    c.target = {x, 6.0, 0.0};
    c.tanHalfFovX = fixture().tree->meta().params.tanHalfFov;
    c.nearPlane = 0.05;
    c.farPlane = 200.0;
    cams.push_back(c);
  }
  return cams;
}

RendererOptions runtimeOptions(uint64_t capacity, LoadBudget budget) {
  RendererOptions o;
  o.width = 128;
  o.height = 96;
  o.threads = 2;
  o.residency.capacityBytes = capacity;
  o.residency.budget = budget;
  o.residency.maxQueue = 8;
  return o;
}

// Every ideal block is loaded before each frame is drawn (the guarantee's precondition).
RendererOptions everythingResident() {
  LoadBudget b;
  b.kind = LoadBudget::Kind::Blocks;
  b.perFrame = UINT64_MAX;
  RendererOptions o = runtimeOptions(uint64_t(1) << 32, b);
  o.residency.maxQueue = UINT32_MAX;
  return o;
}

// One stored atlas of the fixture's RGB tree: the BC1 mip chain of an A x A atlas, 8 bytes per 4 x 4 block
// of every level down to 1 x 1 (a level below 4 x 4 is one block). Capacity counts these bytes.
uint64_t atlasBytes() {
  const MtaMeta& m = fixture().tree->meta();
  uint64_t bytes = 0;
  for (uint64_t s = m.params.atlasSize;; s /= 2) {
    bytes += ((s + 3) / 4) * ((s + 3) / 4) * 8;
    if (s == 1) break;
  }
  return bytes;
}

TEST(Residency, CapacityIsNeverExceededAndTheRootAtlasStaysResident) {
  const PagingFile& f = *fixture().tree;
  ASSERT_GT(f.meta().trees[0].nodes.size(), 20u) << "the fixture should give a deep tree";
  LoadBudget b;
  b.kind = LoadBudget::Kind::Blocks;
  b.perFrame = 2;
  TreeRenderer r(f, runtimeOptions(atlasBytes() * 7, b));
  const uint32_t root = f.meta().trees[0].atlasBlocks[0];
  uint64_t evicted = 0;
  for (const Camera& c : path()) {
    const FrameResult fr = r.renderFrame(c);
    EXPECT_LE(fr.bytesResident, fr.capacityBytes) << "frame " << fr.frame;
    EXPECT_TRUE(r.residency()->resident(root)) << "frame " << fr.frame;
    evicted += fr.residency.blocksEvicted;
  }
  EXPECT_LE(r.residency()->peakBytesResident(), atlasBytes() * 7);
  EXPECT_GT(evicted, 0u) << "the capacity should be tight enough to force evictions";
}

TEST(Residency, DecodedBytesResidentHoldEveryChainTheFrameUploadsAndOnlyThoseOnTheFirstFrame) {
  // Raw blocks: what is uploaded is the decoded RGBA8 chain itself.
  const PagingFile& f = *rawFixture().tree;
  LoadBudget b;
  b.kind = LoadBudget::Kind::Blocks;
  b.perFrame = 2;
  const uint64_t rawAtlas = uint64_t(f.meta().params.atlasSize) * f.meta().params.atlasSize * 3;
  TreeRenderer r(f, runtimeOptions(rawAtlas * 7, b));
  bool first = true;
  for (const Camera& c : path()) {
    const FrameResult fr = r.renderFrame(c);
    // Every texture a frame draws is uploaded once, from a chain the cache holds (the untextured draws'
    // 1 x 1 white texture, 4 bytes, is the one upload that is not a cached chain). Before the first frame
    // the cache is empty, so then the cached chains are exactly the uploaded ones.
    const uint64_t uploaded = fr.counters.texture_bytes_uploaded;
    ASSERT_GT(uploaded, 4u) << "frame " << fr.frame;
    EXPECT_GE(fr.decodedBytesResident + 4, uploaded) << "frame " << fr.frame;
    if (first) { EXPECT_LE(fr.decodedBytesResident, uploaded) << "frame " << fr.frame; }
    first = false;
  }
}

TEST(Residency, BlocksAreLoadedInPriorityOrderWithinEachFrame) {
  const PagingFile& f = *fixture().tree;
  LoadBudget b;
  b.kind = LoadBudget::Kind::Blocks;
  b.perFrame = 3;
  ResidencyOptions ro;
  ro.capacityBytes = atlasBytes() * 12;
  ro.budget = b;
  ro.maxQueue = 6;
  Residency res(f, ro);
  const BlockIndex index = buildBlockIndex(f.meta(), kRecordedLayers);
  ViewParams v;
  v.width = 128;
  v.height = 96;
  size_t framesWithSeveralLoads = 0;
  for (const Camera& c : path()) {
    v.camera = c;
    const auto pr = usagePriorities(f.meta(), index, makeViewContext(f.meta(), v));
    const ResidencyFrameStats& s = res.update(pr);
    framesWithSeveralLoads += s.loadOrder.size() >= 2;
    for (size_t i = 1; i < s.loadOrder.size(); ++i)
      EXPECT_FALSE(morePressing(pr[s.loadOrder[i]], s.loadOrder[i], pr[s.loadOrder[i - 1]], s.loadOrder[i - 1]))
          << "a more pressing block was loaded after a less pressing one";
    for (uint32_t blk : s.loadOrder) EXPECT_NE(pr[blk].usage, Usage::Unused);
    EXPECT_LE(res.bytesResident(), ro.capacityBytes);
  }
  EXPECT_GT(framesWithSeveralLoads, 0u) << "no frame loaded two blocks, so the order was never checked";
}

TEST(Residency, TheBackgroundLoaderKeepsTheSameInvariants) {
  // The wall-clock mode is not reproducible, but capacity and root residency hold all the same.
  const PagingFile& f = *fixture().tree;
  LoadBudget b;
  b.kind = LoadBudget::Kind::Time;
  b.slotMs = 2.0;
  TreeRenderer r(f, runtimeOptions(atlasBytes() * 7, b));
  const uint32_t root = f.meta().trees[0].atlasBlocks[0];
  uint64_t loaded = 0;
  for (const Camera& c : path()) {
    const FrameResult fr = r.renderFrame(c);
    EXPECT_LE(fr.bytesResident, fr.capacityBytes);
    EXPECT_TRUE(r.residency()->resident(root));
    loaded += fr.residency.blocksLoaded;
  }
  EXPECT_GT(loaded, 0u);
}

TEST(Residency, BudgetParsingNamesTheOptionAndTheUnit) {
  EXPECT_EQ(LoadBudget::parse("8MiB", "--budget").perFrame, 8u << 20);
  EXPECT_EQ(LoadBudget::parse("4blocks", "--budget").kind, LoadBudget::Kind::Blocks);
  EXPECT_EQ(LoadBudget::parse("5ms", "--budget").kind, LoadBudget::Kind::Time);
  try {
    LoadBudget::parse("8 furlongs", "--budget");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--budget"), std::string::npos);
  }
  EXPECT_THROW(LoadBudget::parse("-3", "--budget"), Error);
}

TEST(Residency, ACapacityBelowTheRootAtlasIsRefused) {
  ResidencyOptions ro;
  ro.capacityBytes = atlasBytes() - 1;
  EXPECT_THROW(Residency(*fixture().tree, ro), Error);
}

// S3TC: capacity and bytes resident count the compressed blocks (the thesis's k), so a capacity of exactly
// one compressed root atlas holds it, and holding it costs those bytes, far below its raw A² · 3.
TEST(Residency, CapacityAndBytesResidentCountCompressedBlockBytes) {
  const PagingFile& f = *fixture().tree;
  ASSERT_EQ(f.meta().encoding, BlockEncoding::S3tc);
  LoadBudget b;
  b.kind = LoadBudget::Kind::Blocks;
  b.perFrame = 1;
  TreeRenderer r(f, runtimeOptions(atlasBytes(), b));
  const FrameResult fr = r.renderFrame(path().front());
  EXPECT_EQ(fr.capacityBytes, atlasBytes());
  EXPECT_EQ(fr.bytesResident, atlasBytes());
  EXPECT_EQ(fr.blocksResident, 1u);
  EXPECT_LT(atlasBytes(), uint64_t(f.meta().params.atlasSize) * f.meta().params.atlasSize * 3 / 4);
}

// The list `cl` with every S3TC texture replaced by its decoded RGBA8 levels (raster/bc_decode.h called
// here, outside the backend): the textures the oracle should have sampled. Every command that carries blob
// bytes (texture, buffer and uniform uploads) is copied with its bytes.
CommandList withDecodedTextures(const CommandList& cl) {
  CommandList out;
  std::map<ResourceId, TextureDesc> compressed;
  for (const Command& c : cl.commands()) {
    if (const auto* ct = std::get_if<CreateTexture>(&c); ct && ct->desc.compression != BcFormat::None) {
      compressed[ct->id] = ct->desc;
      CreateTexture plain = *ct;
      plain.desc.compression = BcFormat::None;
      out.appendRaw(plain);
    } else if (const auto* up = std::get_if<UploadTexture>(&c)) {
      UploadTexture u = *up;
      const auto it = compressed.find(up->id);
      if (it == compressed.end()) {
        u.data = out.appendBlob(cl.bytes(up->data));
      } else {
        const TextureDesc& d = it->second;
        u.data = out.appendBlob(decodeBcLevel(d.compression, levelWidth(d, up->level), levelHeight(d, up->level),
                                              cl.bytes(up->data)));
      }
      out.appendRaw(u);
    } else if (const auto* ub = std::get_if<UploadBuffer>(&c)) {
      UploadBuffer u = *ub;
      u.data = out.appendBlob(cl.bytes(ub->data));
      out.appendRaw(u);
    } else if (const auto* su = std::get_if<SetUniforms>(&c)) {
      SetUniforms u = *su;
      u.data = out.appendBlob(cl.bytes(su->data));
      out.appendRaw(u);
    } else {
      out.appendRaw(c);
    }
  }
  out.setNextId(cl.nextId());
  return out;
}

// The S3TC frames upload compressed textures, and what the oracle draws from them is exactly what it draws
// from the same textures decoded beforehand: decoding is the only step between the blocks and sampling.
TEST(TreeRenderer, ACompressedFrameEqualsTheFrameDrawnFromTheSameTreesDecodedTextures) {
  TreeRenderer r(*fixture().tree, everythingResident());
  size_t compared = 0;
  for (const Camera& c : path()) {
    const FrameResult fr = r.renderFrame(c);
    size_t compressedTextures = 0;
    for (const Command& cmd : r.lastList().commands())
      if (const auto* ct = std::get_if<CreateTexture>(&cmd)) compressedTextures += ct->desc.compression != BcFormat::None;
    ASSERT_GT(compressedTextures, 0u) << "frame " << fr.frame;
    CpuBackend oracle;
    oracle.execute(withDecodedTextures(r.lastList()), "decoded");
    EXPECT_TRUE(oracle.texture(oracle.presented().at(0).texture)->levels[0] == fr.image) << "frame " << fr.frame;
    ++compared;
  }
  EXPECT_GT(compared, 0u);
}

// Same blocks resident (a block budget and room for all): the S3TC run's cached chains decode to exactly
// the raw run's RGBA8 chains, texture for texture, so the decoded bytes agree frame by frame.
TEST(Residency, DecodedBytesResidentOfAnS3tcTreeEqualTheRawTreesChainBytes) {
  TreeRenderer s3tc(*fixture().tree, everythingResident()), raw(*rawFixture().tree, everythingResident());
  size_t frames = 0;
  for (const Camera& c : path()) {
    const FrameResult a = s3tc.renderFrame(c), b = raw.renderFrame(c);
    ASSERT_GT(b.decodedBytesResident, 0u);
    EXPECT_EQ(a.decodedBytesResident, b.decodedBytesResident) << "frame " << a.frame;
    EXPECT_LT(a.counters.texture_bytes_uploaded, b.counters.texture_bytes_uploaded) << "frame " << a.frame;
    ++frames;
  }
  EXPECT_GT(frames, 0u);
}

TEST(TreeRenderer, WithOnlyTheRootInMemoryEverythingIsDrawnWithTheRootAtlas) {
  const PagingFile& f = *fixture().tree;
  LoadBudget b;
  b.kind = LoadBudget::Kind::Blocks;
  b.perFrame = 1;
  TreeRenderer r(f, runtimeOptions(atlasBytes(), b));  // room for the root alone: nothing can ever be loaded
  const Camera close = path()[23];
  const FrameResult fr = r.renderFrame(close);
  EXPECT_EQ(fr.plan.atlasNodes, 1u);
  EXPECT_EQ(fr.plan.coarserThanNeeded, 1u);
  EXPECT_EQ(fr.counters.texture_state_changes, 1u);
  EXPECT_GT(fr.plan.trianglesDrawn, 0u);
}

TEST(TreeRenderer, WithAnUnlimitedBudgetNoNeededBlockIsMissing) {
  const PagingFile& f = *fixture().tree;
  const RendererOptions o = everythingResident();
  TreeRenderer r(f, o);
  bool sawOriginals = false, sawInner = false;
  for (const Camera& c : path()) {
    const FrameResult fr = r.renderFrame(c);
    EXPECT_EQ(fr.residency.neededMissing, 0u) << "frame " << fr.frame;
    EXPECT_EQ(fr.plan.coarserThanNeeded, 0u) << "frame " << fr.frame;
    sawOriginals |= fr.plan.originalLeaves > 0;
    sawInner |= fr.plan.atlasNodes > 0 && fr.plan.originalLeaves == 0;
  }
  EXPECT_TRUE(sawOriginals) << "the close-up frames should refine to original textures";
  EXPECT_TRUE(sawInner);
}

TEST(TreeRenderer, TheThreeRunsDrawExactlyTheSameTriangles) {
  const PagingFile& f = *fixture().tree;
  LoadBudget b;
  b.kind = LoadBudget::Kind::Blocks;
  b.perFrame = 2;
  RendererOptions atlas = runtimeOptions(atlasBytes() * 8, b), orig = atlas, dummy = atlas;
  orig.mode = RenderMode::Original;
  dummy.mode = RenderMode::Dummy;
  TreeRenderer ra(f, atlas), ro(f, orig), rd(f, dummy);
  for (const Camera& c : path()) {
    const FrameResult a = ra.renderFrame(c), o = ro.renderFrame(c), d = rd.renderFrame(c);
    EXPECT_EQ(a.plan.trianglesDrawn, o.plan.trianglesDrawn);
    EXPECT_EQ(d.plan.trianglesDrawn, o.plan.trianglesDrawn);
    EXPECT_LE(d.counters.texture_state_changes, 1u);
    EXPECT_LE(d.counters.draw_calls, o.counters.draw_calls);
  }
}

std::vector<std::string> imageHashes(int threads, LoadBudget b) {
  RendererOptions o = runtimeOptions(atlasBytes() * 8, b);
  o.threads = threads;
  TreeRenderer r(*fixture().tree, o);
  std::vector<std::string> h;
  for (const Camera& c : path()) h.push_back(sha256Hex(r.renderFrame(c).image));
  return h;
}

TEST(TreeRenderer, DeterministicBudgetsGiveTheSameFramesForAnyThreadCount) {
  LoadBudget b;
  b.kind = LoadBudget::Kind::Bytes;
  b.perFrame = atlasBytes() / 2;  // a block takes two frames
  const auto one = imageHashes(1, b);
  EXPECT_EQ(one, imageHashes(2, b));
  EXPECT_EQ(one, imageHashes(5, b));
  EXPECT_EQ(std::set<std::string>(one.begin(), one.end()).size() > 10, true) << "the path should change the image";
}

// Run 1 uploads every visible leaf's originals, which a big city makes several GiB: the frame budget is
// the renderer's option, and the error names the run and the frame.
TEST(TreeRenderer, TheFrameMemoryBudgetIsAnOptionAndItsErrorNamesTheRunAndFrame) {
  RendererOptions o = everythingResident();
  o.mode = RenderMode::Original;
  o.limits.frameBytes = 64 * 1024;
  TreeRenderer r(*fixture().tree, o);
  try {
    r.renderFrame(path()[23]);
    FAIL() << "a frame over 64 KiB was drawn";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("original run, frame 0"), std::string::npos) << m;
    EXPECT_NE(m.find("--memory-budget"), std::string::npos) << m;
  }
  o.limits.frameBytes = uint64_t(1) << 32;
  TreeRenderer roomy(*fixture().tree, o);
  EXPECT_GT(roomy.renderFrame(path()[23]).plan.originalLeaves, 0u);
}

TEST(TexelAnalysis, NoAtlasPixelMagnifiesBeyondTauWhenEveryNeededBlockIsResident) {
  const PagingFile& f = *fixture().tree;
  const RendererOptions o = everythingResident();
  TreeRenderer r(f, o);
  uint64_t atlasPixels = 0;
  for (const Camera& c : path()) {
    const FrameResult fr = r.renderFrame(c);
    const TexelFrame t = analyzeTexels(r, c, fr, r.triangleIds(c, fr.plan), f.meta().params.tau);
    EXPECT_EQ(t.magnificationViolations, 0u) << "frame " << fr.frame << ", max ratio " << t.maxAtlasRatioBase;
    // The wall's textures are mapped without stretch, so a texel is as long on screen along s and t.
    EXPECT_EQ(t.perAxisViolations, 0u) << "frame " << fr.frame << ", max per axis " << t.maxAtlasAxisBase;
    atlasPixels += t.pixelsAtlas;
  }
  EXPECT_GT(atlasPixels, 10000u);
}

// The per-node bound passes the distance test wherever the corner ray's does (its factor is never
// smaller), so it stops the traversal at the same node or above: never more draws; over the path fewer
// nodes, and the guarantee still holds.
TEST(TexelAnalysis, ThePerNodeBoundDrawsFewerNodesThanTheCornerRayAndKeepsTheGuarantee) {
  const PagingFile& f = *fixture().tree;
  RendererOptions corner = everythingResident(), node = everythingResident();
  corner.bound = DistanceBound::FrameCorner;
  node.bound = DistanceBound::PerNode;
  TreeRenderer rc(f, corner), rn(f, node);
  uint64_t nodesCorner = 0, nodesNode = 0;
  for (const Camera& c : path()) {
    const FrameResult a = rc.renderFrame(c), b = rn.renderFrame(c);
    EXPECT_LE(b.plan.atlasNodes + b.plan.originalLeaves, a.plan.atlasNodes + a.plan.originalLeaves) << "frame " << a.frame;
    nodesCorner += a.plan.atlasNodes + a.plan.originalLeaves;
    nodesNode += b.plan.atlasNodes + b.plan.originalLeaves;
    const TexelFrame t = analyzeTexels(rn, c, b, rn.triangleIds(c, b.plan), f.meta().params.tau);
    EXPECT_EQ(t.magnificationViolations, 0u) << "frame " << b.frame;
  }
  EXPECT_LT(nodesNode, nodesCorner);
}

TEST(TexelAnalysis, AFrameDrawnWithTheRootAloneReportsViolationsUpClose) {
  const PagingFile& f = *fixture().tree;
  LoadBudget b;
  b.kind = LoadBudget::Kind::Blocks;
  b.perFrame = 1;
  TreeRenderer r(f, runtimeOptions(atlasBytes(), b));
  const Camera close = path()[23];
  const FrameResult fr = r.renderFrame(close);
  const TexelFrame t = analyzeTexels(r, close, fr, r.triangleIds(close, fr.plan), f.meta().params.tau);
  EXPECT_GT(t.magnificationViolations, 1000u);
  EXPECT_GT(t.perAxisViolations, 1000u);
  EXPECT_EQ(t.pixelsOriginal, 0u);
}

// s runs over 4 times as many texels as t across each quad: seen head-on, a texel is 4 times longer on
// screen along t than GL's ρ (the longer screen-axis derivative, along s) says, at every level sampled.
TEST(TexelAnalysis, AStretchedTextureSpansFourTimesMorePixelsAlongOneEdgeThanRhoSays) {
  Scene scene = gridScene(4, 4, 32, 1.0f);
  for (glm::vec2& uv : scene.geometry.layers[0].uv) uv.x *= 4.0f;
  TempFile file{"stretched.mta"};
  BuildParams p = smallTreeParams();
  buildMta(scene, p, file.path);
  const PagingFile f(file.path);
  RendererOptions o = everythingResident();
  o.mode = RenderMode::Original;
  TreeRenderer r(f, o);
  Camera c;
  c.eye = {2.0, 2.0, 12.0};
  c.target = {2.0, 2.0, 0.0};
  c.tanHalfFovX = 0.5;
  c.nearPlane = 0.05;
  c.farPlane = 100.0;
  const FrameResult fr = r.renderFrame(c);
  const TexelFrame t = analyzeTexels(r, c, fr, r.triangleIds(c, fr.plan), f.meta().params.tau);
  uint64_t pixels = 0, belowLevel0 = 0;
  for (size_t i = 0; i < t.ratio.size(); ++i) {
    if (t.source[i] != 2) continue;
    ++pixels;
    if (t.ratio[i] != t.ratioBase[i]) ++belowLevel0;
    EXPECT_NEAR(t.axisRatio[i] / t.ratio[i], 4.0, 0.01) << "pixel " << i;
  }
  EXPECT_GT(pixels, 1000u);
  EXPECT_GT(belowLevel0, 1000u) << "the view should sample below level 0";
  EXPECT_EQ(t.perAxisViolations, 0u) << "original textures never count as violations";
}

// Quad 5 of the grid gets collinear texcoords (every v the same): its texels are lines, infinitely long on
// screen across them. Its atlas pixels are counted apart and stay out of the per-axis maximum, which then
// stays what the other quads give.
TEST(TexelAnalysis, AtlasPixelsOfCollinearTexcoordsAreCountedApartFromThePerAxisMaximum) {
  Scene scene = gridScene(4, 4, 32, 1.0f);
  for (int k = 5 * 6; k < 6 * 6; ++k) scene.geometry.layers[0].uv[size_t(k)].y = 0.25f;
  TempFile file{"collinear.mta"};
  BuildParams p = smallTreeParams();
  buildMta(scene, p, file.path);
  const PagingFile f(file.path);
  TreeRenderer r(f, everythingResident());
  Camera c;
  c.eye = {2.0, 2.0, 16.0};  // far enough that the quads are drawn with atlases
  c.target = {2.0, 2.0, 0.0};
  c.tanHalfFovX = 0.5;
  c.nearPlane = 0.05;
  c.farPlane = 100.0;
  const FrameResult fr = r.renderFrame(c);
  ASSERT_GT(fr.plan.atlasNodes, 0u);
  const TexelFrame t = analyzeTexels(r, c, fr, r.triangleIds(c, fr.plan), f.meta().params.tau);
  EXPECT_GT(t.atlasPixelsDegenerateTexcoords, 20u) << t.pixelsAtlas << " atlas pixels, " << t.pixelsOriginal << " original";
  EXPECT_LT(t.atlasPixelsDegenerateTexcoords, t.pixelsAtlas / 8) << "one quad of 16";
  EXPECT_GT(t.maxAtlasAxisBase, 0.0);
  EXPECT_LT(t.maxAtlasAxisBase, 16.0 * t.maxAtlasRatioBase) << "the other quads' texels are square";
}

TEST(TexelAnalysis, RatioBinsAreThePowersOfTheSquareRootOfTwo) {
  EXPECT_EQ(ratioBinLower(0), 0.0);
  EXPECT_EQ(ratioBinLower(1), 0.25);
  EXPECT_EQ(ratioBinLower(5), 1.0);
  EXPECT_EQ(ratioBinLower(7), 2.0);
  EXPECT_EQ(ratioBinLower(11), 8.0);
  EXPECT_NEAR(ratioBinLower(6), 1.4142135623730951, 1e-15);
}

}  // namespace
}  // namespace tessera::mta
