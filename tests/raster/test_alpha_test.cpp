// glTF materials in the programs (docs/spec-choices.md F9, F10): the base-colour factor, the MASK
// alpha test as a discard, and OPAQUE / MASK alpha forced to 1, in "textured" (slot 8.y / 8.z) and in
// "texarray_batch"'s materials TAM layout (slot 4.x = 1); and in provenance mode the ALPHA_TEST fork
// where the legal filtered alpha straddles the cutoff (docs/crosscheck.md).
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "raster/provenance.h"
#include "raster/texture.h"
#include "tests/raster/render_helpers.h"
#include "tools/scenes/builder.h"
#include "tools/scenes/scenes.h"

namespace tessera::scenes {

namespace {

constexpr std::array<uint8_t, 4> kClear = {0, 0, 255, 255};  // the background: (0, 0, 1, 1)
constexpr std::array<uint8_t, 3> kRgb = {200, 100, 50};        // every texel's colour

// A 16 x 16 RGBA8 frame cleared to blue and covered by one quad whose 16 x 16 texture (LINEAR, clamped)
// puts texel column x at pixel column x, centre on centre: texel (x, y) = (200, 100, 50, 16 x). The
// material: factor 1, alpha cutoff `cutoff`, alpha forced to 1. `batched` draws it with
// texarray_batch's materials layout (one TAM entry naming layer 0 of a one-layer array), else with
// textured. The written colour is (200, 100, 50, 255) wherever the fragment survives the test.
CommandList maskFrame(float cutoff, bool batched) {
  CommandList cl;
  RenderTarget t;
  t.color[0] = createTarget(cl, Format::RGBA8, 16, 16);
  cl.setRenderTarget(t);
  cl.setViewport({0, 0, 16, 16});
  cl.clearColor(0, {0, 0, 1, 1});
  std::vector<uint8_t> px(16 * 16 * 4);
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 16; ++x) {
      uint8_t* p = &px[(y * 16 + x) * 4];
      p[0] = kRgb[0], p[1] = kRgb[1], p[2] = kRgb[2], p[3] = uint8_t(16 * x);
    }
  TextureDesc d;
  d.kind = batched ? TextureKind::Tex2DArray : TextureKind::Tex2D;
  d.width = d.height = 16;
  const ResourceId tex = cl.createTexture(d);
  cl.uploadTexture(tex, 0, 0, px);
  SamplerState s;
  s.minFilter = Filter::Linear;
  s.wrapS = s.wrapT = Wrap::ClampToEdge;
  const ResourceId smp = cl.createSampler(s);
  Mesh m;
  m.quad({0, 0, 0}, {16, 0, 0}, {16, 16, 0}, {0, 16, 0}, {0, 0, 0, 0}, {1, 0, 0, 0}, {1, 1, 0, 0}, {0, 1, 0, 0});
  const uint32_t n = bindMesh(cl, m);
  if (batched) {
    const float tam[8] = {0, 0, cutoff, 1, 1, 1, 1, 1};
    TextureDesc td;
    td.kind = TextureKind::Buffer;
    td.format = Format::RGBA32F;
    td.width = 2;
    td.buffer = cl.createBuffer(BufferKind::Texel, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(tam), sizeof tam));
    cl.useProgram(cl.createProgram("texarray_batch"));
    setMatrix(cl, 0, ortho(0, 16, 0, 16, -1, 1));
    setVec4(cl, 4, {1, 0, 0, 0});
    cl.bindTexture(0, cl.createTexture(td));
    cl.bindTexture(1, tex);
    cl.bindSampler(1, smp);
  } else {
    cl.useProgram(cl.createProgram("textured"));
    setMatrix(cl, 0, ortho(0, 16, 0, 16, -1, 1));
    setTexturedDefaults(cl);
    setVec4(cl, 8, {0, cutoff, 1, 0});
    cl.bindTexture(0, tex);
    cl.bindSampler(0, smp);
  }
  cl.drawIndexed(0, n);
  return cl;
}

