// Provenance mode: the same bytes as the fast path, plus per-pixel intervals and ambiguity classes
// (raster/provenance.h, docs/crosscheck.md) that match what the geometry of the frame allows.
//
// Small frames whose freedoms are known by construction pin the class model pixel by pixel: no
// freedom gives an unclassed, zero-width pixel; an edge through a pixel centre gives EDGE_TIE; a
// blended write gives BLEND_PRECISION with the +-2.5 LSB tolerance of docs/crosscheck.md; a NEAREST
// lookup at a texel boundary gives SUBTEXEL_NEAR_HALF only where the two texels differ. On every
// built-in scene, "unclassed" and "zero-width interval" must be the same set of pixels (the judge
// relies on it), and two scenes get class counts derived from their geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "raster/provenance.h"
#include "raster/sample.h"
#include "raster/texture.h"
#include "tests/raster/render_helpers.h"
#include "tools/scenes/builder.h"
#include "tools/scenes/scenes.h"

namespace tessera::scenes {

namespace {

// One presented image in provenance mode, addressed in GL window coordinates (x right, y up).
struct ProvImage {
  int w = 0, h = 0, channels = 0;
  std::vector<uint8_t> v, lo, hi;  // top-down, imagePixels() layout
  std::vector<uint16_t> cls;       // bottom row first, as Provenance stores it
  uint8_t val(int x, int y, int c = 0) const { return v[(size_t(h - 1 - y) * w + x) * 4 + c]; }
  uint8_t low(int x, int y, int c = 0) const { return lo[(size_t(h - 1 - y) * w + x) * 4 + c]; }
  uint8_t high(int x, int y, int c = 0) const { return hi[(size_t(h - 1 - y) * w + x) * 4 + c]; }
  uint16_t classes(int x, int y) const { return cls[size_t(y) * w + x]; }
  bool exact(int x, int y) const {
    for (int c = 0; c < 4; ++c)
      if (low(x, y, c) != val(x, y, c) || high(x, y, c) != val(x, y, c)) return false;
    return true;
  }
};

ProvImage renderProvenance(const CommandList& cl, size_t image = 0) {
  CpuBackend b(RenderOptions{2, true, {}, 8});  // judged against 8 sub-pixel bits
  b.execute(cl, "provenance test");
  const PresentedImage p = b.presented().at(image);
  const TextureData& t = *b.texture(p.texture);
  EXPECT_EQ(t.desc.format, Format::RGBA8);
  ProvImage r;
  r.w = int(levelWidth(t.desc, p.level));
  r.h = int(levelHeight(t.desc, p.level));
  r.v = imagePixels(t, p.level, p.layer);
  r.lo = imagePixels(*t.prov->lo, p.level, p.layer);
  r.hi = imagePixels(*t.prov->hi, p.level, p.layer);
  const auto& all = t.prov->classes[p.level];
  r.cls.assign(all.begin() + ptrdiff_t(size_t(p.layer) * r.w * r.h),
               all.begin() + ptrdiff_t(size_t(p.layer + 1) * r.w * r.h));
  return r;
}

// A 16 x 16 RGBA8 frame cleared to 0, orthographic in pixel units, flat_color 0.25 (63.75 in bytes:
// not near a rounding tie), optionally with additive blending.
CommandList flatFrame(const Mesh& m, bool additive, int draws = 1) {
  CommandList cl;
  RenderTarget t;
  t.color[0] = createTarget(cl, Format::RGBA8, 16, 16);
  cl.setRenderTarget(t);
  cl.setViewport({0, 0, 16, 16});
  cl.clearColor(0, {0, 0, 0, 0});
  const uint32_t n = bindMesh(cl, m);
  cl.useProgram(cl.createProgram("flat_color"));
  setMatrix(cl, 0, ortho(0, 16, 0, 16, -1, 1));
  setVec4(cl, 4, {0.25f, 0.25f, 0.25f, 0.25f});
  if (additive) {
    BlendState b;
    b.enabled = true;
    b.srcRgb = b.dstRgb = b.srcAlpha = b.dstAlpha = BlendFactor::One;
    cl.setBlendState(b);
  }
  for (int i = 0; i < draws; ++i) cl.drawIndexed(0, n);
  return cl;
}

Mesh square(float x0, float y0, float x1, float y1) {
  Mesh m;
  m.quad({x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}, {}, {}, {}, {});
  return m;
}

}  // namespace

TEST(ProvenanceClasses, ARectangleOnPixelCornersLeavesEveryPixelUnclassedAndExact) {
  // [4, 12] x [4, 10]: every side lies half a pixel from the nearest centre and the diagonal that
  // splits it (slope 3/4: 4 (y - 4) - 3 (x - 4) = 0 has no half-integer solution) at least 0.1 px, far
  // beyond the tie margin of sqrt(2)/256 px; the colour is constant and nothing blends: GL has no
  // choice anywhere. (A square would put its diagonal through the centres (k + 1/2, k + 1/2).)
  const ProvImage p = renderProvenance(flatFrame(square(4, 4, 12, 10), false));
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const bool inside = x >= 4 && x < 12 && y >= 4 && y < 10;
      ASSERT_EQ(p.classes(x, y), 0) << x << "," << y;
      ASSERT_TRUE(p.exact(x, y)) << x << "," << y;
      ASSERT_EQ(p.val(x, y), inside ? 64 : 0) << x << "," << y;
    }
}

