// The oracle shades the vertices of consecutive draws together, when their triangles are set up
// (raster/cpu_backend.cpp, shadePending), not when each draw is recorded, and takes a large draw in
// slices. A draw must still see the vertex buffer and layout that were bound when it was issued, even
// if later draws bind others before anything forces the pending draws through, and every triangle of
// a sliced draw keeps its gl_PrimitiveID.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "tests/raster/render_helpers.h"
#include "tools/scenes/builder.h"

namespace tessera::scenes {
using tessera::testing::renderList;

namespace {

constexpr int kSize = 32;

std::span<const uint8_t> bytesOf(const std::vector<Vertex>& v) {
  return {reinterpret_cast<const uint8_t*>(v.data()), v.size() * sizeof(Vertex)};
}

// Two triangles in different places, each from its own vertex buffer and layout: mesh B's buffer
// interleaves every vertex with an unused one (stride two vertices, attributes one vertex in), so
// shading A's vertices with B's layout, or B's with A's buffer, draws somewhere else. With
// `flushBetween`, A's buffer is uploaded again (the same bytes) between the draws: an upload to a
// buffer that a pending draw reads flushes first, so A's triangle is set up before B's are bound.
CommandList twoBufferFrame(bool flushBetween) {
  CommandList cl;
  RenderTarget t;
  t.color[0] = createTarget(cl, Format::RGBA8, kSize, kSize);
  cl.setRenderTarget(t);
  cl.setViewport({0, 0, kSize, kSize});
  cl.clearColor(0, {0, 0, 0, 0});
  const std::vector<Vertex> a = {{{1, 1, 0}, {}, 0}, {{15, 1, 0}, {}, 0}, {{1, 15, 0}, {}, 0}};
  std::vector<Vertex> b;
  const Vertex unused{{-100, -100, 0}, {}, 0};
  for (const glm::vec3 p : {glm::vec3(31, 31, 0), glm::vec3(17, 31, 0), glm::vec3(31, 17, 0)}) {
    b.push_back(unused);
    b.push_back({p, {}, 0});
  }
  const std::vector<uint32_t> idx = {0, 1, 2};
  const std::span<const uint8_t> ib(reinterpret_cast<const uint8_t*>(idx.data()), idx.size() * sizeof(uint32_t));
  const ResourceId vbA = cl.createBuffer(BufferKind::Vertex, bytesOf(a));
  const ResourceId vbB = cl.createBuffer(BufferKind::Vertex, bytesOf(b));
  const ResourceId ibuf = cl.createBuffer(BufferKind::Index, ib);
  cl.useProgram(cl.createProgram("flat_color"));
  setMatrix(cl, 0, ortho(0, kSize, 0, kSize, -1, 1));
  setVec4(cl, 4, {1, 0.5f, 0.25f, 1});
  cl.bindIndexBuffer(ibuf, IndexType::U32);

  cl.bindVertexBuffer(vbA);
  cl.setVertexLayout(standardLayout());
  cl.drawIndexed(0, 3);
  if (flushBetween) cl.uploadBuffer(vbA, 0, bytesOf(a));
  VertexLayout interleaved = standardLayout();
  interleaved.stride = 2 * sizeof(Vertex);
  for (VertexAttrib& at : interleaved.attribs)
    if (at.components != 0) at.offset += uint32_t(sizeof(Vertex));
  cl.bindVertexBuffer(vbB);
  cl.setVertexLayout(interleaved);
  cl.drawIndexed(0, 3);
  return cl;
}

int coloured(const std::vector<uint8_t>& img) {
  int n = 0;
  for (size_t i = 0; i < img.size(); i += 4) n += img[i] != 0;
  return n;
}

}  // namespace

TEST(DeferredVertices, EachDrawUsesTheVertexBufferAndLayoutBoundWhenItWasIssued) {
  for (int threads : {1, 2}) {
    const auto together = renderList(twoBufferFrame(false), threads);
    const auto apart = renderList(twoBufferFrame(true), threads);
    ASSERT_EQ(together.images.size(), 1u);
    ASSERT_EQ(apart.images.size(), 1u);
    EXPECT_EQ(together.hashes[0], apart.hashes[0]) << threads << " threads";
    // Both triangles are drawn, each in its own corner: 2 x (14 x 14 / 2 pixels, about).
    EXPECT_GT(coloured(together.images[0]), 150) << threads << " threads";
    EXPECT_EQ(together.stats.triangles_binned, 2u);
  }
}

TEST(DeferredVertices, ATriangleOfASlicedDrawKeepsItsPrimitiveIdWithinTheWholeDraw) {
  // 40,000 triangles, each covering the centre of one pixel of a 256 x 256 target, in one draw: more
  // than two slices (kPendingTriangles is 16384). object_id writes gl_PrimitiveID to attachment 1.
  constexpr int kW = 256, kTris = 40000;
  Mesh m;
  for (int i = 0; i < kTris; ++i) {
    const float x = float(i % kW), y = float(i / kW);
    m.triangle({{x + 0.2f, y + 0.2f, 0}, {}, 7}, {{x + 0.9f, y + 0.2f, 0}, {}, 7}, {{x + 0.2f, y + 0.9f, 0}, {}, 7});
  }
  CommandList cl;
  RenderTarget t;
  t.color[0] = createTarget(cl, Format::R32UI, kW, kW);
  t.color[1] = createTarget(cl, Format::R32UI, kW, kW);
  cl.setRenderTarget(t);
  cl.setViewport({0, 0, kW, kW});
  const uint32_t n = bindMesh(cl, m);
  cl.useProgram(cl.createProgram("object_id"));
  setMatrix(cl, 0, ortho(0, kW, 0, kW, -1, 1));
  cl.drawIndexed(0, n);
  for (int threads : {1, 2}) {
    const auto r = renderList(cl, threads);
    ASSERT_EQ(r.images.size(), 2u);
    const std::vector<uint8_t>& ids = r.images[1];  // top row first, one uint32 per pixel
    ASSERT_EQ(ids.size(), size_t(kW) * kW * 4);
    int wrong = 0;
    for (int i = 0; i < kTris; ++i) {
      const int x = i % kW, y = i / kW;
      uint32_t id;
      std::memcpy(&id, ids.data() + (size_t(kW - 1 - y) * kW + size_t(x)) * 4, 4);
      if (id != uint32_t(i) && wrong++ < 5) ADD_FAILURE() << "triangle " << i << " wrote gl_PrimitiveID " << id;
    }
    EXPECT_EQ(wrong, 0) << threads << " threads";
    EXPECT_EQ(r.stats.triangles_binned, uint64_t(kTris));
  }
}

}  // namespace tessera::scenes
