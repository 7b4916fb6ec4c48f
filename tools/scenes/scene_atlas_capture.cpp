// atlas_capture: the render-to-texture-atlas capture pass with depth (Trapp & Döllner 2010, §2.3,
// §3.1). Four textured boxes go through program atlas_capture into a 2-layer layered target of the
// frame's size: colour 0 RGBA8 (cleared (0, 0, 0, 0): alpha 0 = empty), colour 1 RG32F (cleared
// (1, 0): far, not covered) and a layered D32F depth. Object i lands in layer i / 2, left or right
// half (x' = 0.5 x -/+ 0.5 w), clipped by the undisplaced position's four side planes; a fifth box
// has a record without a layer and is dropped. The target stays bound, so all four images (two
// attachments x two layers) are presented and cross-checked: the RG32F images hold gl_FragCoord.z.
// Back faces are culled and object 0 is two interpenetrating boxes: the depth test then rejects
// fragments in layer 0 only. A layer-1 fragment that fails the depth test would trigger softpipe's
// known layered-colour-to-layer-0 bug (docs/softpipe-edge-flips.md §1, pinned by layered_target),
// whose stray texels in layer 0 no expectation can cover here (nothing else writes them); this frame
// is meant to test gl_FragCoord.z and the attachments on both implementations, not that bug again.
// atlas_capture_tab: the same objects batched (texture-array batching): one draw through
// atlas_capture_tab, the textures as layers of one array, so each region should hold what
// atlas_capture puts there (up to the lookup's legal freedoms: textureGrad with the quad's derivatives).
#include "raster/texture.h"
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