TEST(ProvenanceClasses, EdgesThroughPixelCentresAreTiesExceptTheSharedDiagonal) {
  // The square [2.5, 10.5]^2 (two triangles split along the diagonal from (2.5, 2.5) to (10.5, 10.5)):
  // its four sides run through the centres of columns / rows 2 and 10, and the diagonal through the
  // centres (k, k). The 9 * 4 - 4 = 32 side pixels are ties: the fill convention (left and bottom in)
  // decides them, another implementation may decide otherwise, so they hold two candidates, the clear
  // value 0 and the colour 64. The diagonal is shared by the two triangles with identical endpoints:
  // GL 4.6 §14.6.1 makes exactly one of them produce the fragment, so its 7 inner pixels are 64 and
  // nothing else (no gap, no double hit). Every other pixel is at least half a pixel from every edge.
  const ProvImage p = renderProvenance(flatFrame(square(2.5f, 2.5f, 10.5f, 10.5f), false));
  int classed = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const bool inRange = x >= 2 && x <= 10 && y >= 2 && y <= 10;
      const bool onSide = inRange && (x == 2 || x == 10 || y == 2 || y == 10);
      const bool covered = x >= 2 && x < 10 && y >= 2 && y < 10;
      ASSERT_EQ(p.val(x, y), covered ? 64 : 0) << x << "," << y;
      if (onSide) {
        ++classed;
        ASSERT_EQ(p.classes(x, y), kEdgeTie) << x << "," << y;
        for (int c = 0; c < 4; ++c) {
          ASSERT_EQ(p.low(x, y, c), 0) << x << "," << y;
          ASSERT_EQ(p.high(x, y, c), 64) << x << "," << y;
        }
      } else {
        ASSERT_EQ(p.classes(x, y), 0) << x << "," << y;
        ASSERT_TRUE(p.exact(x, y)) << x << "," << y;
      }
    }
  EXPECT_EQ(classed, 32);
}

TEST(ProvenanceClasses, ABlendedWriteCarriesTheDerivedToleranceAndPropagatesIntoTheNextBlend) {
  // Additive blending of 0.25 onto 0: exact result 63.75 LSB, widened by the 2.5 LSB blend tolerance
  // to [61.25, 66.25], i.e. bytes 61..66. A second identical draw blends 0.25 onto that interval:
  // 63.75 + [61, 66] = [124.75, 129.75], widened to [122.25, 132.25]: bytes 122..132, value 128.
  // The rectangle of the test above has no edge tie, so the only class is BLEND_PRECISION.
  for (int draws : {1, 2}) {
    const ProvImage p = renderProvenance(flatFrame(square(4, 4, 12, 10), true, draws));
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) {
        const bool inside = x >= 4 && x < 12 && y >= 4 && y < 10;
        if (!inside) {
          ASSERT_EQ(p.classes(x, y), 0) << x << "," << y;
          ASSERT_TRUE(p.exact(x, y)) << x << "," << y;
          ASSERT_EQ(p.val(x, y), 0) << x << "," << y;
          continue;
        }
        ASSERT_EQ(p.classes(x, y), kBlendPrecision) << x << "," << y << " after " << draws << " draws";
        for (int c = 0; c < 4; ++c) {
          ASSERT_EQ(p.val(x, y, c), draws == 1 ? 64 : 128) << x << "," << y;
          ASSERT_EQ(p.low(x, y, c), draws == 1 ? 61 : 122) << x << "," << y << " after " << draws << " draws";
          ASSERT_EQ(p.high(x, y, c), draws == 1 ? 66 : 132) << x << "," << y << " after " << draws << " draws";
        }
      }
  }
}

