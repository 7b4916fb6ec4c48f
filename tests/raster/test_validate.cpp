// validate(): every diagnostic on a minimal list that triggers it, and none on a correct frame.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <string>

#include "raster/program.h"
#include "raster/validate.h"
#include "tests/raster/validate_test_util.h"

namespace tessera {
namespace {

using testing::dump;

template <class T>
std::span<const uint8_t> asBytes(const std::vector<T>& v) {
  return {reinterpret_cast<const uint8_t*>(v.data()), v.size() * sizeof(T)};
}

// Vertex format of the test frames: vec4 position at location 0, one U32 at location 1.
struct Vertex {
  float pos[4];
  uint32_t id;
};
static_assert(sizeof(Vertex) == 20);

VertexLayout vertexLayout() {
  VertexLayout l;
  l.stride = sizeof(Vertex);
  l.attribs[0] = {0, 4, AttribType::F32, 0};
  l.attribs[1] = {1, 1, AttribType::U32, 16};
  return l;
}

std::vector<Vertex> quad() { return {{{-1, -1, 0, 1}, 0}, {{1, -1, 0, 1}, 1}, {{1, 1, 0, 1}, 2}, {{-1, 1, 0, 1}, 3}}; }

std::string programName() { return std::string(programNames().at(0)); }

// What the ready-to-draw frame leaves out, to test each missing piece alone.
struct Omit {
  bool program = false, vertexBuffer = false, layout = false, target = false, indexBuffer = false;
};

// A frame with every resource created and bound, ready for draws: a 4x4 mipmapped texture on unit
// 0, an 8x8 RGBA8 + D32F target, 4 vertices, 6 U16 indices.
struct Frame {
  CommandList l;
  ResourceId tex = 0, smp = 0, prog = 0, vb = 0, ib = 0, color = 0, depth = 0;