struct ProvPixels {
  std::vector<uint8_t> v, lo, hi;  // top-down
  std::vector<uint16_t> cls;       // bottom row first
  std::vector<std::vector<Candidate>> cands;
  const uint8_t* at(const std::vector<uint8_t>& img, int x, int y) const { return &img[(size_t(15 - y) * 16 + x) * 4]; }
};

ProvPixels renderProv(const CommandList& cl) {
  CpuBackend b(RenderOptions{2, true, {}, 8});
  b.execute(cl, "alpha test");
  const PresentedImage p = b.presented().at(0);
  const TextureData& t = *b.texture(p.texture);
  ProvPixels r;
  r.v = imagePixels(t, 0, 0);
  r.lo = imagePixels(*t.prov->lo, 0, 0);
  r.hi = imagePixels(*t.prov->hi, 0, 0);
  r.cls = t.prov->classes[0];
  r.cands = t.prov->candidates[0];
  return r;
}

bool isColour(const uint8_t* p, const std::array<uint8_t, 4>& c) {
  return p[0] == c[0] && p[1] == c[1] && p[2] == c[2] && p[3] == c[3];
}

}  // namespace

// Outside the anonymous namespace: the TEST_P classes derive from it, and in a unity batch (not the main
// file) GCC warns about a class with a base of internal linkage (-Wsubobject-linkage).
class AlphaTest : public ::testing::TestWithParam<bool> {};

TEST_P(AlphaTest, AMaskCutoffOnATexelsExactAlphaForksOnlyThatColumnIntoWrittenAndNotWritten) {
  // Pixel column x samples texel column x at its centre: alpha 16 x / 255, its neighbours 16 LSB away.
  // GL may move the sample by 1/128 px (a weight of at most 3/256 on a neighbour: 0.19 LSB) and round
  // the filter by 1 LSB (FILTER_PRECISION), so column x's legal alpha lies within 16 x +- 1.2 LSB.
  // The cutoff 128/255 sits exactly on column 8's alpha: that interval straddles it, so GL may discard
  // the fragment or keep it (ALPHA_TEST, two candidates: the blue background and the colour). Columns
  // 0-7 (alpha <= 113.2 LSB) are discarded and 9-15 (>= 142.8 LSB) kept by every legal GL: one exact
  // value each, no class (the kept colour is constant and its alpha forced to 1).
  const std::array<uint8_t, 4> colour = {kRgb[0], kRgb[1], kRgb[2], 255};
  const ProvPixels p = renderProv(maskFrame(float(128.0 / 255.0), GetParam()));
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const size_t i = size_t(y) * 16 + x;
      if (x == 8) {
        EXPECT_NE(p.cls[i] & kAlphaTest, 0) << x << "," << y;
        // Both outcomes are in the hull and each is a candidate of its own.
        EXPECT_TRUE(isColour(p.at(p.lo, x, y), {0, 0, kRgb[2], 255})) << x << "," << y;
        EXPECT_TRUE(isColour(p.at(p.hi, x, y), {kRgb[0], kRgb[1], 255, 255})) << x << "," << y;
        ASSERT_EQ(p.cands[i].size(), 2u) << x << "," << y;
        bool background = false, written = false;
        for (const Candidate& c : p.cands[i]) {
          background = background || (c.lo[0] == 0 && c.hi[0] == 0 && c.lo[2] == 255 && c.hi[2] == 255);
          written = written || (c.lo[0] == kRgb[0] && c.hi[0] == kRgb[0] && c.lo[2] == kRgb[2] && c.hi[2] == kRgb[2]);
        }
        EXPECT_TRUE(background && written) << x << "," << y;
      } else {
        EXPECT_EQ(p.cls[i], 0) << x << "," << y;
        const std::array<uint8_t, 4>& want = x < 8 ? kClear : colour;
        EXPECT_TRUE(isColour(p.at(p.v, x, y), want)) << x << "," << y;
        EXPECT_TRUE(isColour(p.at(p.lo, x, y), want) && isColour(p.at(p.hi, x, y), want)) << x << "," << y;
      }
    }
}