namespace {
// One "textured" quad over the whole w x h viewport (identity MVP) sampling a size x size texture whose
// column x has colourOf(x) in every row, with sampler `s`; st holds the texcoords at the corners
// (-1, -1), (1, -1), (1, 1), (-1, 1).
CommandList stripeQuadFrame(uint32_t w, uint32_t h, uint32_t size, std::array<uint8_t, 4> (*colourOf)(uint32_t),
                            bool mipmaps, const SamplerState& s, const std::array<glm::vec4, 4>& st) {
  CommandList cl;
  RenderTarget t;
  t.color[0] = createTarget(cl, Format::RGBA8, w, h);
  cl.setRenderTarget(t);
  cl.setViewport({0, 0, int32_t(w), int32_t(h)});
  cl.clearColor(0, {0, 0, 0, 0});
  RgbaImage img;
  img.width = img.height = size;
  img.rgba.resize(size_t(size) * size * 4);
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) img.set(x, y, colourOf(x));
  cl.bindTexture(0, uploadTexture(cl, img, mipmaps));
  cl.bindSampler(0, cl.createSampler(s));
  Mesh m;
  m.quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, st[0], st[1], st[2], st[3]);
  const uint32_t n = bindMesh(cl, m);
  cl.useProgram(cl.createProgram("textured"));
  setMatrix(cl, 0, glm::mat4(1.0f));
  setTexturedDefaults(cl);
  cl.drawIndexed(0, n);
  return cl;
}

// A 16 x 12 frame filled by one "textured" quad (identity MVP, full viewport) sampling a 4 x 4
// texture with NEAREST filters: columns 0-1 red, columns 2-3 blue, so the texture changes only at
// s = 0.5 (and at the REPEAT seam s = 0 / 1). Texcoords run from sOffset to 1 + sOffset across the
// quad, so pixel column x samples s = (x + 0.5) / 16 + sOffset: 4 pixels per texel across, 3 down
// (magnification, lambda = log2(1/3), far from the mag/min switch at 0). 16 x 12 rather than square
// keeps the quad's diagonal (slope 3/4) off every pixel centre.
CommandList nearestFrame(float sOffset) {
  SamplerState s;
  s.minFilter = Filter::Nearest;
  s.magFilter = Filter::Nearest;
  const float s0 = sOffset, s1 = 1.0f + sOffset;
  return stripeQuadFrame(
      16, 12, 4, [](uint32_t x) { return x < 2 ? std::array<uint8_t, 4>{255, 0, 0, 255} : std::array<uint8_t, 4>{0, 0, 255, 255}; },
      false, s, {glm::vec4{s0, 0, 0, 0}, {s1, 0, 0, 0}, {s1, 1, 0, 0}, {s0, 1, 0, 0}});
}
}  // namespace

TEST(ProvenanceClasses, ANearestSampledFlatRegionHasZeroWidthIntervals) {
  // sOffset = 0: the texel boundaries s = k / 4 fall on pixel edges (x = 4k), every centre is 1/8 texel
  // from the nearest boundary, far beyond the 1/128 px position tolerance; t is uniform per texture
  // column. Nothing is classed.
  const ProvImage p = renderProvenance(nearestFrame(0.0f));
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 16; ++x) {
      ASSERT_EQ(p.classes(x, y), 0) << x << "," << y;
      ASSERT_TRUE(p.exact(x, y)) << x << "," << y;
      ASSERT_EQ(p.val(x, y, 0), x < 8 ? 255 : 0) << x << "," << y;
      ASSERT_EQ(p.val(x, y, 2), x < 8 ? 0 : 255) << x << "," << y;
    }
}

TEST(ProvenanceClasses, ANearestLookupOnATexelBoundaryIsClassedOnlyWhereTheTexelsDiffer) {
  // sOffset = 1/32 moves every texel boundary onto a pixel centre: column x samples s = (x + 1) / 16,
  // so columns 3, 7, 11 and 15 sit exactly on s = 1/4, 1/2, 3/4 and 1. Only at s = 1/2 (red | blue)
  // and s = 1 (blue | red across the REPEAT seam) do the two candidate texels differ: those columns
  // are SUBTEXEL_NEAR_HALF with an interval covering both colours. At s = 1/4 and 3/4 both texels
  // have the same colour, so the freedom changes nothing and the pixel stays unclassed and exact.
  // The quad neighbours of columns 7 and 15 (columns 6 and 14) may carry OUTPUT_ROUNDING: the output
  // tolerance is the quad's own output gradient / 128 px, and the colour may change inside that quad.
  const ProvImage p = renderProvenance(nearestFrame(1.0f / 32.0f));
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 16; ++x) {
      const uint16_t c = p.classes(x, y);
      if (x == 7 || x == 15) {
        ASSERT_NE(c & kSubtexelNearHalf, 0) << x << "," << y;
        ASSERT_EQ(c & ~(kSubtexelNearHalf | kOutputRounding), 0) << x << "," << y << " classes " << c;
        EXPECT_EQ(p.low(x, y, 0), 0) << x << "," << y;
        EXPECT_EQ(p.high(x, y, 0), 255) << x << "," << y;
        EXPECT_EQ(p.low(x, y, 2), 0) << x << "," << y;
        EXPECT_EQ(p.high(x, y, 2), 255) << x << "," << y;
        continue;
      }
      const bool red = x < 7;  // columns 8-14 sample s in (1/2, 1): blue
      ASSERT_EQ(p.val(x, y, 0), red ? 255 : 0) << x << "," << y;
      ASSERT_EQ(p.val(x, y, 2), red ? 0 : 255) << x << "," << y;
      if (x == 6 || x == 14) {
        ASSERT_EQ(c & ~kOutputRounding, 0) << x << "," << y << " classes " << c;
        continue;
      }
      ASSERT_EQ(c, 0) << x << "," << y;
      ASSERT_TRUE(p.exact(x, y)) << x << "," << y;
    }
}

