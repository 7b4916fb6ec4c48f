// ghosted-ao (Trapp & Döllner 2010, Fig. 3D): program atlas_sprite_ao's occlusion and edges on a
// hand-made atlas, and the recorder's refusal of a border the kernel would cross.
#include <gtest/gtest.h>

#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "base/error.h"
#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "raster/programs/atlas_ao.h"
#include "mta/camera.h"
#include "rtta/rtta_record.h"
#include "tests/rtta/box_scene.h"

namespace tessera {

namespace {

constexpr int kW = 16, kH = 8;
constexpr float kStepC = 1.0f / 1024.0f;  // the crease's depth slope per texel (exact in float)

template <class T>
std::span<const uint8_t> bytesOf(const std::vector<T>& v) {
  return {reinterpret_cast<const uint8_t*>(v.data()), v.size() * sizeof(T)};
}

// A 16x8 frame with one full-screen sprite of atlas_sprite_ao over a 16x8 one-layer atlas: colour
// (160, 80, 240, 255) everywhere, every texel covered, window depth z(x) = 1/2 - |x - 8| / 1024: a
// V-shaped valley (concave seen from the eye, smaller z is nearer) along the column x = 8.
// Bias c / 2, edge step `edgeStep` (1: no crease is an edge), edge colour black, factors f[k] = 1 - k / 8.
CommandList valleyFrame(float edgeStep = 1.0f) {
  CommandList cl;
  TextureDesc cd;
  cd.kind = TextureKind::Tex2DArray;
  cd.width = kW, cd.height = kH, cd.layers = 1;
  const ResourceId colour = cl.createTexture(cd);
  TextureDesc dd = cd;
  dd.format = Format::RG32F;
  const ResourceId depth = cl.createTexture(dd);
  std::vector<uint8_t> c;
  std::vector<float> d;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      c.insert(c.end(), {160, 80, 240, 255});
      d.push_back(0.5f - float(x > 8 ? x - 8 : 8 - x) * kStepC);
      d.push_back(1.0f);
    }
  cl.uploadTexture(colour, 0, 0, c);
  cl.uploadTexture(depth, 0, 0, bytesOf(d));
  TextureDesc td;
  td.width = kW, td.height = kH;
  RenderTarget rt;
  rt.color[0] = cl.createTexture(td);
  td.format = Format::D32F;
  rt.depth = cl.createTexture(td);
  cl.setRenderTarget(rt);
  cl.setViewport({0, 0, kW, kH});
  cl.clearColor(0, {0, 0, 1, 1});
  cl.clearDepth(1.0f);
  DepthState ds;
  ds.test = true;
  cl.setDepthState(ds);
  const std::vector<float> v{-1, -1, 0, 1, 0, 0, 0, 0, 1, -1, 0, 1, 0, 0, 0, 0, 1, 1, 0, 1, 0, 0, 0, 0,
                             -1, -1, 0, 1, 0, 0, 0, 0, 1, 1,  0, 1, 0, 0, 0, 0, -1, 1, 0, 1, 0, 0, 0, 0};
  cl.bindVertexBuffer(cl.createBuffer(BufferKind::Vertex, bytesOf(v)));
  VertexLayout l;
  l.stride = 32;
  l.attribs[0] = {0, 4, AttribType::F32, 0};
  l.attribs[2] = {2, 4, AttribType::F32, 16};
  cl.setVertexLayout(l);
  cl.bindTexture(0, colour);
  cl.bindTexture(1, depth);
  cl.useProgram(cl.createProgram("atlas_sprite_ao"));
  cl.setUniforms(7, std::vector<float>{1, 1, 1, 1});
  cl.setUniforms(8, std::vector<float>{kStepC / 2, edgeStep, 0, 0});
  cl.setUniforms(9, std::vector<float>{0, 0, 0, 1});
  cl.setUniforms(10, std::vector<float>{1, 0.875f, 0.75f, 0.625f, 0.5f, 0, 0, 0});
  cl.draw(0, 6);
  return cl;
}

}  // namespace

