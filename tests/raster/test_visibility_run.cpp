// Visibility runs (raster/rast.cpp): consecutive triangles without blending, discard or gl_FragDepth
// are walked for coverage and depth first, and only the fragments still visible at the run's end are
// shaded. The bytes and every counter must be the immediate walk's, which the "reference" SIMD target
// takes (it has no interpolation kernels, so no triangle joins a run). Uploads flush only when
// unexecuted work reads what they write (raster/cpu_backend.cpp), and tiles_rasterized keeps counting
// bins per upload segment.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "raster/simd_targets.h"
#include "tests/raster/render_helpers.h"
#include "tools/scenes/builder.h"
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {
using tessera::testing::expectBestTargetGivesReferenceFrame;
using tessera::testing::Rendered;
using tessera::testing::renderList;

namespace {

// An odd size: two by two tiles, the right and top ones partial, with quads past the last column and row.
constexpr int kW = 97, kH = 79;

// What can break a run, or must be handled inside one, at layer `i` of the frame.
struct Layers {
  bool depthTest = true;
  int noDepthWrite = -1;  // this layer passes the test but does not write depth
  int discard = -1;       // this layer discards (alpha cutoff 0.9; its filtered alpha is 0.16 to 1)
  int blend = -1;         // this layer blends (source over)
  bool uploads = false;   // an unrelated texture upload, then a re-upload of layer 0's texture, mid-frame
};

// Six full-target textured layers (two triangles each, so quads on the diagonal hold pixels of both)
// at depths that make some later layers hidden and some visible, each with its own texture and
// texture scale, trilinear; then a smaller tilted triangle in front over part of them.
CommandList layeredFrame(const Layers& o) {
  CommandList cl;
  RenderTarget t;
  t.color[0] = createTarget(cl, Format::RGBA8, kW, kH);
  t.depth = createTarget(cl, Format::D32F, kW, kH);
  cl.setRenderTarget(t);
  cl.setViewport({0, 0, kW, kH});
  cl.clearColor(0, {0.1f, 0.2f, 0.3f, 1});
  cl.clearDepth(1.0f);
  const float z[6] = {0.5f, 0.7f, 0.2f, 0.3f, -0.4f, 0.1f};
  Mesh m;
  for (int i = 0; i < 6; ++i)
    m.quad({-1, -1, z[i]}, {1, -1, z[i]}, {1, 1, z[i]}, {-1, 1, z[i]}, {0, 0, 0, 0}, {3 + i, 0, 0, 0}, {3 + i, 2 + i, 0, 0},
           {0, 2 + i, 0, 0});
  m.triangle({{-0.8f, -0.9f, -0.9f}, {0, 0, 0, 0}, 0}, {{0.9f, -0.2f, -0.9f}, {5, 0, 0, 0}, 0},
             {{-0.3f, 0.95f, -0.9f}, {0, 5, 0, 0}, 0});
  bindMesh(cl, m);
  cl.useProgram(cl.createProgram("textured"));
  setMatrix(cl, 0, glm::mat4(1.0f));
  setTexturedDefaults(cl);
  SamplerState s;
  s.minFilter = Filter::LinearMipmapLinear;
  cl.bindSampler(0, cl.createSampler(s));
  std::vector<ResourceId> tex;
  for (int i = 0; i < 7; ++i) {
    // Half the cells nearly transparent: the discarding layer keeps some fragments and drops others.
    tex.push_back(uploadTexture(cl, checker(32, 32, uint32_t(2 + i), {uint8_t(40 * i), 200, 90, 255},
                                            {250, uint8_t(30 * i), 60, 40}), true));
  }
  for (int i = 0; i < 7; ++i) {
    DepthState d;
    d.test = o.depthTest;
    d.write = i != o.noDepthWrite;
    cl.setDepthState(d);
    BlendState b;
    if (i == o.blend) {
      b.enabled = true;
      b.srcRgb = b.srcAlpha = BlendFactor::SrcAlpha;
      b.dstRgb = b.dstAlpha = BlendFactor::OneMinusSrcAlpha;
    }
    cl.setBlendState(b);
    setVec4(cl, 8, {0, i == o.discard ? 0.9f : 0.0f, 0, 0});
    if (o.uploads && i == 3) {
      uploadTexture(cl, checker(8, 8, 1, {1, 2, 3, 4}, {5, 6, 7, 8}), false);  // read by nothing: no flush
      const RgbaImage img = checker(32, 32, 5, {10, 20, 30, 255}, {200, 210, 220, 255});
      cl.uploadTexture(tex[0], 0, 0, img.rgba);  // layer 0 samples tex[0]: its level 0 changes after it ran
    }
    cl.bindTexture(0, tex[size_t(i)]);
    cl.drawIndexed(6 * uint32_t(i), i < 6 ? 6 : 3);
  }
  return cl;
}

// The frame's bytes and counters at 1, 2 and 7 threads on the best SIMD target are those of the
// "reference" target at 1 thread (the immediate walk); that reference run is returned.
Rendered expectImmediateBytesOf(const CommandList& cl, const std::string& what) {
  const Rendered immediate = expectBestTargetGivesReferenceFrame(cl, {1, 2, 7}, what);
  EXPECT_EQ(immediate.hashes.size(), 1u) << what;
  return immediate;
}

void expectImmediateBytes(const Layers& o, const std::string& what) {
  const Rendered immediate = expectImmediateBytesOf(layeredFrame(o), what);
  if (o.discard >= 0) {
    EXPECT_GT(immediate.stats.fragments_discarded, 0u) << what << ": the frame must discard";
  }
}

// Without a depth test, a Visibility walk over a box its triangle covers whole (TriangleRasterizer::
// visibleBox) fills the owner map and counts in closed form instead of walking blocks. On a 203 x 141
// target (tiles of 64: the last column and row partial, odd, with quads past the edge): three full-target
// layers (enough overlap that every tile walks a visibility run), large random triangles that cover
// some tiles whole, and triangles with a side exactly through pixel centres on a tile's edge, so that
// the fill rule decides whether a box is covered.
CommandList wholeTileFrame(bool depthAttachment, uint32_t seed) {
  constexpr int w = 203, h = 141;
  std::mt19937 rng(seed);
  const auto unit = [&]() { return float(rng() % 10001) / 10000.0f; };
  const auto colour = [&]() { return glm::vec4{unit(), unit(), unit(), 1.0f}; };
  Mesh m;
  const auto tri = [&](glm::vec2 a, glm::vec2 b, glm::vec2 c) {
    m.triangle({{a, 0}, colour(), 0}, {{b, 0}, colour(), 0}, {{c, 0}, colour(), 0});
  };
  for (int i = 0; i < 3; ++i)
    m.quad({0, 0, 0}, {w, 0, 0}, {w, h, 0}, {0, h, 0}, colour(), colour(), colour(), colour());
  for (int i = 0; i < 12; ++i) {
    const float x = unit() * w, y = unit() * h, size = 60.0f + unit() * 340.0f;
    const auto corner = [&]() { return glm::vec2{x + (unit() - 0.5f) * size, y + (unit() - 0.5f) * size}; };
    tri(corner(), corner(), corner());
  }
  // Last, so no later layer hides them: triangles reaching far past the target (inside the guard band)
  // with one side exactly through a row or column of pixel centres at a tile's edge. The fill rule
  // leaves out row 63 (a top edge) and column 127 (a right edge), so no box of those tiles is covered;
  // it keeps row 64 (a bottom edge) and column 128 (a left edge), so boxes of tiles there are.
  tri({-300, 63.5f}, {500, 63.5f}, {100, -500});
  tri({-300, 64.5f}, {100, 600}, {500, 64.5f});
  tri({127.5f, -500}, {127.5f, 600}, {-600, 70});
  tri({128.5f, -500}, {900, 70}, {128.5f, 600});
  // A left side between pixel centres at x = 193: boxes from column 193 (odd) to the last, 202 (even),
  // whose 2 x 2 quads are not half the box's width.
  tri({193.0f, -500}, {900, 70}, {193.0f, 600});
  CommandList cl;
  beginFrame(cl, w, h, depthAttachment, {0.5f, 0.25f, 0.75f, 1.0f});
  const uint32_t count = bindMesh(cl, m);
  cl.useProgram(cl.createProgram("vertex_color"));
  setMatrix(cl, 0, ortho(0, w, 0, h, -1, 1));
  cl.drawIndexed(0, count);
  return cl;
}

// A size x size RGBA8 target, bound, with its viewport, cleared to opaque black (LazyFlush's frames).
CommandList squareFrame(int size) {
  CommandList cl;
  RenderTarget t;
  t.color[0] = createTarget(cl, Format::RGBA8, size, size);
  cl.setRenderTarget(t);
  cl.setViewport({0, 0, size, size});
  cl.clearColor(0, {0, 0, 0, 1});
  return cl;
}

}  // namespace

TEST(VisibilityRun, HiddenLayersGiveTheImmediateWalksBytesAndCounters) {
  expectImmediateBytes({}, "depth test");
  expectImmediateBytes({.depthTest = false}, "no depth test (the last layer wins)");
  expectImmediateBytes({.noDepthWrite = 2}, "a layer without depth writes");
}

TEST(VisibilityRun, ADiscardingOrBlendingDrawEndsTheRunAndStillGetsTheImmediateBytes) {
  // A discarding layer that joined a run would own pixels whose fragments it then discards, and those
  // pixels would show the clear colour instead of the layer below.
  expectImmediateBytes({.discard = 4}, "discard in the middle");
  expectImmediateBytes({.blend = 4}, "blend in the middle");
  expectImmediateBytes({.noDepthWrite = 1, .discard = 4, .blend = 5}, "all three");
}

TEST(VisibilityRun, TrianglesCoveringWholeTilesWithoutADepthTestGiveTheImmediateBytes) {
  for (const uint32_t seed : {1u, 2u, 3u}) {
    for (const bool depthAttachment : {false, true}) {
      const std::string what = std::string(depthAttachment ? "depth attachment, test off" : "no depth attachment") +
                               ", seed " + std::to_string(seed);
      const Rendered r = expectImmediateBytesOf(wholeTileFrame(depthAttachment, seed), what);
      EXPECT_GT(r.stats.pixels_written, 4u * 203u * 141u) << what << ": the layers overlap (a visibility run per tile)";
    }
  }
}

TEST(VisibilityRun, UploadsMidFrameGiveTheImmediateBytes) {
  expectImmediateBytes({.uploads = true}, "uploads");
}

TEST(LazyFlush, AnUploadToATextureThatAnUnexecutedDrawSamplesLetsThatDrawSeeTheOldTexels) {
  // Left half: a draw samples texture T (one level, one colour); then T is uploaded with another colour
  // and the right half samples it. Each half must show the colour T had when its draw was issued.
  constexpr int kS = 64;
  CommandList cl = squareFrame(kS);
  Mesh m;
  m.quad({-1, -1, 0}, {0, -1, 0}, {0, 1, 0}, {-1, 1, 0}, {0, 0, 0, 0}, {1, 0, 0, 0}, {1, 1, 0, 0}, {0, 1, 0, 0});
  m.quad({0, -1, 0}, {1, -1, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0, 0}, {1, 0, 0, 0}, {1, 1, 0, 0}, {0, 1, 0, 0});
  bindMesh(cl, m);
  cl.useProgram(cl.createProgram("textured"));
  setMatrix(cl, 0, glm::mat4(1.0f));
  setTexturedDefaults(cl);
  const ResourceId tex = uploadTexture(cl, checker(4, 4, 4, {255, 0, 0, 255}, {255, 0, 0, 255}), false);
  cl.bindTexture(0, tex);
  cl.drawIndexed(0, 6);
  const RgbaImage green = checker(4, 4, 4, {0, 255, 0, 255}, {0, 255, 0, 255});
  cl.uploadTexture(tex, 0, 0, green.rgba);
  cl.drawIndexed(6, 6);
  for (int threads : {1, 2}) {
    const Rendered r = renderList(cl, threads);
    ASSERT_EQ(r.images.size(), 1u);
    const std::vector<uint8_t>& img = r.images[0];
    const size_t row = size_t(kS / 2) * kS * 4;
    const uint8_t* left = img.data() + row + size_t(kS / 4) * 4;
    const uint8_t* right = img.data() + row + size_t(3 * kS / 4) * 4;
    EXPECT_EQ(int(left[0]), 255) << threads << " threads: the left draw saw the new texels";
    EXPECT_EQ(int(left[1]), 0) << threads << " threads";
    EXPECT_EQ(int(right[0]), 0) << threads << " threads";
    EXPECT_EQ(int(right[1]), 255) << threads << " threads";
  }
}

TEST(LazyFlush, TilesRasterizedCountsTheBinsOfEachUploadSegmentAsBefore) {
  // 128 x 128 is four tiles. Clear (segment 1: 4 bins), an upload read by nothing, then a draw over
  // every tile (segment 2: 4 more), then an upload and a draw over the bottom-left tile only (1 more).
  // Before uploads flushed only when needed, each upload ended the scene, which gave these nine.
  constexpr int kS = 128;
  CommandList cl = squareFrame(kS);
  Mesh m;
  m.quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {}, {}, {}, {});
  m.quad({-0.9f, -0.9f, 0}, {-0.1f, -0.9f, 0}, {-0.1f, -0.1f, 0}, {-0.9f, -0.1f, 0}, {}, {}, {}, {});
  bindMesh(cl, m);
  cl.useProgram(cl.createProgram("flat_color"));
  setMatrix(cl, 0, glm::mat4(1.0f));
  setVec4(cl, 4, {1, 1, 0, 1});
  uploadTexture(cl, checker(4, 4, 1, {1, 2, 3, 4}, {5, 6, 7, 8}), false);
  cl.drawIndexed(0, 6);
  uploadTexture(cl, checker(4, 4, 1, {1, 2, 3, 4}, {5, 6, 7, 8}), false);
  cl.drawIndexed(6, 6);
  EXPECT_EQ(renderList(cl, 1).stats.tiles_rasterized, 9u);
  EXPECT_EQ(renderList(cl, 2).stats.tiles_rasterized, 9u);
}

}  // namespace tessera::scenes