// ---- the built-in scenes ----

class ProvenanceMode : public ::testing::TestWithParam<std::string> {};

TEST_P(ProvenanceMode, ValuesMatchTheFastPathAndAPixelIsUnclassedExactlyWhenItsIntervalIsOneValue) {
  const scenes::SceneInfo* info = scenes::find(GetParam());
  const CommandList cl = scenes::build(info->name, info->width, info->height);
  const auto fast = tessera::testing::renderList(cl, 2);
  CpuBackend b(RenderOptions{2, true, {}, 8});  // judged against 8 sub-pixel bits
  b.execute(cl, GetParam());
  // layered_target's atlas: its only array texture, rendered in pass 1.
  const TextureData* atlas = nullptr;
  for (const Command& c : cl.commands())
    if (const auto* ct = std::get_if<CreateTexture>(&c); ct && ct->desc.kind == TextureKind::Tex2DArray && !atlas)
      atlas = b.texture(ct->id);
  const auto images = b.presented();
  ASSERT_EQ(images.size(), fast.hashes.size());
  for (size_t i = 0; i < images.size(); ++i) {
    const TextureData& t = *b.texture(images[i].texture);
    EXPECT_EQ(imageSha256(t, images[i].level, images[i].layer), fast.hashes[i]) << "provenance changed the bytes";
    ASSERT_TRUE(t.prov) << "no interval images for a presented target";
    const auto v = imagePixels(t, images[i].level, images[i].layer);
    const auto lo = imagePixels(*t.prov->lo, images[i].level, images[i].layer);
    const auto hi = imagePixels(*t.prov->hi, images[i].level, images[i].layer);
    const uint32_t w = levelWidth(t.desc, images[i].level), h = levelHeight(t.desc, images[i].level);
    const size_t bpt = texelBytes(t.desc.format);
    const int channels = channelCount(t.desc.format);
    ASSERT_EQ(v.size(), size_t(w) * h * bpt);
    const auto& cls = t.prov->classes[images[i].level];
    ASSERT_EQ(cls.size(), size_t(t.desc.layers) * w * h);
    // Each channel's value and bounds as doubles (unorm bytes, float or uint words).
    auto channel = [&](const std::vector<uint8_t>& img, size_t px, int c) {
      const uint8_t* p = &img[px * bpt];
      if (isUnorm(t.desc.format)) return double(p[c]);
      if (isFloat(t.desc.format)) {
        float f;
        std::memcpy(&f, p + 4 * c, 4);
        return double(f);
      }
      uint32_t u;
      std::memcpy(&u, p + 4 * c, 4);
      return double(u);
    };
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) {
        const size_t px = size_t(y) * w + x;  // top-down
        const uint16_t c = cls[(size_t(images[i].layer) * h + (h - 1 - y)) * w + x];
        bool zeroWidth = true;
        for (int k = 0; k < channels; ++k) {
          const double l = channel(lo, px, k), val = channel(v, px, k), u = channel(hi, px, k);
          ASSERT_LE(l, val) << "image " << i << " pixel " << x << "," << y << " channel " << k;
          ASSERT_GE(u, val) << "image " << i << " pixel " << x << "," << y << " channel " << k;
          zeroWidth = zeroWidth && l == val && u == val;
        }
        // The judge accepts a differing pixel iff it lies in the interval; docs/crosscheck.md promises
        // that an unclassed pixel must match bit for bit. Both hold only if the two sets agree.
        if (c != 0) {
          ASSERT_FALSE(zeroWidth) << "image " << i << " pixel " << x << "," << y << " is classed " << c
                                  << " but its interval is one value";
        } else {
          // (blend's alpha on an exact .5 tie and layered_target's atlas intervals used to be wide
          // without a class; they are OUTPUT_ROUNDING and INPUT_INTERVAL now.)
          ASSERT_TRUE(zeroWidth) << "image " << i << " pixel " << x << "," << y
                                 << " is unclassed but its interval is wider than its value";
        }
      }
  }
}

