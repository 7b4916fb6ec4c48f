// Fragment depth in the programs: gl_FragCoord.z (Quad::z) is the depth the test compares, and a
// program that writes gl_FragDepth (Program::writesDepth) has the depth test and write use its
// value, clamped to [0, 1] (docs/spec-choices.md F11). Exercised through the render-to-texture-atlas
// programs atlas_capture (reads gl_FragCoord.z) and atlas_sprite (writes gl_FragDepth), and the
// scenes atlas_capture and atlas_sprites.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "raster/provenance.h"
#include "raster/texture.h"
#include "tools/scenes/builder.h"
#include "tools/scenes/scenes.h"

namespace tessera::scenes {

namespace {

float texelF(const TextureData& t, uint32_t layer, int x, int y, int channel) {
  float v;
  std::memcpy(&v, t.texel(0, layer, uint32_t(x), uint32_t(y)) + 4 * channel, 4);
  return v;
}

const TextureData* findTexture(const CpuBackend& b, Format f, uint32_t w) {
  for (ResourceId id = 0; id < 64; ++id)
    if (const TextureData* t = b.texture(id); t && t->desc.format == f && t->desc.width == w) return t;
  return nullptr;
}

// An 8x8 one-layer layered target (RGBA8 + RG32F + D32F) and one quad through atlas_capture with an
// identity record (layer 0, no displacement) and an identity MVP: the quad's clip position is its
// attribute, so window depth = z / 2 + 1/2. Corner z values z0..z3 (counter-clockwise from (-1, -1)).
// `depthTest` false draws with the depth test off, where only the program reads the depth.
CommandList captureQuad(float z0, float z1, float z2, float z3, bool depthTest = true) {
  CommandList cl;
  TextureDesc d;
  d.kind = TextureKind::Tex2DArray;
  d.width = d.height = 8;
  d.layers = 1;
  d.format = Format::RGBA8;
  RenderTarget rt;
  rt.color[0] = cl.createTexture(d);
  d.format = Format::RG32F;
  rt.color[1] = cl.createTexture(d);
  d.format = Format::D32F;
  rt.depth = cl.createTexture(d);
  rt.layer = kLayered;
  cl.setRenderTarget(rt);
  cl.setViewport({0, 0, 8, 8});
  cl.clearColor(0, {0, 0, 0, 0});
  cl.clearColor(1, {1, 0, 0, 0});
  cl.clearDepth(1.0f);
  Mesh m;
  // Corners a little inside the target so that no pixel centre lies on an edge.
  m.quad({-0.9f, -0.9f, z0}, {0.9f, -0.9f, z1}, {0.9f, 0.9f, z2}, {-0.9f, 0.9f, z3}, {0, 0, 0, 0}, {1, 0, 0, 0},
         {1, 1, 0, 0}, {0, 1, 0, 0}, 0);
  const uint32_t n = bindMesh(cl, m);
  const float rec[8] = {1, 0, 0, 1, 0, 0, 0, 0};
  TextureDesc rd;
  rd.kind = TextureKind::Buffer;
  rd.format = Format::RGBA32F;
  rd.width = 2;
  rd.buffer = cl.createBuffer(BufferKind::Texel, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(rec), sizeof rec));
  cl.bindTexture(0, cl.createTexture(rd));
  cl.bindTexture(1, uploadTexture(cl, checker(4, 4, 2, {200, 100, 50, 0}, {20, 40, 60, 0}), false));
  cl.useProgram(cl.createProgram("atlas_capture"));
  setMatrix(cl, 0, glm::mat4(1.0f));
  setVec4(cl, 7, {1, 1, 1, 1});
  DepthState ds;
  ds.test = depthTest;
  cl.setDepthState(ds);
  cl.drawIndexed(0, n);
  return cl;
}

// A 4x1 frame with depth (cleared to depth 1, colour black) and one 4x1 sprite of atlas_sprite over a
// 4x1 one-layer atlas: colour white, depth texel x = depths[x], all covered; depth function `func`.
CommandList spriteRow(const float (&depths)[4], CompareFunc func) {
  CommandList cl;
  TextureDesc cd;
  cd.kind = TextureKind::Tex2DArray;
  cd.width = 4;
  cd.height = 1;
  cd.layers = 1;
  const ResourceId colour = cl.createTexture(cd);
  TextureDesc dd = cd;
  dd.format = Format::RG32F;
  const ResourceId depth = cl.createTexture(dd);
  const std::vector<uint8_t> white(16, 255);
  cl.uploadTexture(colour, 0, 0, white);
  float dz[8];
  for (int x = 0; x < 4; ++x) dz[2 * x] = depths[x], dz[2 * x + 1] = 1.0f;
  cl.uploadTexture(depth, 0, 0, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(dz), sizeof dz));
  RenderTarget rt;
  rt.color[0] = createTarget(cl, Format::RGBA8, 4, 1);
  rt.depth = createTarget(cl, Format::D32F, 4, 1);
  cl.setRenderTarget(rt);
  cl.setViewport({0, 0, 4, 1});
  cl.clearColor(0, {0, 0, 0, 1});
  cl.clearDepth(1.0f);
  DepthState ds;
  ds.test = true;
  ds.func = func;
  cl.setDepthState(ds);
  // Two triangles over the whole target, shift (0, 0), layer 0.
  const float v[6][8] = {{-1, -1, 0, 1, 0, 0, 0, 0}, {1, -1, 0, 1, 0, 0, 0, 0}, {1, 1, 0, 1, 0, 0, 0, 0},
                         {-1, -1, 0, 1, 0, 0, 0, 0}, {1, 1, 0, 1, 0, 0, 0, 0},  {-1, 1, 0, 1, 0, 0, 0, 0}};
  cl.bindVertexBuffer(cl.createBuffer(BufferKind::Vertex, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(v), sizeof v)));
  VertexLayout l;
  l.stride = 32;
  l.attribs[0] = {0, 4, AttribType::F32, 0};
  l.attribs[2] = {2, 4, AttribType::F32, 16};
  cl.setVertexLayout(l);
  cl.bindTexture(0, colour);
  cl.bindTexture(1, depth);
  cl.useProgram(cl.createProgram("atlas_sprite"));
  setVec4(cl, 7, {1, 1, 1, 1});
  cl.draw(0, 6);
  return cl;
}

