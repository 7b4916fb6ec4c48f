// The plain draw's write loop (raster/rast.cpp, TriangleRasterizer::writePlainRgba8): a draw with one
// RGBA8 output, no blending, no gl_FragDepth and no LOD probe skips the general loop (writeQuads). The
// same draws blended with ONE, ZERO, ADD take the general loop and must give the same bytes and
// counters: GL 4.6 section 17.3.6 clamps the source to [0, 1] for a fixed-point buffer before blending, and
// Cs * 1 + Cd * 0 is Cs exactly for a finite Cd. The frames cover what the plain loop distinguishes:
// whole and partly covered quads, quads past the target's last row and column (an odd-sized target),
// depth writes on and off, colours that vary per pixel and out of [0, 1], and large overlapping
// triangles, which the plain draw walks twice (a visibility run) and the blended one once.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "tests/raster/render_helpers.h"
#include "tools/scenes/builder.h"
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {
namespace {

using tessera::testing::expectRendersAs;
using tessera::testing::Rendered;
using tessera::testing::renderList;

// `n` random triangles of 0.5 to `maxSize` px, random colours in [-0.5, 1.5] per vertex, on a w x h
// target; a LESS depth test with writes if `depth`; blended ONE, ZERO, ADD if `identityBlend`.
CommandList randomTriangles(int w, int h, int n, float maxSize, bool depth, bool identityBlend, uint32_t seed) {
  std::mt19937 rng(seed);
  const auto unit = [&]() { return float(rng() % 10001) / 10000.0f; };
  Mesh m;
  for (int i = 0; i < n; ++i) {
    const float x = unit() * float(w), y = unit() * float(h), z = unit() * 2.0f - 1.0f;
    const float size = 0.5f + unit() * (maxSize - 0.5f);
    const auto corner = [&]() {
      const glm::vec4 colour{unit() * 2.0f - 0.5f, unit() * 2.0f - 0.5f, unit() * 2.0f - 0.5f, unit() * 2.0f - 0.5f};
      return Vertex{{x + (unit() - 0.5f) * size, y + (unit() - 0.5f) * size, z}, colour, 0};
    };
    m.triangle(corner(), corner(), corner());
  }
  CommandList cl;
  beginFrame(cl, w, h, depth, {0.5f, 0.25f, 0.75f, 1.0f});
  const uint32_t count = bindMesh(cl, m);
  cl.useProgram(cl.createProgram("vertex_color"));
  setMatrix(cl, 0, ortho(0, float(w), 0, float(h), -1, 1));
  if (depth) {
    DepthState d;
    d.test = true;
    d.func = CompareFunc::Less;
    cl.setDepthState(d);
  }
  if (identityBlend) {
    BlendState b;
    b.enabled = true;
    b.srcRgb = b.srcAlpha = BlendFactor::One;
    b.dstRgb = b.dstAlpha = BlendFactor::Zero;
    cl.setBlendState(b);
  }
  cl.drawIndexed(0, count);
  return cl;
}

// The plain frame at 1 and 7 threads gives the identity-blended frame's bytes and counters.
void expectGeneralLoopsFrame(int w, int h, int n, float maxSize, bool depth, uint32_t seed) {
  const std::string what = std::to_string(w) + "x" + std::to_string(h) + ", " + std::to_string(n) +
                           " triangles up to " + std::to_string(int(maxSize)) + " px" + (depth ? ", depth LESS" : "") +
                           ", seed " + std::to_string(seed);
  const Rendered general = renderList(randomTriangles(w, h, n, maxSize, depth, true, seed), 1);
  ASSERT_EQ(general.hashes.size(), 1u) << what;
  ASSERT_GT(general.stats.pixels_written, 0u) << what;
  expectRendersAs(randomTriangles(w, h, n, maxSize, depth, false, seed), general, {1, 7}, what);
}

}  // namespace

TEST(PlainWrite, SmallTrianglesOnAnOddSizedTargetGiveTheGeneralLoopsBytesAndCounters) {
  for (const uint32_t seed : {1u, 2u}) {
    expectGeneralLoopsFrame(151, 91, 3000, 6.0f, false, seed);
    expectGeneralLoopsFrame(151, 91, 3000, 6.0f, true, seed);
  }
}

TEST(PlainWrite, LargeOverlappingTrianglesGiveTheGeneralLoopsBytesAndCounters) {
  for (const uint32_t seed : {3u, 4u}) {
    expectGeneralLoopsFrame(203, 137, 200, 120.0f, false, seed);
    expectGeneralLoopsFrame(203, 137, 200, 120.0f, true, seed);
  }
}

}  // namespace tessera::scenes