INSTANTIATE_TEST_SUITE_P(AllScenes, ProvenanceMode, ::testing::ValuesIn([] {
                           std::vector<std::string> names;
                           for (const auto& s : scenes::all()) names.emplace_back(s.name);
                           return names;
                         }()),
                         [](const auto& param) { return param.param; });

namespace {
// Twice the signed area of (a, b, p) in doubled coordinates: zero iff p lies on the line through a, b.
int64_t cross2(int64_t ax, int64_t ay, int64_t bx, int64_t by, int64_t px, int64_t py) {
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

// The edges of one fill_fan fan in doubled pixel coordinates (the scene's fan(): centre (cx, cy), rim
// walking the square of half-size r counter-clockwise in steps of `step` pixels).
struct Segment {
  int64_t ax, ay, bx, by;
};
void fanEdges(int64_t cx2, int64_t cy2, int r, int step, std::vector<Segment>& out) {
  std::vector<std::array<int64_t, 2>> rim;
  for (int i = -r; i < r; i += step) rim.push_back({cx2 + 2 * i, cy2 - 2 * r});
  for (int i = -r; i < r; i += step) rim.push_back({cx2 + 2 * r, cy2 + 2 * i});
  for (int i = r; i > -r; i -= step) rim.push_back({cx2 + 2 * i, cy2 + 2 * r});
  for (int i = r; i > -r; i -= step) rim.push_back({cx2 - 2 * r, cy2 + 2 * i});
  for (size_t i = 0; i < rim.size(); ++i) {
    const auto& a = rim[i];
    const auto& b = rim[(i + 1) % rim.size()];
    out.push_back({cx2, cy2, a[0], a[1]});
    out.push_back({a[0], a[1], b[0], b[1]});
  }
}
// Distance in pixels from the centre of pixel (x, y) to the segment.
double distanceToSegment(const Segment& s, int x, int y) {
  const double px = double(2 * x + 1), py = double(2 * y + 1);
  const double dx = double(s.bx - s.ax), dy = double(s.by - s.ay);
  double t = ((px - double(s.ax)) * dx + (py - double(s.ay)) * dy) / (dx * dx + dy * dy);
  t = std::clamp(t, 0.0, 1.0);
  const double ex = double(s.ax) + t * dx - px, ey = double(s.ay) + t * dy - py;
  return std::sqrt(ex * ex + ey * ey) / 2.0;
}
}  // namespace

TEST(ProvenanceScenes, FillFanClassesExactlyTheFansAndTheirRightAndTopNearMisses) {
  // fill_fan at 128 x 128: fan A centred on (32.5, 64.5), fan B on (96, 64), both of half-size
  // r = min(128/4, 128/2) - 3 = 29, drawn with additive blending (0.25 per hit).
  // - Every pixel a fan covers is a blended write: BLEND_PRECISION. Fan A's square [3.5, 61.5] x
  //   [35.5, 93.5] has its sides on pixel centres: it covers columns 3..60 and rows 35..92 (58 x 58,
  //   left / bottom in), and its right column 61 and top row 93 are near misses (the centre lies on the
  //   edge, so another fill convention covers them): classed too, 59 x 59 in all. Fan B's square
  //   [67, 125] x [35, 93] lies on pixel corners: 58 x 58 covered, no near miss (0.5 px away).
  // - Classed pixels: exactly 59^2 + 58^2 = 6845. The rest is the clear colour, exact.
  // - EDGE_TIE: set on every pixel whose centre lies exactly on a fan edge (exact integer test), and on
  //   no pixel whose centre is more than twice the tie margin (sqrt(2)/256 px) from every edge.
  const ProvImage p = renderProvenance(scenes::build("fill_fan", 128, 128));
  std::vector<Segment> edges;
  fanEdges(65, 129, 29, 3, edges);   // fan A: centre (32.5, 64.5) doubled
  fanEdges(192, 128, 29, 5, edges);  // fan B: centre (96, 64) doubled
  const double kFar = 2.0 * 1.4142135623730951 / 256.0;
  int classed = 0, onEdge = 0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) {
      const bool fanA = x >= 3 && x <= 61 && y >= 35 && y <= 93;
      const bool fanB = x >= 67 && x <= 124 && y >= 35 && y <= 92;
      const uint16_t c = p.classes(x, y);
      classed += c != 0;
      if (!fanA && !fanB) {
        ASSERT_EQ(c, 0) << x << "," << y;
        ASSERT_TRUE(p.exact(x, y)) << x << "," << y;
        ASSERT_EQ(p.val(x, y), 0) << x << "," << y;
        continue;
      }
      ASSERT_NE(c & kBlendPrecision, 0) << x << "," << y;
      ASSERT_EQ(c & ~(kBlendPrecision | kEdgeTie), 0) << x << "," << y << " classes " << c;
      bool exactlyOn = false;
      double nearest = 1e9;
      for (const Segment& s : edges) {
        const int64_t px = 2 * x + 1, py = 2 * y + 1;
        const bool within = px >= std::min(s.ax, s.bx) && px <= std::max(s.ax, s.bx) && py >= std::min(s.ay, s.by) &&
                            py <= std::max(s.ay, s.by);
        exactlyOn = exactlyOn || (within && cross2(s.ax, s.ay, s.bx, s.by, px, py) == 0);
        nearest = std::min(nearest, distanceToSegment(s, x, y));
      }
      onEdge += exactlyOn;
      // Fan A's sides (the square's boundary) are silhouettes; its spokes and all of fan B's are
      // shared by two triangles of the fan with identical endpoints.
      const bool onSide = fanA && (x == 3 || x == 61 || y == 35 || y == 93);
      if (exactlyOn && onSide) {
        ASSERT_NE(c & kEdgeTie, 0) << x << "," << y << " lies on a fan edge";
        EXPECT_EQ(p.low(x, y), 0) << x << "," << y << ": another convention may leave it uncovered";
        EXPECT_GE(p.high(x, y), 64) << x << "," << y << ": another convention may cover it";
      } else if (exactlyOn && !(x == 32 && y == 64)) {
        // Inside a fan, away from its centre (where all spokes meet): exactly one of the two
        // triangles on the spoke hits it, so it reads one hit, 63.75 +- 2.5 LSB (no gap, no double hit).
        ASSERT_EQ(p.val(x, y), 64) << x << "," << y;
        EXPECT_EQ(p.low(x, y), 61) << x << "," << y << ": a gap is not legal on a shared edge";
        EXPECT_EQ(p.high(x, y), 66) << x << "," << y << ": a double hit is not legal on a shared edge";
      } else if (nearest > kFar) {
        ASSERT_EQ(c, kBlendPrecision) << x << "," << y << " is " << nearest << " px from every edge";
        // One hit of 0.25: 63.75 +- 2.5 LSB.
        ASSERT_EQ(p.val(x, y), 64) << x << "," << y;
        ASSERT_EQ(p.low(x, y), 61) << x << "," << y;
        ASSERT_EQ(p.high(x, y), 66) << x << "," << y;
      }
    }
  EXPECT_EQ(classed, 59 * 59 + 58 * 58);
  EXPECT_GT(onEdge, 4 * 58) << "fan A's four sides alone put 4 x 58 centres on edges, its spokes more";
}