// Pixel (x, y) (GL window coordinates, y up) of presented RGBA8 image `img` of size w x h.
const uint8_t* pixel(const std::vector<uint8_t>& img, int w, int h, int x, int y) {
  return &img[(size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4];
}

}  // namespace

TEST(FragCoordZ, AProgramReadingGlFragCoordZGetsExactlyTheDepthTheDepthTestStores) {
  // A sloped quad, one draw, depth LESS over a clear of 1: every covered pixel passes and stores its
  // interpolated depth, which atlas_capture also writes as output 1's first channel.
  CpuBackend b(RenderOptions{2});
  b.execute(captureQuad(-0.8f, 0.1f, 0.7f, -0.2f), "fragcoord");
  const TextureData* rg = findTexture(b, Format::RG32F, 8);
  const TextureData* dz = findTexture(b, Format::D32F, 8);
  ASSERT_TRUE(rg && dz);
  int covered = 0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const float z = texelF(*dz, 0, x, y, 0);
      if (texelF(*rg, 0, x, y, 1) == 0.0f) {  // not covered: both keep their clears
        EXPECT_EQ(z, 1.0f) << x << "," << y;
        EXPECT_EQ(texelF(*rg, 0, x, y, 0), 1.0f) << x << "," << y;
        continue;
      }
      ++covered;
      EXPECT_EQ(texelF(*rg, 0, x, y, 0), z) << x << "," << y;
      EXPECT_GT(z, 0.05f);  // between the corners' window depths 0.1 and 0.85
      EXPECT_LT(z, 0.9f);
    }
  // Corners at +-0.9 NDC = window 0.4 .. 7.6: pixel centres 0.5 .. 7.5, all 64 pixels.
  EXPECT_EQ(covered, 64);
}

TEST(FragCoordZ, AFlatQuadAtNdcDepthOneHalfReadsWindowDepthThreeQuarters) {
  // z_w = z_ndc / 2 + 1/2 (GL 4.6 §13.8.1, depth range [0, 1]) = 0.75 exactly, at every pixel.
  CpuBackend b(RenderOptions{2});
  b.execute(captureQuad(0.5f, 0.5f, 0.5f, 0.5f), "flat");
  const TextureData* rg = findTexture(b, Format::RG32F, 8);
  ASSERT_TRUE(rg);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      EXPECT_EQ(texelF(*rg, 0, x, y, 0), 0.75f) << x << "," << y;
      EXPECT_EQ(texelF(*rg, 0, x, y, 1), 1.0f) << x << "," << y;
    }
}

