// Depth in the candidate-set judgement (docs/crosscheck.md, DEPTH_NEAR_EQUAL): a depth test against a
// depth that a fragment with the same depth-writer signature stored is an exact tie (GL 4.6 Appendix A),
// so it is decided without a fork; different geometry at a near tie still forks; and each candidate
// carries the depth its own chain left, so a fragment behind an edge that another legal snapping moves
// may show there. Each test edits the oracle's own image at pixels whose legal values follow from the
// construction, and checks the verdict.
#include <gtest/gtest.h>

#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "tools/scenes/scene_common.h"
#include "tests/crosscheck/provenance_render.h"
#include "verify/judge.h"

namespace tessera {

namespace {

constexpr int kSize = 32;

// Top-down byte offset of GL pixel (x, y), and its classes (stored bottom row first).
size_t at(int x, int y) { return (size_t(kSize - 1 - y) * kSize + size_t(x)) * 4; }
uint16_t classesAt(const ProvenanceRender& r, int x, int y) {
  return r.tex->prov->classes[r.img.level][size_t(y) * kSize + size_t(x)];
}

// Whether the judge accepts the oracle's image with pixel (x, y) set to grey level v in r, g, b.
bool accepts(const ProvenanceRender& r, int x, int y, uint8_t v) {
  auto other = r.pixels;
  for (int c = 0; c < 3; ++c) other[at(x, y) + c] = v;
  return verify::judge(*r.tex, r.img.level, r.img.layer, other).unexplained == 0;
}

// A sloped quad over (3.3, 3.3) .. (28.7, 28.7) in window pixels (no edge near a centre inside), depth
// from 0.2 to 0.6 across, in grey level `grey`; `zShift` moves it in depth, `flip` splits it along the
// other diagonal (the same plane, other triangles).
void slopedQuad(scenes::Mesh& m, float grey, float zShift = 0.0f, bool flip = false) {
  const glm::vec4 c{grey, grey, grey, 1};
  const glm::vec3 p0{3.3f, 3.3f, -0.2f + zShift}, p1{28.7f, 3.3f, -0.6f + zShift};
  const glm::vec3 p2{28.7f, 28.7f, -0.4f + zShift}, p3{3.3f, 28.7f, 0.0f + zShift};
  if (!flip) {
    m.quad(p0, p1, p2, p3, c, c, c, c);
  } else {
    m.triangle({p1, c, 0}, {p2, c, 0}, {p3, c, 0});
    m.triangle({p1, c, 0}, {p3, c, 0}, {p0, c, 0});
  }
}

// Two draws over a depth buffer cleared to 1: the first in dark grey under LESS, the second (`second`)
// in light grey under `func`. vertex_color takes the colour from a vertex attribute, so both draws
// have the same program, uniforms and positions unless `second` changes them.
CommandList redraw(CompareFunc func, float zShift, bool flip) {
  CommandList cl;
  scenes::beginFrame(cl, kSize, kSize, true, {0, 0, 0, 1});
  cl.useProgram(cl.createProgram("vertex_color"));
  scenes::setMatrix(cl, 0, scenes::ortho(0, kSize, 0, kSize, -1, 1));
  scenes::Mesh m;
  slopedQuad(m, 0.25f);
  slopedQuad(m, 0.75f, zShift, flip);
  const uint32_t n = scenes::bindMesh(cl, m);
  DepthState ds;
  ds.test = true;
  cl.setDepthState(ds);
  cl.drawIndexed(0, n / 2);
  ds.func = func;
  cl.setDepthState(ds);
  cl.drawIndexed(n / 2, n / 2);
  return cl;
}

constexpr uint8_t kDark = 64, kLight = 191;  // 0.25 and 0.75 as unorm8 (63.75, 191.25 rounded)

}  // namespace

TEST(DepthCandidates, ARedrawOfTheSameGeometryUnderLessMustLoseEveryTie) {
  const ProvenanceRender r = renderWithProvenance(redraw(CompareFunc::Less, 0.0f, false));
  for (int y = 6; y < 26; y += 3)
    for (int x = 6; x < 26; x += 3) {
      // On the quad's diagonal the two triangles' chains (same colour, other writers) are merged,
      // and the tie is no longer known to be exact.
      if (x == y) continue;
      ASSERT_EQ(r.pixels[at(x, y)], kDark) << x << "," << y;
      EXPECT_EQ(classesAt(r, x, y) & kDepthNearEqual, 0) << x << "," << y;
      EXPECT_FALSE(accepts(r, x, y, kLight)) << "the second draw cannot win an exact tie under LESS: " << x << "," << y;
    }
}

TEST(DepthCandidates, ARedrawOfTheSameGeometryUnderLequalMustWinEveryTie) {
  const ProvenanceRender r = renderWithProvenance(redraw(CompareFunc::LEqual, 0.0f, false));
  for (int y = 6; y < 26; y += 3)
    for (int x = 6; x < 26; x += 3) {
      if (x == y) continue;  // the diagonal, as above
      ASSERT_EQ(r.pixels[at(x, y)], kLight) << x << "," << y;
      EXPECT_EQ(classesAt(r, x, y) & kDepthNearEqual, 0) << x << "," << y;
      EXPECT_FALSE(accepts(r, x, y, kDark)) << "the second draw cannot lose an exact tie under LEQUAL: " << x << "," << y;
    }
}

TEST(DepthCandidates, OtherGeometryAtANearTieStillAcceptsEitherOutcome) {
  // The same plane split along the other diagonal: other primitives, so GL need not give the same
  // depth bits, and the depths agree only within the precision GL allows.
  const ProvenanceRender r = renderWithProvenance(redraw(CompareFunc::Less, 0.0f, true));
  int forked = 0;
  for (int y = 6; y < 26; y += 3)
    for (int x = 6; x < 26; x += 3) {
      if (!(classesAt(r, x, y) & kDepthNearEqual)) continue;
      EXPECT_TRUE(accepts(r, x, y, kDark)) << x << "," << y;
      EXPECT_TRUE(accepts(r, x, y, kLight)) << x << "," << y;
      EXPECT_FALSE(accepts(r, x, y, 128)) << "no value between the two outcomes: " << x << "," << y;
      ++forked;
    }
  EXPECT_GE(forked, 40) << "the coplanar redraw ties (nearly) everywhere";
}

TEST(DepthCandidates, AFragmentBehindAnEdgeTieMayShowWhereTheEdgeGoesTheOtherWay) {
  // A far white quad first, then a near black one whose left edge x = 16.5 passes exactly through
  // pixel centres, then a far grey quad drawn again over both (LESS). Where the near quad's edge
  // decides a centre, another legal snapping leaves it uncovered, and there the last draw (nearer than
  // the white quad, farther than the black one) wins: grey is legal, and so is the oracle's black.
  CommandList cl;
  scenes::beginFrame(cl, kSize, kSize, true, {0, 0, 0, 1});
  cl.useProgram(cl.createProgram("vertex_color"));
  scenes::setMatrix(cl, 0, scenes::ortho(0, kSize, 0, kSize, -1, 1));
  scenes::Mesh m;
  const glm::vec4 white{1, 1, 1, 1}, black{0, 0, 0, 1}, grey{0.5f, 0.5f, 0.5f, 1};
  // ortho(..., -1, 1) maps z to window depth (1 - z) / 2: z = 0.8 is near, -0.8 far.
  m.quad({2.3f, 2.3f, -0.8f}, {29.7f, 2.3f, -0.8f}, {29.7f, 29.7f, -0.8f}, {2.3f, 29.7f, -0.8f}, white, white, white,
         white);
  m.quad({16.5f, 2.3f, 0.8f}, {29.7f, 2.3f, 0.8f}, {29.7f, 29.7f, 0.8f}, {16.5f, 29.7f, 0.8f}, black, black, black, black);
  m.quad({2.3f, 2.3f, 0.0f}, {29.7f, 2.3f, 0.0f}, {29.7f, 29.7f, 0.0f}, {2.3f, 29.7f, 0.0f}, grey, grey, grey, grey);
  const uint32_t n = scenes::bindMesh(cl, m);
  DepthState ds;
  ds.test = true;
  cl.setDepthState(ds);
  cl.drawIndexed(0, n);
  const ProvenanceRender r = renderWithProvenance(cl);
  int checked = 0;
  for (int y = 6; y < 26; ++y) {
    ASSERT_EQ(r.pixels[at(16, y)], 0) << "the oracle covers centres on its left edge (fill rule): y " << y;
    ASSERT_NE(classesAt(r, 16, y) & kEdgeTie, 0) << y;
    EXPECT_TRUE(accepts(r, 16, y, 0)) << y;
    EXPECT_TRUE(accepts(r, 16, y, 128)) << "grey over white where the black quad's edge goes the other way: y " << y;
    EXPECT_FALSE(accepts(r, 16, y, 255)) << "white is hidden by grey in either case: y " << y;
    EXPECT_FALSE(accepts(r, 20, y, 128)) << "inside the black quad grey never shows: y " << y;
    ++checked;
  }
  EXPECT_EQ(checked, 20);
}

}  // namespace tessera