TEST(ProvenanceScenes, BlendClassesEveryPixelOfTheTwentyBlendedQuadsAndNoEdgeTies) {
  // blend at 256 x 128, ortho 5 x 4 units: 51.2 px per unit across, 32 down. Quad (i, j) spans
  // [i + 0.1, i + 0.9] x [j + 0.1, j + 0.9] units = [51.2 i + 5.12, 51.2 i + 46.08] x [32 j + 3.2,
  // 32 j + 28.8] px: the centres of columns 51.2 i + 5.12 <= x + 0.5 < 51.2 i + 46.08 (5..45, 56..96,
  // 108..147, 159..199, 210..250: 41 + 41 + 40 + 41 + 41 = 204) and rows 3..28 (+ 32 j, 26 each). Every side is at
  // least 0.12 px from the nearest centre and the background's diagonal (y = x / 2) at least 0.5 / sqrt(5) px, far
  // beyond the tie margin: no EDGE_TIE anywhere. Every covered pixel is a blended write, which is never exact (+-2.5
  // LSB): BLEND_PRECISION on exactly those pixels; the background outside can only carry OUTPUT_ROUNDING (it is
  // interpolated).
  const ProvImage p = renderProvenance(scenes::build("blend", 256, 128));
  int blended = 0, expected = 0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 256; ++x) {
      const double cx = x + 0.5, cy = y + 0.5;
      const int i = int(cx / 51.2), j = int(cy / 32.0);
      const double ux = cx - 51.2 * i, uy = cy - 32.0 * j;
      const bool inQuad = ux >= 5.12 && ux < 46.08 && uy >= 3.2 && uy < 28.8;
      const uint16_t c = p.classes(x, y);
      expected += inQuad;
      blended += (c & kBlendPrecision) != 0;
      ASSERT_EQ(c & kEdgeTie, 0) << x << "," << y;
      if (inQuad) {
        ASSERT_NE(c & kBlendPrecision, 0) << x << "," << y;
      } else {
        ASSERT_EQ(c & ~kOutputRounding, 0) << x << "," << y << " classes " << c;
      }
    }
  EXPECT_EQ(expected, 204 * 26 * 4);
  EXPECT_EQ(blended, expected);
}