TEST(FragCoordZ, AProgramReadsGlFragCoordZWithTheDepthTestOffAndTheDepthBufferKeepsItsClear) {
  // gl_FragCoord.z does not depend on the depth test (GL 4.6 §15.2.2); with the test disabled nothing
  // is written to the depth buffer (§17.3.4). The rasterizer must still interpolate the depth for the
  // program (DrawConsts::depthsRead), which no other frame exercises without a depth test.
  CpuBackend b(RenderOptions{2});
  b.execute(captureQuad(0.5f, 0.5f, 0.5f, 0.5f, false), "flat, no depth test");
  const TextureData* rg = findTexture(b, Format::RG32F, 8);
  const TextureData* dz = findTexture(b, Format::D32F, 8);
  ASSERT_TRUE(rg && dz);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      EXPECT_EQ(texelF(*rg, 0, x, y, 0), 0.75f) << x << "," << y;
      EXPECT_EQ(texelF(*rg, 0, x, y, 1), 1.0f) << x << "," << y;
      EXPECT_EQ(texelF(*dz, 0, x, y, 0), 1.0f) << x << "," << y;
    }
  // A sloped quad reads the same depths as with the test on (where every pixel passes over the clear).
  CpuBackend on(RenderOptions{2}), off(RenderOptions{2});
  on.execute(captureQuad(-0.8f, 0.1f, 0.7f, -0.2f), "sloped, depth test");
  off.execute(captureQuad(-0.8f, 0.1f, 0.7f, -0.2f, false), "sloped, no depth test");
  const TextureData* rgOn = findTexture(on, Format::RG32F, 8);
  const TextureData* rgOff = findTexture(off, Format::RG32F, 8);
  ASSERT_TRUE(rgOn && rgOff);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 2; ++c) EXPECT_EQ(texelF(*rgOff, 0, x, y, c), texelF(*rgOn, 0, x, y, c)) << x << "," << y;
}

TEST(FragDepth, AWrittenFragmentDepthDecidesTheDepthTestNotTheDrawOrder) {
  // atlas_sprites (scene_atlas_sprites.cpp): sprite B (drawn after A) has depth 0.3 + (bx - 16) / 16 at
  // atlas column bx = screen x - 12, A has 0.25 + ax / 64 at ax = screen x - 20. At screen x = 28 B's
  // 0.3 beats A's 0.375; at x = 31 A's 0.421875 beats B's 0.4875. Row y = 20: A's texel (ax, 4), B's (bx, 10).
  CpuBackend b(RenderOptions{2});
  b.execute(build("atlas_sprites", 64, 64), "sprites");
  const PresentedImage p = b.presented().at(0);
  const std::vector<uint8_t> img = imagePixels(*b.texture(p.texture), 0, 0);
  const TextureData* dz = findTexture(b, Format::D32F, 64);
  ASSERT_TRUE(dz);
  // B at (28, 20): colour (30, 90, 100) (row 10: (10 / 2) & 1 = 1 -> 90; column 16 -> 100).
  const uint8_t* pb = pixel(img, 64, 64, 28, 20);
  EXPECT_EQ(pb[0], 30);
  EXPECT_EQ(pb[1], 90);
  EXPECT_EQ(pb[2], 100);
  EXPECT_EQ(pb[3], 255);
  EXPECT_EQ(texelF(*dz, 0, 28, 20, 0), 0.3f);
  // A at (31, 20): texel (11, 4) = (120 + 88, 40 + 16, 30).
  const uint8_t* pa = pixel(img, 64, 64, 31, 20);
  EXPECT_EQ(pa[0], 208);
  EXPECT_EQ(pa[1], 56);
  EXPECT_EQ(pa[2], 30);
  EXPECT_EQ(pa[3], 255);
  EXPECT_EQ(texelF(*dz, 0, 31, 20, 0), 0.421875f);
  // B at (41, 20): column bx = 29, depth 0.3 + 13/16 = 1.1125, clamped to 1 (F11): not less than the
  // clear depth 1, so the clear colour (0.2, 0.2, 0.25) -> (51, 51, 64) stays.
  const uint8_t* pc = pixel(img, 64, 64, 41, 20);
  EXPECT_EQ(pc[0], 51);
  EXPECT_EQ(pc[1], 51);
  EXPECT_EQ(pc[2], 64);
  EXPECT_EQ(texelF(*dz, 0, 41, 20, 0), 1.0f);
}