  explicit Frame(const std::vector<Vertex>& vertices = quad(), Omit omit = {}) {
    const TextureDesc texDesc{TextureKind::Tex2D, Format::RGBA8, 4, 4, 1, 3};
    tex = l.createTexture(texDesc);
    for (uint32_t level = 0; level < 3; ++level) {
      l.uploadTexture(tex, level, 0, std::vector<uint8_t>(size_t(levelBytes(texDesc, level)), 0x80));
    }
    smp = l.createSampler({});
    prog = l.createProgram(programName());
    vb = l.createBuffer(BufferKind::Vertex, asBytes(vertices));
    ib = l.createBuffer(BufferKind::Index, asBytes(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}));
    color = l.createTexture({TextureKind::Tex2D, Format::RGBA8, 8, 8, 1, 1});
    depth = l.createTexture({TextureKind::Tex2D, Format::D32F, 8, 8, 1, 1});
    l.bindTexture(0, tex);
    l.bindSampler(0, smp);
    if (!omit.program) l.useProgram(prog);
    if (!omit.program) l.setUniforms(0, std::vector<float>{1, 0, 0, 1, 0.5f, 0.5f, 0, 0});
    if (!omit.vertexBuffer) l.bindVertexBuffer(vb);
    if (!omit.layout) l.setVertexLayout(vertexLayout());
    if (!omit.indexBuffer) l.bindIndexBuffer(ib, IndexType::U16);
    l.setViewport({0, 0, 8, 8});
    l.setScissor({true, {1, 1, 6, 6}});
    l.setDepthState({true, true, CompareFunc::LEqual});
    l.setBlendState({});
    l.setRasterState({CullMode::Back, true, 0});
    if (!omit.target) {
      RenderTarget t;
      t.color[0] = color;
      t.depth = depth;
      l.setRenderTarget(t);
    }
  }
  size_t last() const { return l.commands().size() - 1; }
};

// Exactly one diagnostic, on the last command, containing `text`.
void expectOnlyOnLast(const CommandList& l, std::string_view text) {
  const auto diags = validate(l);
  ASSERT_EQ(diags.size(), 1u) << dump(diags);
  EXPECT_EQ(diags[0].command, l.commands().size() - 1) << dump(diags);
  EXPECT_NE(diags[0].message.find(text), std::string::npos) << dump(diags);
}

// At least one diagnostic on the last command containing `text`, none elsewhere.
void expectOnLast(const CommandList& l, std::string_view text) {
  const auto diags = validate(l);
  ASSERT_FALSE(diags.empty()) << "no diagnostic, expected \"" << text << "\"";
  bool found = false;
  for (const auto& d : diags) {
    EXPECT_EQ(d.command, l.commands().size() - 1) << dump(diags);
    found = found || d.message.find(text) != std::string::npos;
  }
  EXPECT_TRUE(found) << "expected \"" << text << "\" in" << dump(diags);
}

TEST(Validate, ACorrectFrameHasNoDiagnostics) {
  Frame f;
  f.l.clearColor(0, {0, 0, 0, 1});
  f.l.clearDepth(1.0f);
  f.l.draw(0, 3);
  f.l.drawIndexed(0, 6);
  f.l.draw(1, 3);
  f.l.marker("done");
  EXPECT_TRUE(validate(f.l).empty()) << dump(validate(f.l));
  EXPECT_NO_THROW(validateOrThrow(f.l, "good"));
}

// --- resource ids ----------------------------------------------------------------------------

TEST(Validate, AnUnknownResourceIdIsReported) {
  Frame f;
  f.l.bindTexture(1, 99);
  expectOnlyOnLast(f.l, "texture id 99 does not exist");
}

TEST(Validate, AResourceOfTheWrongKindIsReported) {
  Frame f;
  f.l.bindTexture(1, f.smp);
  expectOnlyOnLast(f.l, "is a sampler");
  Frame g;
  g.l.useProgram(g.tex);
  expectOnlyOnLast(g.l, "is a texture");
  Frame h;
  h.l.bindVertexBuffer(h.ib);
  expectOnlyOnLast(h.l, "is a Index buffer, BindVertexBuffer needs a Vertex buffer");
  Frame i;
  i.l.bindIndexBuffer(i.vb, IndexType::U16);
  expectOnlyOnLast(i.l, "BindIndexBuffer needs a Index buffer");
}

TEST(Validate, ADuplicateCreateIsReported) {
  Frame f;
  f.l.appendRaw(CreateSampler{f.tex, {}});
  expectOnlyOnLast(f.l, "duplicate create of id 1");
}

TEST(Validate, ACreateOutOfOrderIsReported) {
  Frame f;
  f.l.appendRaw(CreateSampler{f.l.nextId() + 5, {}});
  expectOnlyOnLast(f.l, "out of creation order");
  Frame g;
  g.l.appendRaw(CreateSampler{0, {}});
  expectOnlyOnLast(g.l, "id 0 is reserved");
}

// --- textures --------------------------------------------------------------------------------

TEST(Validate, InvalidTextureDescriptionsAreReported) {
  constexpr ResourceId kTexel = 0xfffffff0u;  // stands for the Texel buffer made below (id 8)
  struct Case {
    TextureDesc desc;
    std::string_view text;
  };
  const Case cases[] = {
      {{TextureKind::Tex2D, Format::RGBA8, 0, 4, 1, 1}, "size 0x4 is out of range"},
      {{TextureKind::Tex2D, Format::RGBA8, 4, 16385, 1, 1}, "size 4x16385 is out of range"},
      {{TextureKind::Tex2D, Format::RGBA8, 4, 4, 2, 1}, "desc.layers = 2 is out of range (1..1)"},
      {{TextureKind::Tex2DArray, Format::RGBA8, 4, 4, 2049, 1}, "desc.layers = 2049 is out of range (1..2048)"},
      {{TextureKind::Tex2DArray, Format::RGBA8, 4, 4, 0, 1}, "desc.layers = 0"},
      {{TextureKind::Tex2D, Format::RGBA8, 4, 4, 1, 4}, "desc.levels = 4 is out of range (1..3 for 4x4)"},
      {{TextureKind::Tex2D, Format::RGBA8, 4, 4, 1, 0}, "desc.levels = 0"},
      {{TextureKind::Tex2D, Format::RGBA8, 4, 4, 1, 1, 2}, "only meaningful for Buffer textures"},
      {{TextureKind::Buffer, Format::RGBA8, 4, 1, 1, 1, kNone}, "needs a Texel buffer"},
      {{TextureKind::Buffer, Format::RGBA8, 4, 1, 1, 1, 4}, "is a Vertex buffer, a Buffer texture needs a Texel"},
      {{TextureKind::Buffer, Format::D32F, 4, 1, 1, 1, kTexel}, "cannot have format D32F"},
      {{TextureKind::Buffer, Format::RGBA32F, 4, 1, 1, 1, kTexel}, "need 64 bytes but buffer 8 has 32"},
      {{TextureKind::Buffer, Format::R8, 0, 1, 1, 1, kTexel}, "desc.width = 0 texels is out of range"},
      {{TextureKind::Buffer, Format::R8, 4, 2, 1, 1, kTexel}, "height, layers and levels = 1"},
  };
  for (const Case& c : cases) {
    Frame f;
    const ResourceId texel = f.l.createBuffer(BufferKind::Texel, 32);
    TextureDesc d = c.desc;
    if (d.buffer == kTexel) d.buffer = texel;
    f.l.createTexture(d);
    SCOPED_TRACE(std::string(c.text));
    expectOnLast(f.l, c.text);
  }
}

TEST(Validate, LegalTextureDescriptionsAtTheLimitsAreAccepted) {
  Frame f;
  const ResourceId texel = f.l.createBuffer(BufferKind::Texel, 64);
  f.l.createTexture({TextureKind::Buffer, Format::R32UI, 16, 1, 1, 1, texel});
  f.l.createTexture({TextureKind::Tex2DArray, Format::R8, 1, 1, 2048, 1});
  f.l.createTexture({TextureKind::Tex2D, Format::RG32F, 16384, 1, 1, 15});
  f.l.createTexture({TextureKind::Tex2D, Format::R32UI, 3, 5, 1, 3});
  EXPECT_TRUE(validate(f.l).empty()) << dump(validate(f.l));
}

TEST(Validate, AnUploadOfTheWrongSizeIsReported) {
  Frame f;
  f.l.uploadTexture(f.tex, 1, 0, std::vector<uint8_t>(15));
  expectOnlyOnLast(f.l, "data has 15 bytes but level 1 of texture 1 (2x2 RGBA8) has 16");
}

TEST(Validate, AnUploadToALevelOrLayerOutOfRangeIsReported) {
  Frame f;
  f.l.uploadTexture(f.tex, 3, 0, std::vector<uint8_t>(4));
  expectOnlyOnLast(f.l, "level 3 is out of range (texture 1 has 3 levels)");
  Frame g;
  g.l.uploadTexture(g.tex, 0, 1, std::vector<uint8_t>(64));
  expectOnlyOnLast(g.l, "layer 1 is out of range (texture 1 has 1 layers)");
}

TEST(Validate, AnUploadToABufferTextureIsReported) {
  Frame f;
  const ResourceId texel = f.l.createBuffer(BufferKind::Texel, 16);
  const ResourceId bt = f.l.createTexture({TextureKind::Buffer, Format::RGBA8, 4, 1, 1, 1, texel});
  f.l.uploadTexture(bt, 0, 0, std::vector<uint8_t>(16));
  expectOnlyOnLast(f.l, "upload its buffer instead");
}

TEST(Validate, ABufferUploadOutOfRangeIsReported) {
  Frame f;
  f.l.uploadBuffer(f.vb, 4 * sizeof(Vertex) - 2, std::vector<uint8_t>(4));
  expectOnlyOnLast(f.l, "bytes [78, +4) are out of range of buffer 4 (80 bytes)");
  Frame g;
  g.l.uploadBuffer(g.vb, std::numeric_limits<uint64_t>::max(), std::vector<uint8_t>(4));
  expectOnlyOnLast(g.l, "out of range of buffer 4");
}

TEST(Validate, ABlobRangeOutsideTheBlobIsReported) {
  Frame f;
  f.l.appendRaw(UploadBuffer{f.vb, 0, BlobRange{f.l.blob().size() - 2, 4}});
  expectOnlyOnLast(f.l, "lies outside the blob");
}

// --- units, uniforms, samplers, programs -----------------------------------------------------

TEST(Validate, ATextureUnitBeyondTheLimitIsReported) {
  Frame f;
  f.l.bindTexture(16, f.tex);
  expectOnlyOnLast(f.l, "unit 16 is out of range (0..15)");
  Frame g;
  g.l.bindSampler(1000, g.smp);
  expectOnlyOnLast(g.l, "unit 1000 is out of range");
  Frame h;
  h.l.bindTexture(15, h.tex);
  h.l.bindSampler(15, h.smp);
  EXPECT_TRUE(validate(h.l).empty()) << dump(validate(h.l));
}

TEST(Validate, UniformSlotsBeyondTheLimitAreReported) {
  Frame f;
  f.l.setUniforms(62, std::vector<float>(12, 1.0f));
  expectOnlyOnLast(f.l, "slots [62, 65) exceed the 64 uniform slots");
  Frame g;
  g.l.setUniforms(60, std::vector<float>(16, 1.0f));  // exactly up to the last slot
  EXPECT_TRUE(validate(g.l).empty()) << dump(validate(g.l));
}

TEST(Validate, UniformsWithoutAProgramOrWithTheWrongDataSizeAreReported) {
  Frame f(quad(), Omit{.program = true});
  f.l.setUniforms(0, std::vector<float>(4, 1.0f));
  expectOnlyOnLast(f.l, "no program in use");
  Frame g;
  g.l.appendRaw(SetUniforms{0, 2, BlobRange{0, 16}});
  expectOnlyOnLast(g.l, "data has 16 bytes but 2 vec4 slots need 32");
}

TEST(Validate, ASamplerWithAMipmapMagFilterIsReported) {
  Frame f;
  SamplerState s;
  s.magFilter = Filter::LinearMipmapNearest;
  f.l.createSampler(s);
  expectOnlyOnLast(f.l, "magFilter must be Nearest or Linear");
}

TEST(Validate, ASamplerWithANonFiniteLodIsReported) {
  Frame f;
  SamplerState s;
  s.maxLod = std::numeric_limits<float>::infinity();
  f.l.createSampler(s);
  expectOnlyOnLast(f.l, "must be finite");
}

TEST(Validate, AnUnknownProgramNameIsReported) {
  Frame f;
  f.l.createProgram("no_such_program");
  expectOnlyOnLast(f.l, "program name \"no_such_program\" is not in the program registry");
}

// --- draws: missing state --------------------------------------------------------------------

TEST(Validate, ADrawWithoutAProgramIsReported) {
  Frame f(quad(), Omit{.program = true});
  f.l.draw(0, 3);
  expectOnlyOnLast(f.l, "no program in use");
}

TEST(Validate, ADrawWithoutAVertexBufferIsReported) {
  Frame f(quad(), Omit{.vertexBuffer = true});
  f.l.draw(0, 3);
  expectOnlyOnLast(f.l, "no vertex buffer bound");
}

TEST(Validate, ADrawWithoutAVertexLayoutIsReported) {
  Frame f(quad(), Omit{.layout = true});
  f.l.draw(0, 3);
  expectOnlyOnLast(f.l, "no vertex layout set");
}

TEST(Validate, ADrawWithoutARenderTargetIsReported) {
  Frame f(quad(), Omit{.target = true});
  f.l.draw(0, 3);
  expectOnlyOnLast(f.l, "no render target set");
}

TEST(Validate, AnIndexedDrawWithoutAnIndexBufferIsReported) {
  Frame f(quad(), Omit{.indexBuffer = true});
  f.l.draw(0, 3);
  EXPECT_TRUE(validate(f.l).empty()) << dump(validate(f.l));
  f.l.drawIndexed(0, 3);
  expectOnlyOnLast(f.l, "indexed draw without an index buffer");
}

// --- draws: indices and vertex fetch ---------------------------------------------------------

TEST(Validate, AnIndexRangeBeyondTheIndexBufferIsReported) {
  Frame f;
  f.l.drawIndexed(4, 3);
  expectOnlyOnLast(f.l, "indices [4, 7) read bytes [8, 14) past the end of index buffer 5 (12 bytes)");
  Frame g;
  g.l.drawIndexed(0xffffffffu, 0xffffffffu);  // first + count must not wrap around
  expectOnlyOnLast(g.l, "past the end of index buffer");
}

TEST(Validate, AnIndexBeyondTheVertexBufferIsReported) {
  Frame f;
  const ResourceId ib32 = f.l.createBuffer(BufferKind::Index, asBytes(std::vector<uint32_t>{0, 4, 1}));
  f.l.bindIndexBuffer(ib32, IndexType::U32);
  f.l.drawIndexed(0, 3);
  expectOnlyOnLast(
      f.l,
      "index 1 = vertex 4: attribute at location 0 reads bytes [80, 96) past the end of vertex buffer 4 (80 bytes)");
  Frame g;
  const ResourceId ib16 = g.l.createBuffer(BufferKind::Index, asBytes(std::vector<uint16_t>{0, 1, 2, 3, 9, 1}));
  g.l.bindIndexBuffer(ib16, IndexType::U16);
  g.l.drawIndexed(0, 3);
  g.l.drawIndexed(2, 3);  // indices are named by their position in the index buffer
  expectOnlyOnLast(g.l, "index 4 = vertex 9:");
}

TEST(Validate, ANonIndexedDrawBeyondTheVertexBufferIsReported) {
  Frame f;
  f.l.draw(2, 3);
  expectOnlyOnLast(f.l, "vertex 4: attribute at location 0 reads bytes [80, 96) past the end");
  Frame g;
  g.l.draw(0xfffffffeu, 3);
  expectOnlyOnLast(g.l, "beyond vertex index 2^32 - 1");
}

TEST(Validate, AnAttributeOffsetBeyondTheStrideIsCaughtAtTheLastVertex) {
  Frame f;
  VertexLayout l = vertexLayout();
  l.attribs[2] = {2, 2, AttribType::F32, 16};  // reads 8 bytes at 16: past the end for the last vertex
  f.l.setVertexLayout(l);
  f.l.draw(0, 3);
  EXPECT_TRUE(validate(f.l).empty()) << dump(validate(f.l));
  f.l.draw(1, 3);
  expectOnlyOnLast(f.l, "vertex 3: attribute at location 2 reads bytes [76, 84)");
}

TEST(Validate, NaNOrInfinityInAReferencedPositionIsReported) {
  auto vertices = quad();
  vertices[3].pos[1] = std::numeric_limits<float>::quiet_NaN();
  Frame f(vertices);
  f.l.draw(0, 3);  // vertex 3 is not referenced
  EXPECT_TRUE(validate(f.l).empty()) << dump(validate(f.l));
  f.l.draw(1, 3);
  expectOnlyOnLast(f.l, "vertex 3: position (location 0) component 1 is nan");

  vertices = quad();
  vertices[2].pos[3] = -std::numeric_limits<float>::infinity();
  Frame g(vertices);
  g.l.drawIndexed(0, 6);
  expectOnlyOnLast(g.l, "vertex 2: position (location 0) component 3 is -inf");
}

TEST(Validate, AU32AttributeOfTwoToThe24IsReported) {
  auto vertices = quad();
  vertices[1].id = (1u << 24) - 1;  // still exact
  Frame ok(vertices);
  ok.l.drawIndexed(0, 6);
  EXPECT_TRUE(validate(ok.l).empty()) << dump(validate(ok.l));
  vertices[1].id = 1u << 24;
  Frame f(vertices);
  f.l.drawIndexed(0, 6);
  expectOnlyOnLast(f.l, "vertex 1: U32 attribute at location 1 component 0 = 16777216 is >= 2^24");
}

TEST(Validate, BufferContentsAreThoseUploadedBeforeEachDraw) {
  auto bad = quad();
  bad[0].pos[0] = std::numeric_limits<float>::infinity();
  Frame f(bad);
  // Overwrite vertex 0 before the first draw: the draw sees good data.
  const auto good = quad();
  f.l.uploadBuffer(f.vb, 0, asBytes(std::vector<Vertex>{good[0]}));
  f.l.draw(0, 3);
  EXPECT_TRUE(validate(f.l).empty()) << dump(validate(f.l));
  // Break vertex 2 after it: only the second draw sees it.
  auto v2 = good[2];
  v2.pos[2] = std::numeric_limits<float>::quiet_NaN();
  f.l.uploadBuffer(f.vb, 2 * sizeof(Vertex), asBytes(std::vector<Vertex>{v2}));
  f.l.draw(0, 3);
  expectOnlyOnLast(f.l, "vertex 2: position (location 0) component 2 is nan");
  // A whole-buffer upload replaces everything again.
  f.l.uploadBuffer(f.vb, 0, asBytes(good));
  f.l.drawIndexed(0, 6);
  const auto diags = validate(f.l);
  ASSERT_EQ(diags.size(), 1u) << dump(diags);  // only the earlier draw
}

TEST(Validate, AVertexFoundValidUnderOneLayoutIsCheckedAgainUnderAnother) {
  // validate() remembers the vertices it found valid (a vertex many indices share is read once); that
  // must not carry over to a layout that reads other bytes as the position.
  auto vertices = quad();
  const uint32_t nanBits = 0x7fc00000u;
  for (Vertex& v : vertices) v.id = nanBits;
  Frame f(vertices);
  VertexLayout positionOnly;
  positionOnly.stride = sizeof(Vertex);
  positionOnly.attribs[0] = {0, 4, AttribType::F32, 0};
  f.l.setVertexLayout(positionOnly);
  f.l.drawIndexed(0, 6);
  EXPECT_TRUE(validate(f.l).empty()) << dump(validate(f.l));
  VertexLayout shifted = positionOnly;
  shifted.attribs[0].offset = 4;  // (pos.y, pos.z, pos.w, id): id's bits are a NaN
  f.l.setVertexLayout(shifted);
  f.l.drawIndexed(0, 6);
  expectOnlyOnLast(f.l, "vertex 0: position (location 0) component 3 is nan");
}

TEST(Validate, ASweptBufferStillReportsTheInvalidVerticesADrawReads) {
  // After draws have checked enough indices, validate() checks the whole buffer in one sweep and
  // then reads only its record per index. A draw that reads vertex 5 (NaN position, U32 id 2^24, and
  // vertex 7's id too) must still get both reports; the draws before, which skip them, none.
  std::vector<Vertex> vertices;
  for (int i = 0; i < 8; ++i) vertices.push_back({{float(i % 2), float(i / 2), 0, 1}, uint32_t(i)});
  vertices[5].pos[1] = std::numeric_limits<float>::quiet_NaN();
  vertices[5].id = vertices[7].id = 1u << 24;
  Frame f(vertices);
  f.l.draw(0, 3);  // 3 indices: not yet swept (8 vertices)
  f.l.draw(1, 3);  // 6 > 7 / 2: the sweep
  f.l.draw(2, 3);
  EXPECT_TRUE(validate(f.l).empty()) << dump(validate(f.l));
  f.l.draw(3, 3);  // vertices 3, 4, 5
  const auto diags = validate(f.l);
  ASSERT_EQ(diags.size(), 2u) << dump(diags);
  EXPECT_NE(diags[0].message.find("vertex 5: position (location 0) component 1 is nan"), std::string::npos)
      << dump(diags);
  EXPECT_NE(diags[1].message.find("vertex 5: U32 attribute at location 1 component 0 = 16777216"), std::string::npos)
      << dump(diags);
  f.l.draw(5, 3);  // vertices 5, 6, 7: vertex 5 again, and vertex 7's id
  const auto more = validate(f.l);
  ASSERT_EQ(more.size(), 4u) << dump(more);
  EXPECT_NE(more[3].message.find("vertex 5: U32"), std::string::npos) << dump(more);
}

TEST(Validate, AHugeSparselyUploadedBufferIsCheckedExactlyAndCheaply) {
  // 1 GiB declared, 48 bytes uploaded: never-uploaded bytes read as zero, and validate() must not
  // allocate the declared size. Vertex 0's position starts 2 bytes before a 64 KiB boundary, so the
  // NaN in its component 0 straddles two storage pages.
  Frame f;
  const ResourceId big = f.l.createBuffer(BufferKind::Vertex, uint64_t(1) << 30);
  std::vector<float> v(12, 0.5f);
  v[0] = std::numeric_limits<float>::quiet_NaN();
  f.l.uploadBuffer(big, 65534, std::span(reinterpret_cast<const uint8_t*>(v.data()), v.size() * 4));
  VertexLayout l;
  l.stride = 16;
  // Byte 65534 = vertex 4095 (16 * 4095 = 65520) + attribute offset 14 (offsets stay <= 2047).
  l.attribs[0] = {0, 4, AttribType::F32, 14};
  f.l.bindVertexBuffer(big);
  f.l.setVertexLayout(l);
  f.l.draw(4096, 3);  // vertices 4096..4098: uploaded 0.5s and zeros
  EXPECT_TRUE(validate(f.l).empty()) << dump(validate(f.l));
  f.l.draw(4095, 3);
  expectOnlyOnLast(f.l, "vertex 4095: position (location 0) component 0 is nan");
  f.l.draw(67108095, 3);  // far into the never-uploaded part: zeros
  f.l.draw(67108862, 3);  // vertex 67108862 is the last that fits; the next ends 14 bytes past 2^30
  const auto diags = validate(f.l);
  ASSERT_EQ(diags.size(), 2u) << dump(diags);
  EXPECT_NE(diags[1].message.find("vertex 67108863: attribute at location 0 reads bytes"), std::string::npos)
      << dump(diags);
}

TEST(Validate, AnInvalidVertexLayoutIsReported) {
  Frame f;
  VertexLayout l = vertexLayout();
  l.attribs[1].location = 0;
  f.l.setVertexLayout(l);
  expectOnlyOnLast(f.l, "location 0 is used by two attributes");
  Frame g;
  l = vertexLayout();
  l.stride = 0;
  g.l.setVertexLayout(l);
  expectOnlyOnLast(g.l, "stride 0 is ambiguous");
  Frame h;
  l = vertexLayout();
  l.attribs[1].components = 5;
  h.l.setVertexLayout(l);
  expectOnlyOnLast(h.l, "components = 5");
}

// --- viewport, render target, clears ---------------------------------------------------------

TEST(Validate, AZeroNegativeOrHugeViewportIsReported) {
  for (Rect r : {Rect{0, 0, 0, 8}, Rect{0, 0, 8, -1}, Rect{0, 0, 16385, 8}}) {
    Frame f;
    f.l.setViewport(r);
    expectOnlyOnLast(f.l, "is out of range (1..16384)");
  }
  Frame g;
  g.l.setViewport({0, 20000, 8, 8});
  expectOnlyOnLast(g.l, "viewport origin (0, 20000) is out of range");
  Frame ok;
  ok.l.setViewport({-16384, 16384, 16384, 16384});
  EXPECT_TRUE(validate(ok.l).empty()) << dump(validate(ok.l));
}

TEST(Validate, ANegativeScissorIsReported) {
  Frame f;
  f.l.setScissor({false, {0, 0, -1, 4}});
  expectOnlyOnLast(f.l, "scissor size -1x4 is negative");
}

RenderTarget target(ResourceId color, ResourceId depth, uint32_t level = 0, uint32_t layer = 0) {
  RenderTarget t;
  t.color[0] = color;
  t.depth = depth;
  t.level = level;
  t.layer = layer;
  return t;
}

TEST(Validate, RenderTargetAttachmentsOfDifferentSizesAreReported) {
  Frame f;
  const ResourceId small = f.l.createTexture({TextureKind::Tex2D, Format::D32F, 4, 4, 1, 1});
  f.l.setRenderTarget(target(f.color, small));
  expectOnlyOnLast(f.l, "attachment sizes differ at level 0: color[0] is 8x8, depth is 4x4");
}

TEST(Validate, RenderTargetFormatsThatCannotBeRenderedAreReported) {
  Frame f;
  f.l.setRenderTarget(target(f.depth, kNone));
  expectOnlyOnLast(f.l, "color[0]: texture 7 has format D32F, which is not colour-renderable");
  Frame g;
  g.l.setRenderTarget(target(g.color, g.color));
  expectOnLast(g.l, "depth: texture 6 has format RGBA8; depth attachments must be D32F");
}

TEST(Validate, RenderTargetLevelsAndLayersOutOfRangeAreReported) {
  Frame f;
  f.l.setRenderTarget(target(f.tex, kNone, 3));
  expectOnlyOnLast(f.l, "level 3 is out of range for color[0]");
  Frame g;
  g.l.setRenderTarget(target(g.color, g.depth, 0, 1));
  expectOnLast(g.l, "layer 1 is out of range for color[0]");
  Frame h;
  h.l.setRenderTarget(target(h.color, kNone, 0, kLayered));
  expectOnlyOnLast(h.l, "a layered target needs array textures");
  Frame ok;
  const ResourceId arr = ok.l.createTexture({TextureKind::Tex2DArray, Format::RGBA8, 8, 8, 4, 2});
  const ResourceId arrDepth = ok.l.createTexture({TextureKind::Tex2DArray, Format::D32F, 8, 8, 4, 2});
  ok.l.setRenderTarget(target(arr, arrDepth, 1, kLayered));  // both 4x4 at level 1
  ok.l.setRenderTarget(target(arr, kNone, 0, 3));
  EXPECT_TRUE(validate(ok.l).empty()) << dump(validate(ok.l));
}

TEST(Validate, ClearingAnAttachmentThatIsNotAttachedIsReported) {
  Frame f;
  f.l.clearColor(1, {0, 0, 0, 0});
  expectOnlyOnLast(f.l, "colour attachment 1 is not attached");
  Frame g;
  g.l.clearColor(4, {0, 0, 0, 0});
  expectOnlyOnLast(g.l, "attachment 4 is out of range (0..3)");
  Frame h;
  h.l.setRenderTarget(target(h.color, kNone));
  h.l.clearDepth(1.0f);
  expectOnlyOnLast(h.l, "no depth attachment");
  Frame i(quad(), Omit{.target = true});
  i.l.clearColor(0, {0, 0, 0, 0});
  expectOnlyOnLast(i.l, "no render target set");
}

TEST(Validate, SamplingATextureThatIsAttachedToTheTargetIsAFeedbackLoop) {
  Frame f;  // f.tex is bound to unit 0 with the default (mipmapped) sampler state of f.smp
  f.l.setRenderTarget(target(f.tex, kNone, 1));
  f.l.clearColor(0, {0, 0, 0, 0});  // clears do not sample
  EXPECT_TRUE(validate(f.l).empty()) << dump(validate(f.l));
  f.l.draw(0, 3);
  expectOnlyOnLast(f.l, "texture 1 on unit 0 is also attached to the render target as color[0] at level 1");
}

TEST(Validate, ANonMipmappedSamplerMayReadLevelZeroWhileLevelOneIsRendered) {
  Frame f;
  SamplerState s;
  s.minFilter = Filter::Linear;
  f.l.bindSampler(0, f.l.createSampler(s));
  f.l.setRenderTarget(target(f.tex, kNone, 1));
  f.l.draw(0, 3);
  EXPECT_TRUE(validate(f.l).empty()) << dump(validate(f.l));
  f.l.setRenderTarget(target(f.tex, kNone, 0));
  f.l.draw(0, 3);
  expectOnlyOnLast(f.l, "feedback loop");
  f.l.bindTexture(0, kNone);
  f.l.draw(0, 3);
  ASSERT_EQ(validate(f.l).size(), 1u) << dump(validate(f.l));
}

// --- reporting -------------------------------------------------------------------------------

TEST(Validate, ValidateOrThrowListsTheFirstTenDiagnostics) {
  Frame f;
  const size_t first = f.l.commands().size();
  for (int i = 0; i < 12; ++i) f.l.bindTexture(0, 1000 + i);
  try {
    validateOrThrow(f.l, "scene.tframe");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("scene.tframe: 12 problems", 0), 0u) << m;
    EXPECT_NE(m.find("command " + std::to_string(first) + " (BindTexture): texture id 1000 does not exist"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("texture id 1009"), std::string::npos) << m;
    EXPECT_EQ(m.find("texture id 1010"), std::string::npos) << m;
    EXPECT_NE(m.find("... and 2 more"), std::string::npos) << m;
  }
}

TEST(Validate, AMillionVertexFrameWithEightLargeDrawsValidatesCleanly) {
  constexpr uint32_t kVertices = 1'000'000;
  std::vector<Vertex> vertices(kVertices);
  for (uint32_t i = 0; i < kVertices; ++i) vertices[i] = {{float(i % 1000), float(i / 1000), 0, 1}, i};
  std::vector<uint32_t> indices(3 * size_t(kVertices));
  for (size_t i = 0; i < indices.size(); ++i) indices[i] = uint32_t((i * 7919) % kVertices);
  Frame f;
  const ResourceId vb = f.l.createBuffer(BufferKind::Vertex, asBytes(vertices));
  const ResourceId ib = f.l.createBuffer(BufferKind::Index, asBytes(indices));
  f.l.bindVertexBuffer(vb);
  f.l.bindIndexBuffer(ib, IndexType::U32);
  for (int i = 0; i < 4; ++i) {
    f.l.draw(0, kVertices - 1);
    f.l.drawIndexed(0, uint32_t(indices.size()));
  }
  const auto diags = validate(f.l);
  EXPECT_TRUE(diags.empty()) << dump(diags);
}

}  // namespace
}  // namespace tessera