namespace {
void captureBox(Mesh& m, glm::vec3 c, float e, uint32_t id) {
  const float x0 = c.x - e, x1 = c.x + e, y0 = c.y - e, y1 = c.y + e, z0 = c.z - e, z1 = c.z + e;
  // texcoord (s, t, TAM entry = object id): atlas_capture reads (s, t), atlas_capture_tab all three.
  const float e3 = float(id);
  const glm::vec4 t0{0, 0, e3, 0}, t1{1, 0, e3, 0}, t2{1, 1, e3, 0}, t3{0, 1, e3, 0};
  m.quad({x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}, t0, t1, t2, t3, id);  // +z
  m.quad({x1, y0, z0}, {x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}, t0, t1, t2, t3, id);  // -z
  m.quad({x1, y0, z1}, {x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, t0, t1, t2, t3, id);  // +x
  m.quad({x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0}, t0, t1, t2, t3, id);  // -x
  m.quad({x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0}, {x0, y1, z0}, t0, t1, t2, t3, id);  // +y
  m.quad({x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}, t0, t1, t2, t3, id);  // -y
}
}  // namespace

// Both capture scenes: `tab` draws every box in one draw through atlas_capture_tab (one 5-layer
// texture array on unit 1, an RG32F TAM on unit 0 naming layer i for entry i, the records on unit 9);
// otherwise one draw per object through atlas_capture (records on unit 0, the object's texture on 1).
void buildCapture(CommandList& cl, int w, int h, bool tab) {
  const ResourceId color = createTarget(cl, Format::RGBA8, w, h, 2);
  const ResourceId depthColor = createTarget(cl, Format::RG32F, w, h, 2);
  const ResourceId depth = createTarget(cl, Format::D32F, w, h, 2);
  RenderTarget rt;
  rt.color[0] = color;
  rt.color[1] = depthColor;
  rt.depth = depth;
  rt.layer = kLayered;
  cl.setRenderTarget(rt);
  cl.setViewport({0, 0, w, h});
  cl.clearColor(0, {0, 0, 0, 0});
  cl.clearColor(1, {1, 0, 0, 0});
  cl.clearDepth(1.0f);

  Mesh m;
  const glm::vec3 centres[5] = {{-0.6f, -0.3f, 0}, {0.5f, 0.4f, -0.5f}, {0.1f, 0.0f, 0.6f}, {-0.2f, 0.6f, -1.0f}, {0, 0, 0}};
  for (uint32_t i = 0; i < 5; ++i) captureBox(m, centres[i], 0.45f, i);
  captureBox(m, {-0.9f, 0.05f, 0.0f}, 0.3f, 0);  // object 0: a second box, through the first one
  bindMesh(cl, m);
  // Records: object i < 4 -> layer i / 2, left or right half: x' = 0.5 x -/+ 0.5 w, y' = y; object 4
  // has layer -1 (no layer: the geometry stage drops its triangles).
  std::vector<float> rec;
  for (uint32_t i = 0; i < 4; ++i) rec.insert(rec.end(), {0.5f, 0, 0, 1, (i & 1) ? 0.5f : -0.5f, 0, float(i / 2), 0});
  rec.insert(rec.end(), {0.5f, 0, 0, 1, 0, 0, -1, 0});
  std::span<const uint8_t> recBytes(reinterpret_cast<const uint8_t*>(rec.data()), rec.size() * sizeof(float));
  TextureDesc rd;
  rd.kind = TextureKind::Buffer;
  rd.format = Format::RGBA32F;
  rd.width = uint32_t(rec.size() / 4);
  rd.buffer = cl.createBuffer(BufferKind::Texel, recBytes);
  cl.bindTexture(tab ? 9 : 0, cl.createTexture(rd));
  cl.useProgram(cl.createProgram(tab ? "atlas_capture_tab" : "atlas_capture"));
  setMatrix(cl, 0, mul(perspective(60.0, double(w) / 2.0 / double(h), 0.1, 20.0), lookAt({1.2f, 1.5f, 3.0f}, {0, 0, 0}, {0, 1, 0})));
  setVec4(cl, 7, {1, 1, 1, 1});
  RasterState rs;
  rs.clipMask = 0x0f;
  rs.cull = CullMode::Back;
  cl.setRasterState(rs);
  DepthState ds;
  ds.test = true;
  cl.setDepthState(ds);
  SamplerState s;
  s.minFilter = Filter::LinearMipmapLinear;
  cl.bindSampler(1, cl.createSampler(s));
  auto image = [](uint32_t i) {
    const std::array<uint8_t, 4> a = {uint8_t(80 + 40 * i), uint8_t(220 - 40 * i), uint8_t(120 + 30 * (i & 1)), 255};
    return checker(32, 32, 4, a, {40, 40, 40, 128});
  };
  if (tab) {
    TextureDesc d;
    d.kind = TextureKind::Tex2DArray;
    d.width = d.height = 32;
    d.layers = 5;
    d.levels = fullMipCount(32, 32);
    const ResourceId array = cl.createTexture(d);
    for (uint32_t i = 0; i < 5; ++i) {
      const auto chain = buildMipChainRGBA8(32, 32, image(i).rgba);
      for (uint32_t lev = 0; lev < chain.size(); ++lev) cl.uploadTexture(array, lev, i, chain[lev]);
    }
    std::vector<float> tam;
    for (uint32_t i = 0; i < 5; ++i) tam.insert(tam.end(), {0, float(i)});
    TextureDesc td;
    td.kind = TextureKind::Buffer;
    td.format = Format::RG32F;
    td.width = 5;
    td.buffer = cl.createBuffer(BufferKind::Texel, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(tam.data()), tam.size() * sizeof(float)));
    cl.bindTexture(0, cl.createTexture(td));
    cl.bindTexture(1, array);
    cl.drawIndexed(0, 6 * 36);  // every box, one draw
    return;
  }
  for (uint32_t i = 0; i < 5; ++i) {
    cl.bindTexture(1, uploadTexture(cl, image(i), true));
    cl.drawIndexed(i * 36, 36);
    if (i == 0) cl.drawIndexed(5 * 36, 36);  // object 0's second box, same texture
  }
}

void buildAtlasCapture(CommandList& cl, int w, int h) { buildCapture(cl, w, h, false); }
void buildAtlasCaptureTab(CommandList& cl, int w, int h) { buildCapture(cl, w, h, true); }

}  // namespace tessera::scenes