TEST(AtlasSprite, AnEmptyAtlasTexelIsDiscardedAndShowsWhatLiesBehind) {
  // Screen (26, 32) is A's texel (6, 16), inside A's empty disc (radius 4 around (8, 16)); behind it
  // C's texel (22, 28) of layer 1: checker cell (5 + 7) & 1 = 0, light (200, 210, 90), depth 0.7.
  CpuBackend b(RenderOptions{2});
  b.execute(build("atlas_sprites", 64, 64), "sprites");
  const PresentedImage p = b.presented().at(0);
  const std::vector<uint8_t> img = imagePixels(*b.texture(p.texture), 0, 0);
  const uint8_t* c = pixel(img, 64, 64, 26, 32);
  EXPECT_EQ(c[0], 200);
  EXPECT_EQ(c[1], 210);
  EXPECT_EQ(c[2], 90);
  EXPECT_EQ(texelF(*findTexture(b, Format::D32F, 64), 0, 26, 32, 0), 0.7f);
  // Discarded fragments: A's disc, the integer (dx, dy) with dx^2 + dy^2 < 16: 7 + 2 * 7 + 2 * 7 + 2 * 5
  // = 45; C's 2-texel border: 32^2 - 28^2 = 240. B has no empty texel.
  EXPECT_EQ(b.stats().fragments_discarded, 285u);
}

TEST(FragDepth, AFragmentDepthOutsideTheDepthRangeIsClampedBeforeTheTestAndTheWrite) {
  // F11: the written depth is clamped to [0, 1], NaN -> 0. Under ALWAYS every fragment writes: -0.5 -> 0,
  // 2 -> 1, NaN -> 0, 0.5 stays.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  {
    CpuBackend b(RenderOptions{2});
    b.execute(spriteRow({-0.5f, 2.0f, nan, 0.5f}, CompareFunc::Always), "clamp");
    const TextureData* dz = findTexture(b, Format::D32F, 4);
    ASSERT_TRUE(dz);
    EXPECT_EQ(texelF(*dz, 0, 0, 0, 0), 0.0f);
    EXPECT_EQ(texelF(*dz, 0, 1, 0, 0), 1.0f);
    EXPECT_EQ(texelF(*dz, 0, 2, 0, 0), 0.0f);
    EXPECT_EQ(texelF(*dz, 0, 3, 0, 0), 0.5f);
  }
  // Under LESS over the clear depth 1: 2 clamps to 1, which is not less than 1, so that pixel keeps the
  // black clear colour; the others are written white.
  CpuBackend b(RenderOptions{2});
  b.execute(spriteRow({-0.5f, 2.0f, nan, 0.5f}, CompareFunc::Less), "clamp less");
  const PresentedImage p = b.presented().at(0);
  const std::vector<uint8_t> img = imagePixels(*b.texture(p.texture), 0, 0);
  EXPECT_EQ(img[0], 255);
  EXPECT_EQ(img[4], 0);
  EXPECT_EQ(img[8], 255);
  EXPECT_EQ(img[12], 255);
  EXPECT_EQ(b.stats().fragments_depth_failed, 1u);
}

TEST(FragDepth, ProvenanceModeFindsNoDepthOrDiscardFreedomInSpritesFromExactTexels) {
  // The sprites' depth and coverage flag are texelFetches of uploaded textures (exact, spread 0) and
  // their edges lie on pixel edges: no depth test, discard or coverage may go another way in GL, even
  // where B's clamped depth 1 meets the clear depth 1 (an exact comparison, F11). Only the comparator's
  // generic output-rounding allowance for a colour gradient inside a quad may class a pixel.
  CpuBackend b(RenderOptions{2, true, {}, 8});
  b.execute(build("atlas_sprites", 64, 64), "sprites prov");
  const PresentedImage p = b.presented().at(0);
  const TextureData& t = *b.texture(p.texture);
  CpuBackend fast(RenderOptions{2});
  fast.execute(build("atlas_sprites", 64, 64), "sprites");
  EXPECT_EQ(imagePixels(t, 0, 0), imagePixels(*fast.texture(fast.presented().at(0).texture), 0, 0));
  const uint16_t discrete = kDepthNearEqual | kAlphaTest | kEdgeTie | kClipEdge | kInputInterval;
  for (size_t i = 0; i < t.prov->classes[0].size(); ++i)
    EXPECT_EQ(t.prov->classes[0][i] & discrete, 0) << i % 64 << "," << i / 64;
}

}  // namespace tessera::scenes