TEST_P(AlphaTest, ACutoffFarFromEveryLegalAlphaGivesNoClassAndOneOutcomePerPixel) {
  // Cutoff 120/255: 6.8 LSB above column 7's legal alpha and 6.8 below column 8's. No pixel may go
  // either way: columns 0-7 keep the background, 8-15 take the colour, all exact and unclassed.
  const std::array<uint8_t, 4> colour = {kRgb[0], kRgb[1], kRgb[2], 255};
  const ProvPixels p = renderProv(maskFrame(float(120.0 / 255.0), GetParam()));
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const size_t i = size_t(y) * 16 + x;
      const std::array<uint8_t, 4>& want = x < 8 ? kClear : colour;
      EXPECT_EQ(p.cls[i], 0) << x << "," << y;
      EXPECT_TRUE(isColour(p.at(p.v, x, y), want)) << x << "," << y;
      EXPECT_TRUE(isColour(p.at(p.lo, x, y), want) && isColour(p.at(p.hi, x, y), want)) << x << "," << y;
    }
}

TEST_P(AlphaTest, TheFastPathDiscardsWhatTheValueRunDiscardsAndCountsIt) {
  // Cutoff 120/255: 8 columns of 16 discarded, 128 fragments, in the fast path as in provenance mode.
  const CommandList cl = maskFrame(float(120.0 / 255.0), GetParam());
  const tessera::testing::Rendered fast = tessera::testing::renderList(cl, 2);
  EXPECT_EQ(fast.stats.fragments_discarded, 128u);
  const ProvPixels p = renderProv(cl);
  std::vector<uint8_t> fastImg = fast.images.at(0);
  EXPECT_EQ(fastImg, p.v);
}

INSTANTIATE_TEST_SUITE_P(BothPrograms, AlphaTest, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& i) { return i.param ? "texarray_batch" : "textured"; });

TEST(Materials, TheBaselineAndTheBatchedProgramGiveTheSameColoursForTheSameMaterials) {
  // alpha_mask draws each material twice, with textured on the left (x 4..60) and with texarray_batch's
  // materials TAM on the right (x 68..124): the same quads moved by 64 px, the same texture, LINEAR
  // without mipmaps (no LOD dependence), so every pixel must agree with its partner 64 px away.
  const tessera::testing::Rendered r = tessera::testing::renderList(build("alpha_mask", 128, 96), 2);
  const std::vector<uint8_t>& img = r.images.at(0);
  int compared = 0;
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 4; ++c) {
        ASSERT_EQ(img[(size_t(y) * 128 + x) * 4 + c], img[(size_t(y) * 128 + x + 64) * 4 + c]) << x << "," << y;
        ++compared;
      }
  EXPECT_EQ(compared, 96 * 64 * 4);
  // The MASK row (window y 4..27): the texture's alpha is 128 (s + t) / 255 (texel (x, y) holds
  // 4 + 4 x + 4 y), and the factor 0.8 passes it iff 0.8 * 128 (s + t) >= 127.5, s + t >= 1.2451. At
  // y = 16, t = 12.5 / 24 = 0.5208, and s = (x + 0.5 - 4) / 56: column 42 (s + t = 1.2083, 123.7 LSB)
  // keeps the background, column 47 (1.2976, 132.9 LSB) is written with alpha forced to 255.
  const auto px = [&](int x, int y) { return &img[(size_t(95 - y) * 128 + x) * 4]; };
  EXPECT_EQ(px(42, 16)[0], 28);  // 0.11 * 255 = 28.05, the background
  EXPECT_EQ(px(42, 16)[2], 51);  // 0.2 * 255
  EXPECT_EQ(px(47, 16)[2], 63);  // the four texels around have blue 90; 90 * 0.7 = 63
  EXPECT_EQ(px(47, 16)[3], 255);
  // Every discarded fragment left the background in the MASK quads (x 4..59 and 68..123, y 4..27),
  // and nothing else was discarded.
  uint64_t background = 0;
  for (int y = 4; y < 28; ++y)
    for (int x = 4; x < 124; ++x)
      if (x < 60 || x >= 68) background += px(x, y)[0] == 28 && px(x, y)[1] == 38 && px(x, y)[2] == 51;
  EXPECT_GT(background, 0u);
  EXPECT_EQ(r.stats.fragments_discarded, background);
}

}  // namespace tessera::scenes