TEST(AtlasSpriteAo, ConcaveCreasesDarkenByTheirOccludingPairsPlanesKeepTheirColourAndBordersAreEdges) {
  CpuBackend b(RenderOptions{2});
  b.execute(valleyFrame(), "valley");
  ASSERT_EQ(b.presented().size(), 1u);
  const std::vector<uint8_t> img = imagePixels(*b.texture(b.presented()[0].texture), 0, 0);
  auto at = [&](int x, int y) {  // GL window coordinates, y up; imagePixels is top row first
    const uint8_t* p = &img[(size_t(kH - 1 - y) * kW + size_t(x)) * 4];
    return std::vector<int>{p[0], p[1], p[2], p[3]};
  };
  // Worked out by hand: the second difference of a pair (o, -o) is z(x + ox) + z(x - ox) - 2 z(x).
  // At x = 8 it is -4c for the x pair and both diagonals, 0 for the y pair: k = 3 where the diagonals'
  // rows exist (2 <= y <= 5), else k = 1 (the x pair alone; pairs reaching outside the texture are
  // uncovered and skipped). At x = 7 and 9 it is -2c < -c/2: the same k. At x = 6 it is 0 (a plane).
  const std::vector<int> k3{100, 50, 150, 255}, k1{140, 70, 210, 255}, flat{160, 80, 240, 255}, edge{0, 0, 0, 255};
  for (int x : {7, 8, 9}) {
    for (int y = 2; y <= 5; ++y) EXPECT_EQ(at(x, y), k3) << x << "," << y;
    EXPECT_EQ(at(x, 1), k1) << x;
    EXPECT_EQ(at(x, 6), k1) << x;
  }
  for (int x : {2, 3, 4, 5, 6, 10, 11, 12, 13})
    for (int y = 1; y < kH - 1; ++y) EXPECT_EQ(at(x, y), flat) << x << "," << y;
  // A 4-neighbour outside the atlas is uncovered: a silhouette, drawn in the edge colour.
  for (int x = 0; x < kW; ++x) {
    EXPECT_EQ(at(x, 0), edge) << x;
    EXPECT_EQ(at(x, kH - 1), edge) << x;
  }
  for (int y = 0; y < kH; ++y) {
    EXPECT_EQ(at(0, y), edge) << y;
    EXPECT_EQ(at(kW - 1, y), edge) << y;
  }
}

TEST(AtlasSpriteAo, ANeighbourFartherThanTheEdgeStepInDepthIsAnEdge) {
  // The same valley with the edge step below its slope c: every pixel has a 4-neighbour c away in
  // depth, so every pixel is drawn in the edge colour.
  CpuBackend b(RenderOptions{2});
  b.execute(valleyFrame(kStepC / 2), "valley edges");
  const std::vector<uint8_t> img = imagePixels(*b.texture(b.presented()[0].texture), 0, 0);
  for (size_t i = 0; i < img.size(); i += 4)
    EXPECT_EQ((std::vector<int>{img[i], img[i + 1], img[i + 2], img[i + 3]}), (std::vector<int>{0, 0, 0, 255})) << i / 4;
}

TEST(RttaGhostedAo, ABorderNarrowerThanTheKernelIsRefusedBecauseItWouldReadANeighboursRegion) {
  const rtta::RttaScene s = rtta::testing::boxScene(rtta::testing::fiveBoxes(), 4);
  mta::Camera c;
  c.eye = {1.5, 2.5, 7.0};
  c.target = {0.5, 0.0, 0.0};
  c.nearPlane = 0.5;
  c.farPlane = 40.0;
  rtta::RttaView v;
  v.mvp = mta::viewProjection(c, 128, 96);
  v.eye = c.eye;
  v.width = 128, v.height = 96;
  rtta::RttaOptions o;
  o.composite = rtta::Composite::GhostedAo;
  o.params.border = programs::kAoRadius - 1;
  try {
    (void)rtta::recordRttaFrame(s, v, o);
    FAIL() << "a border of " << o.params.border << " must be refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--border 1 is narrower than the occlusion kernel's radius 2"), std::string::npos)
        << e.what();
  }
  o.params.border = programs::kAoRadius;
  const rtta::RttaFrame f = rtta::recordRttaFrame(s, v, o);
  EXPECT_FALSE(f.important.empty());
}

}  // namespace tessera
