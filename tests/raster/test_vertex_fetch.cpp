// Vertex fetch (raster/cpu_backend.cpp, fetchGroup): attribute by attribute over groups of 64
// vertices. Each vertex must get its own index's attribute values, components a layout leaves out
// must read as (0, 0, 0, 1) (GL 4.6 §10.3), U32 attributes convert to their float values, and none of
// it may depend on where a vertex falls in a group, on whether the draw's indices are dense, on
// threads or on provenance mode (which keeps the inputs in the slice's array instead of a group
// buffer).
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "tests/raster/render_helpers.h"
#include "tools/scenes/builder.h"

namespace tessera::scenes {
namespace {

constexpr int kFetchSize = 16;
constexpr int kFetchTris = 200;  // 600 vertices: ten groups, the last one partial

// A colour level in [0, 4]: the channel value level / 5 is level * 51 as unorm8 (exact enough that
// the barycentric sum's rounding cannot move it: 51 k is an integer, far from a rounding boundary).
int fetchLevel(int i, int channel) { return channel == 0 ? i % 5 : (i / 5) % 5; }

// One triangle per pixel centre, triangle i at pixel i, coloured by its index through vertex_color's
// attribute 1. `u32`: the colour is a 3-component U32 attribute holding 0 or 1 per channel (level
// odd); otherwise a 2-component F32 attribute (level / 5), so blue reads 0 and alpha 1. `spread`:
// the used vertices sit every fourth one in the buffer, so the draw's indices are not dense.
// `earlier`: a draw before it, in the same flush, fetches a 4-component colour (0.8, 0.8, 0.8, 0.2)
// at the same location for as many vertices, all outside the target: whatever it leaves in a vertex
// input must not reach the components the colour draw's layout leaves out.
CommandList fetchFrame(bool u32, bool spread, bool earlier = false) {
  struct V {
    float pos[2];
    float rgF[2];
    uint32_t rgbU[3];
    uint32_t pad;
  };
  static_assert(sizeof(V) == 32, "the layout below assumes a 32-byte vertex");
  const int every = spread ? 4 : 1;
  std::vector<V> verts(size_t(kFetchTris) * 3 * size_t(every), V{{-50, -50}, {0, 0}, {0, 0, 0}, 0});
  std::vector<uint32_t> idx;
  for (int i = 0; i < kFetchTris; ++i) {
    const float x = float(i % kFetchSize), y = float(i / kFetchSize);
    const float corner[3][2] = {{x + 0.1f, y + 0.1f}, {x + 0.95f, y + 0.1f}, {x + 0.1f, y + 0.95f}};
    for (int k = 0; k < 3; ++k) {
      const size_t at = (size_t(i) * 3 + size_t(k)) * size_t(every);
      V& v = verts[at];
      v.pos[0] = corner[k][0], v.pos[1] = corner[k][1];
      v.rgF[0] = float(fetchLevel(i, 0)) / 5.0f, v.rgF[1] = float(fetchLevel(i, 1)) / 5.0f;
      for (int c = 0; c < 3; ++c) v.rgbU[c] = uint32_t(fetchLevel(i, c == 2 ? 0 : c) & 1);
      idx.push_back(uint32_t(at));
    }
  }
  CommandList cl;
  RenderTarget t;
  t.color[0] = createTarget(cl, Format::RGBA8, kFetchSize, kFetchSize);
  cl.setRenderTarget(t);
  cl.setViewport({0, 0, kFetchSize, kFetchSize});
  cl.clearColor(0, {0, 0, 0, 0});
  const ResourceId vb = cl.createBuffer(
      BufferKind::Vertex, {reinterpret_cast<const uint8_t*>(verts.data()), verts.size() * sizeof(V)});
  const ResourceId ib = cl.createBuffer(
      BufferKind::Index, {reinterpret_cast<const uint8_t*>(idx.data()), idx.size() * sizeof(uint32_t)});
  VertexLayout l;
  l.stride = sizeof(V);
  l.attribs[0] = {0, 2, AttribType::F32, 0};
  l.attribs[3] = u32 ? VertexAttrib{1, 3, AttribType::U32, uint32_t(offsetof(V, rgbU))}
                     : VertexAttrib{1, 2, AttribType::F32, uint32_t(offsetof(V, rgF))};
  cl.useProgram(cl.createProgram("vertex_color"));
  setMatrix(cl, 0, ortho(0, kFetchSize, 0, kFetchSize, -1, 1));
  if (earlier) {
    const float outside[8] = {-50, -50, 0.8f, 0.8f, 0.8f, 0.2f, 0, 0};
    std::vector<float> other;
    for (size_t v = 0; v < idx.size(); ++v) other.insert(other.end(), outside, outside + 8);
    cl.bindVertexBuffer(cl.createBuffer(
        BufferKind::Vertex, {reinterpret_cast<const uint8_t*>(other.data()), other.size() * sizeof(float)}));
    VertexLayout l4;
    l4.stride = 8 * sizeof(float);
    l4.attribs[0] = {0, 2, AttribType::F32, 0};
    l4.attribs[3] = {1, 4, AttribType::F32, 2 * sizeof(float)};
    cl.setVertexLayout(l4);
    cl.draw(0, uint32_t(idx.size()));
  }
  cl.bindVertexBuffer(vb);
  cl.setVertexLayout(l);
  cl.bindIndexBuffer(ib, IndexType::U32);
  cl.drawIndexed(0, uint32_t(idx.size()));
  return cl;
}

std::vector<uint8_t> renderFetch(const CommandList& cl, int threads, bool provenance) {
  RenderOptions o{threads};
  o.provenance = provenance;
  CpuBackend b(o);
  b.execute(cl, "vertex_fetch");
  EXPECT_EQ(b.presented().size(), 1u);
  const PresentedImage p = b.presented().at(0);  // presented() returns a copy
  return imagePixels(*b.texture(p.texture), p.level, p.layer);
}

TEST(VertexFetch, EveryVertexGetsItsOwnAttributesWithGlsDefaultsForMissingComponents) {
  for (const bool u32 : {false, true})
    for (const bool spread : {false, true})
      for (const int threads : {1, 2})
        for (const bool provenance : {false, true}) {
          // An earlier draw with a wider layout only with the dense F32 frame (where its stale blue and
          // alpha would show), at both thread counts and in both modes.
          const bool earlier = !u32 && !spread;
          const std::vector<uint8_t> img = renderFetch(fetchFrame(u32, spread, earlier), threads, provenance);
          ASSERT_EQ(img.size(), size_t(kFetchSize * kFetchSize * 4));
          for (int i = 0; i < kFetchSize * kFetchSize; ++i) {
            // imagePixels is top-down; pixel i of the frame is at row kFetchSize - 1 - i / kFetchSize.
            const int x = i % kFetchSize, y = i / kFetchSize;
            const uint8_t* px = &img[(size_t(kFetchSize - 1 - y) * kFetchSize + size_t(x)) * 4];
            uint8_t expect[4] = {0, 0, 0, 0};  // the clear colour where no triangle is
            if (i < kFetchTris) {
              if (u32) {
                for (int c = 0; c < 3; ++c) expect[c] = uint8_t(255 * (fetchLevel(i, c == 2 ? 0 : c) & 1));
              } else {
                expect[0] = uint8_t(51 * fetchLevel(i, 0)), expect[1] = uint8_t(51 * fetchLevel(i, 1));  // blue: 0
              }
              expect[3] = 255;  // alpha: the default w of 1
            }
            for (int c = 0; c < 4; ++c)
              ASSERT_EQ(int(px[c]), int(expect[c]))
                  << "triangle " << i << ", channel " << c << (u32 ? ", U32" : ", F32") << (spread ? ", spread" : "")
                  << ", " << threads << " threads" << (provenance ? ", provenance" : "")
                  << (earlier ? ", after a wider layout" : "");
          }
        }
}

}  // namespace
}  // namespace tessera::scenes