namespace {
// A 16 x 16 frame filled by one "textured" quad over a 16 x 16 mipmapped texture of one-texel
// vertical stripes (black, white), with s from 0 to 1.25 across and t = 1/2: 1.25 texels per pixel,
// lambda = log2(1.25) = 0.32, between the mag/min switch points c = 0 and c = 1/2, 1/16 or more from both.
CommandList switchFrame(Filter mag) {
  SamplerState s;
  s.minFilter = Filter::NearestMipmapNearest;
  s.magFilter = mag;
  // t is constant, so rho = |ds/dx| exactly under every legal rho rule (GL 4.6 eq. 8.7's bounds meet).
  return stripeQuadFrame(
      16, 16, 16,
      [](uint32_t x) { return x % 2 ? std::array<uint8_t, 4>{255, 255, 255, 255} : std::array<uint8_t, 4>{0, 0, 0, 255}; },
      true, s, {glm::vec4{0, 0.5f, 0, 0}, {1.25f, 0.5f, 0, 0}, {1.25f, 0.5f, 0, 0}, {0, 0.5f, 0, 0}});
}
}  // namespace

TEST(ProvenanceClasses, TheHalfSwitchPointIsALegalAlternativeOnlyForMagLinearWithNearestMipmaps) {
  // GL 4.6 §8.14: with mag LINEAR and min NEAREST_MIPMAP_NEAREST the switch point may be c = 1/2, so at
  // lambda = 0.32 GL may magnify: LINEAR between a black and a white texel gives greys where the
  // oracle (c = 0: NEAREST on level 0) gives 0 or 255. Those pixels must be LOD_NEAR_SWITCH with an
  // interval that reaches the grey. With mag NEAREST both switch points give NEAREST on
  // level 0: no LOD_NEAR_SWITCH anywhere.
  const ProvImage lin = renderProvenance(switchFrame(Filter::Linear));
  const ProvImage near = renderProvenance(switchFrame(Filter::Nearest));
  int grey = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      ASSERT_TRUE(lin.val(x, y) == 0 || lin.val(x, y) == 255) << x << "," << y;
      ASSERT_EQ(near.classes(x, y) & kLodNearSwitch, 0) << x << "," << y;
      if ((lin.classes(x, y) & kLodNearSwitch) && lin.high(x, y) - lin.low(x, y) >= 31) ++grey;
    }
  // The texel coordinate 1.25 (x + 1/2) - 1/2 has the fraction 1/8, 3/8, 5/8 or 7/8: LINEAR moves the
  // nearest texel's 0 or 255 by 1/8 or 3/8 of 255 (32 or 96) at every pixel.
  EXPECT_EQ(grey, 16 * 16);
}

namespace {
// A 16 x 16 frame filled by one "textured" quad over a 16 x 16 texture, LINEAR, CLAMP_TO_EDGE: texel
// columns 0-7 black, 8-15 white, every row alike. s and t run from 0 to 1 across the quad, so pixel
// (x, y) looks up the exact texel centre (x + 1/2, y + 1/2): weights 0 and 1 (lambda = 0, LINEAR for
// magnification and minification alike).
CommandList texelCentreFrame() {
  SamplerState s;
  s.minFilter = Filter::Linear;
  s.magFilter = Filter::Linear;
  s.wrapS = s.wrapT = Wrap::ClampToEdge;
  return stripeQuadFrame(
      16, 16, 16,
      [](uint32_t x) { return x < 8 ? std::array<uint8_t, 4>{0, 0, 0, 255} : std::array<uint8_t, 4>{255, 255, 255, 255}; },
      false, s, {glm::vec4{0, 0, 0, 0}, {1, 0, 0, 0}, {1, 1, 0, 0}, {0, 1, 0, 0}});
}
}  // namespace

