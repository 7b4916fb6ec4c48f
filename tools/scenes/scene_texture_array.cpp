// texture_array: texture-array batching (Trapp & Döllner 2015). Three texture arrays of different
// resolutions (64^2 x 4, 32^2 x 3, 16^2 x 2 layers, full mip chains) on units 1-3, the texture-array
// mapping TAM as an RG32F buffer texture on unit 0, and a tilted 3 x 3 grid of quads, each naming
// its TAM entry in texcoord.z, drawn with ONE draw call.
#include "raster/texture.h"
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

namespace {
ResourceId makeArray(CommandList& cl, uint32_t size, uint32_t layers, uint32_t seed) {
  TextureDesc d;
  d.kind = TextureKind::Tex2DArray;
  d.width = d.height = size;
  d.layers = layers;
  d.levels = fullMipCount(size, size);
  const ResourceId id = cl.createTexture(d);
  Rng rng{seed};
  for (uint32_t l = 0; l < layers; ++l) {
    const std::array<uint8_t, 4> a = {uint8_t(64 + rng.below(192)), uint8_t(64 + rng.below(192)),
                                      uint8_t(64 + rng.below(192)), 255};
    RgbaImage img =
        checker(size, size, std::max(1u, size / 8), a, {uint8_t(a[0] / 4), uint8_t(a[1] / 4), uint8_t(a[2] / 4), 255});
    const auto chain = buildMipChainRGBA8(size, size, img.rgba);
    for (uint32_t lev = 0; lev < chain.size(); ++lev) cl.uploadTexture(id, lev, l, chain[lev]);
  }
  return id;
}
}  // namespace

void buildTextureArray(CommandList& cl, int w, int h) {
  beginFrame(cl, w, h, true, {0.05f, 0.05f, 0.08f, 1});
  const ResourceId arrays[3] = {makeArray(cl, 64, 4, 1), makeArray(cl, 32, 3, 2), makeArray(cl, 16, 2, 3)};
  // TAM: 9 entries (arrayID, layerID) covering every layer of every array.
  std::vector<float> tam;
  const uint32_t layers[3] = {4, 3, 2};
  for (uint32_t a = 0; a < 3; ++a)
    for (uint32_t l = 0; l < layers[a]; ++l) tam.insert(tam.end(), {float(a), float(l)});
  std::span<const uint8_t> tamBytes(reinterpret_cast<const uint8_t*>(tam.data()), tam.size() * sizeof(float));
  const ResourceId tamBuf = cl.createBuffer(BufferKind::Texel, tamBytes);
  TextureDesc td;
  td.kind = TextureKind::Buffer;
  td.format = Format::RG32F;
  td.width = uint32_t(tam.size() / 2);
  td.buffer = tamBuf;
  const ResourceId tamTex = cl.createTexture(td);

  Mesh m;
  for (int i = 0; i < 9; ++i) {
    const float x0 = float(i % 3) - 1.5f, y0 = float(i / 3) - 1.5f, e = 0.95f, z = float(i);
    m.quad({x0, y0, 0}, {x0 + e, y0, 0}, {x0 + e, y0 + e, 0}, {x0, y0 + e, 0}, {0, 0, z, 0}, {2, 0, z, 0}, {2, 2, z, 0},
           {0, 2, z, 0});
  }
  const uint32_t n = bindMesh(cl, m);
  cl.useProgram(cl.createProgram("texarray_batch"));
  setMatrix(cl, 0, mul(perspective(50.0, double(w) / h, 0.1, 50.0), lookAt({0.5f, -3.2f, 2.6f}, {0, 0, 0}, {0, 0, 1})));
  DepthState ds;
  ds.test = true;
  cl.setDepthState(ds);
  cl.bindTexture(0, tamTex);
  SamplerState s;
  s.minFilter = Filter::LinearMipmapLinear;
  const ResourceId smp = cl.createSampler(s);
  for (uint32_t a = 0; a < 3; ++a) {
    cl.bindTexture(1 + a, arrays[a]);
    cl.bindSampler(1 + a, smp);
  }
  cl.drawIndexed(0, n);
}

}  // namespace tessera::scenes
