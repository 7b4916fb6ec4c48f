// layered_target: render-to-texture-atlas (Trapp & Döllner 2010). Pass 1 renders four textured
// boxes, each displaced in NDC into its own half of one layer of a 2-layer 128x128 array target
// (colour RGBA8 + layered D32F depth), gl_Layer from a record buffer, clipped by four clip distances
// on the undisplaced position. Pass 2 shows layer 0 (left) and layer 1 (right) side by side through
// the texture-array program.
#include "raster/texture.h"
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

namespace {
void box(Mesh& m, glm::vec3 c, float e, uint32_t id) {
  const float x0 = c.x - e, x1 = c.x + e, y0 = c.y - e, y1 = c.y + e, z0 = c.z - e, z1 = c.z + e;
  const glm::vec4 t0{0, 0, 0, 0}, t1{1, 0, 0, 0}, t2{1, 1, 0, 0}, t3{0, 1, 0, 0};
  m.quad({x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}, t0, t1, t2, t3, id);  // +z
  m.quad({x1, y0, z0}, {x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}, t0, t1, t2, t3, id);  // -z
  m.quad({x1, y0, z1}, {x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, t0, t1, t2, t3, id);  // +x
  m.quad({x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0}, t0, t1, t2, t3, id);  // -x
  m.quad({x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0}, {x0, y1, z0}, t0, t1, t2, t3, id);  // +y
  m.quad({x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}, t0, t1, t2, t3, id);  // -y
}
}  // namespace

void buildLayeredTarget(CommandList& cl, int w, int h) {
  constexpr int kAtlas = 128;
  // Pass 1: the layered atlas.
  const ResourceId atlas = createTarget(cl, Format::RGBA8, kAtlas, kAtlas, 2);
  const ResourceId atlasDepth = createTarget(cl, Format::D32F, kAtlas, kAtlas, 2);
  RenderTarget rt;
  rt.color[0] = atlas;
  rt.depth = atlasDepth;
  rt.layer = kLayered;
  cl.setRenderTarget(rt);
  cl.setViewport({0, 0, kAtlas, kAtlas});
  cl.clearColor(0, {0.2f, 0.2f, 0.25f, 1});
  cl.clearDepth(1.0f);

  Mesh m;
  const glm::vec3 centres[4] = {{-0.6f, -0.3f, 0}, {0.5f, 0.4f, -0.5f}, {0.1f, 0.0f, 0.6f}, {-0.2f, 0.6f, -1.0f}};
  for (uint32_t i = 0; i < 4; ++i) box(m, centres[i], 0.45f, i);
  bindMesh(cl, m);
  // Records: object i -> layer i / 2, left or right half: x' = 0.5 x -/+ 0.5 w, y' = y.
  std::vector<float> rec;
  for (uint32_t i = 0; i < 4; ++i) rec.insert(rec.end(), {0.5f, 0, 0, 1, (i & 1) ? 0.5f : -0.5f, 0, float(i / 2), 0});
  std::span<const uint8_t> recBytes(reinterpret_cast<const uint8_t*>(rec.data()), rec.size() * sizeof(float));
  TextureDesc rd;
  rd.kind = TextureKind::Buffer;
  rd.format = Format::RGBA32F;
  rd.width = uint32_t(rec.size() / 4);
  rd.buffer = cl.createBuffer(BufferKind::Texel, recBytes);
  cl.bindTexture(0, cl.createTexture(rd));
  cl.useProgram(cl.createProgram("atlas_displace"));
  setMatrix(cl, 0, mul(perspective(60.0, 1.0, 0.1, 20.0), lookAt({1.2f, 1.5f, 3.0f}, {0, 0, 0}, {0, 1, 0})));
  setVec4(cl, 7, {1, 1, 1, 1});
  RasterState rs;
  rs.clipMask = 0x0f;
  cl.setRasterState(rs);
  DepthState ds;
  ds.test = true;
  cl.setDepthState(ds);
  SamplerState s;
  s.minFilter = Filter::LinearMipmapLinear;
  cl.bindSampler(1, cl.createSampler(s));
  for (uint32_t i = 0; i < 4; ++i) {
    const std::array<uint8_t, 4> a = {uint8_t(80 + 50 * i), uint8_t(220 - 40 * i), uint8_t(120 + 30 * (i & 1)), 255};
    cl.bindTexture(1, uploadTexture(cl, checker(32, 32, 4, a, {40, 40, 40, 255}), true));
    cl.drawIndexed(i * 36, 36);
  }

  // Pass 2: show both layers.
  beginFrame(cl, w, h, false, {0, 0, 0, 1});
  cl.setRasterState({});
  cl.setDepthState({});
  const float tam[4] = {0, 0, 0, 1};
  std::span<const uint8_t> tamBytes(reinterpret_cast<const uint8_t*>(tam), sizeof tam);
  TextureDesc td;
  td.kind = TextureKind::Buffer;
  td.format = Format::RG32F;
  td.width = 2;
  td.buffer = cl.createBuffer(BufferKind::Texel, tamBytes);
  cl.bindTexture(0, cl.createTexture(td));
  cl.bindTexture(1, atlas);
  SamplerState nearest;
  nearest.minFilter = Filter::Nearest;
  nearest.magFilter = Filter::Nearest;
  cl.bindSampler(1, cl.createSampler(nearest));
  Mesh q;
  q.quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0, 0}, {1, 0, 0, 0}, {1, 1, 0, 0}, {0, 1, 0, 0});
  q.quad({1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {0, 0, 1, 0}, {1, 0, 1, 0}, {1, 1, 1, 0}, {0, 1, 1, 0});
  const uint32_t n = bindMesh(cl, q);
  cl.useProgram(cl.createProgram("texarray_batch"));
  setMatrix(cl, 0, ortho(0, 2, 0, 1, -1, 1));
  cl.drawIndexed(0, n);
}

}  // namespace tessera::scenes