TEST(ProvenanceClasses, ALinearLookupAtATexelCentreGetsNoFilterPrecisionWideningWhereItsTexelsAgree) {
  // FILTER_PRECISION (docs/crosscheck.md) bounds the rounding of a filter that blends different
  // texels with weights not in {0, 1}. At a texel centre the oracle's weights are 0 and 1; the
  // coordinate tolerance (1/128 px of 1/16 texel per pixel, plus 1/512 texel) reaches weights of a few
  // 256ths towards the neighbours, which changes nothing while the neighbours hold the same value.
  // Columns 1-6 and 9-14: every texel in reach agrees, so the pixel is exact, without a class (before,
  // each LINEAR lookup was widened by 1 LSB: [0, 1] and [254, 255]). Columns 7 and 8 reach the other
  // colour: the blended alternatives are widened, by 1 LSB beyond the blend itself.
  const ProvImage p = renderProvenance(texelCentreFrame());
  for (int y = 1; y < 15; ++y)
    for (int x = 0; x < 16; ++x) {
      const uint8_t v = x < 8 ? 0 : 255;
      ASSERT_EQ(p.val(x, y, 0), v) << x << "," << y;
      if ((x >= 1 && x <= 6) || (x >= 9 && x <= 14)) {
        EXPECT_EQ(p.classes(x, y) & kFilterPrecision, 0) << x << "," << y;
        EXPECT_TRUE(p.exact(x, y)) << x << "," << y << ": " << int(p.low(x, y)) << ".." << int(p.high(x, y));
      } else if (x == 7 || x == 8) {
        EXPECT_NE(p.classes(x, y) & kFilterPrecision, 0) << x << "," << y;
        // A weight of at most 3/256 on the other colour moves the value by at most 3 LSB (255 * 3 / 256
        // = 2.99), plus the 1 LSB of FILTER_PRECISION.
        const int reach = x == 7 ? p.high(x, y) : 255 - p.low(x, y);
        EXPECT_GE(reach, 2) << x << "," << y;
        EXPECT_LE(reach, 4) << x << "," << y;
      }
    }
}

TEST(ProvenanceLookups, TwoLookupsWithSeveralCandidatesInOneFragmentAreCountedForTheHullFallback) {
  // An R8 8 x 8 texture, NEAREST_MIPMAP_NEAREST: level 0 flat 0, level 1 flat 255, the rest 100. A quad
  // with ds/dx = 2^0.47 / 8 (t constant) has lambda = 0.47: level 0 for the oracle, level 1 legal too
  // (1/16 LOD tolerance), so each lookup has two candidates, {0} and {255}. The sampler counts, in the
  // lower-bound hull run, how many lookups of each pixel had several candidates; with two, the
  // rasterizer keeps the hull runs and flags the pixel kLookupFallback (rast_provenance.cpp).
  TextureDesc d;
  d.kind = TextureKind::Tex2D;
  d.format = Format::R8;
  d.width = d.height = 8;
  d.levels = 4;
  TextureData tex(d);
  for (uint32_t l = 0; l < 4; ++l)
    std::fill(tex.levels[l].begin(), tex.levels[l].end(), uint8_t(l == 0 ? 0 : (l == 1 ? 255 : 100)));
  SamplerState ss;
  ss.minFilter = Filter::NearestMipmapNearest;
  ss.magFilter = Filter::Nearest;
  TexUnit u;
  u.tex = &tex;
  u.sampler = SamplerQ::from(ss);
  const float k = 1.385109f / 8.0f;  // 2^0.47 texels per pixel
  const float s[4] = {0.3f, 0.3f + k, 0.3f, 0.3f + k}, t[4] = {0.5f, 0.5f, 0.5f, 0.5f};
  ShadeProvenance& sp = shadeProvenance();
  sp.active = true;
  sp.resetPixels();
  float out[4][4];
  sp.bound = SampleBound::Lo;
  sampleQuad2D(u, s, t, 0.0f, out);  // one lookup
  for (int p = 0; p < 4; ++p) {
    EXPECT_EQ(sp.forkingLookups[size_t(p)], 1) << p;
    EXPECT_EQ(sp.lookupCandidates[size_t(p)], 2) << p;
    EXPECT_EQ(out[p][0], 0.0f) << "the hull's lower bound: level 0";
  }
  sampleQuad2D(u, s, t, 0.0f, out);  // a second one in the same fragment
  for (int p = 0; p < 4; ++p) EXPECT_EQ(sp.forkingLookups[size_t(p)], 2) << p;
  // The candidates themselves: candidate 1 is level 1 in both bounds, candidate 0 the oracle's level 0.
  sp.candidate = 1;
  sampleQuad2D(u, s, t, 0.0f, out);
  for (int p = 0; p < 4; ++p) EXPECT_EQ(out[p][0], 1.0f) << p;
  sp.candidate = 0;
  sp.bound = SampleBound::Hi;
  sampleQuad2D(u, s, t, 0.0f, out);
  for (int p = 0; p < 4; ++p) EXPECT_EQ(out[p][0], 0.0f) << p;
  // Counting happens only in the lower-bound hull run.
  for (int p = 0; p < 4; ++p) EXPECT_EQ(sp.forkingLookups[size_t(p)], 2) << p;
  sp.resetPixels();
  sp.active = false;
  sp.bound = SampleBound::Value;
}

}  // namespace tessera::scenes
