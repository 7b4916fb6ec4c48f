// The small-box walk (raster/rast.cpp, TriangleRasterizer::smallBox): a triangle whose box in the tile
// is at most 4x4 pixels inside one 8x8 block is tested pixel by pixel instead of through the block's
// trivial tests and the coverage kernel. The "reference" SIMD target walks every block, so the same
// frames there give the bytes and counters the small-box walk must reproduce: one-pixel triangles,
// and random small triangles with vertices on pixel centres and edges (the fill rule's ties), across
// block and tile edges, blended additively (a pixel covered twice or missed shows) and depth-tested.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "tests/raster/render_helpers.h"
#include "tools/scenes/builder.h"
#include "tools/scenes/sweep_scenes.h"

namespace tessera::scenes {
namespace {

using tessera::testing::expectBestTargetGivesReferenceFrame;

// `n` triangles of 0.1 to 5 px with random positions, half of them on the half-pixel grid (vertices
// on pixel centres: edges through them), at random depths; additive blending or a LESS depth test.
CommandList smallTriangles(int w, int h, int n, bool depth, uint32_t seed) {
  std::mt19937 rng(seed);
  const auto coord = [&](int extent) {
    return rng() % 2 ? float(rng() % uint32_t(2 * extent)) / 2.0f : float(rng() % uint32_t(extent * 256)) / 256.0f;
  };
  Mesh m;
  for (int i = 0; i < n; ++i) {
    const float x = coord(w), y = coord(h), z = float(int(rng() % 201) - 100) / 101.0f;
    const float size = float(rng() % 50 + 1) / 10.0f;
    const auto corner = [&]() {
      const float dx = (float(rng() % 1001) / 1000.0f) * size, dy = (float(rng() % 1001) / 1000.0f) * size;
      return Vertex{{x + (rng() % 2 ? dx : std::floor(dx * 2) / 2), y + dy, z}, {}, 0};
    };
    m.triangle(corner(), corner(), corner());
  }
  CommandList cl;
  RenderTarget t;
  t.color[0] = createTarget(cl, Format::RGBA8, w, h);
  if (depth) t.depth = createTarget(cl, Format::D32F, w, h);
  cl.setRenderTarget(t);
  cl.setViewport({0, 0, w, h});
  cl.clearColor(0, {0, 0, 0, 0});
  if (depth) cl.clearDepth(1.0f);
  const uint32_t count = bindMesh(cl, m);
  cl.useProgram(cl.createProgram("flat_color"));
  setMatrix(cl, 0, ortho(0, w, 0, h, -1, 1));
  setVec4(cl, 4, {0.25f, 0.125f, 0.5f, 0.25f});
  if (depth) {
    DepthState d;
    d.test = true;
    d.func = CompareFunc::Less;
    cl.setDepthState(d);
  } else {
    BlendState b;
    b.enabled = true;
    b.srcRgb = b.dstRgb = b.srcAlpha = b.dstAlpha = BlendFactor::One;
    cl.setBlendState(b);
  }
  cl.drawIndexed(0, count);
  return cl;
}

// The frame on the best target, at 1 and 7 threads, gives the reference target's bytes and counters.
void expectReferenceFrame(const CommandList& cl, const std::string& what) {
  expectBestTargetGivesReferenceFrame(cl, {1, 7}, what);
}

}  // namespace

TEST(SmallBox, OnePixelTrianglesGiveTheBlockWalksBytesAndCounters) {
  expectReferenceFrame(buildTinyTris(256, 256, 40000), "tiny_tris 40k");
}

TEST(SmallBox, SmallTrianglesOnPixelCentresAndBlockEdgesGiveTheBlockWalksBytes) {
  for (const uint32_t seed : {1u, 2u, 3u}) {
    expectReferenceFrame(smallTriangles(150, 90, 6000, false, seed), "additive, seed " + std::to_string(seed));
    expectReferenceFrame(smallTriangles(150, 90, 6000, true, seed), "depth LESS, seed " + std::to_string(seed));
  }
}

}  // namespace tessera::scenes
