// array_layers: the layer of an array lookup is floor(r + 1/2) clamped to [0, layers - 1]
// (GL 4.6 §8.14.2, spec-choices). A row of quads through "texarray_batch" whose TAM entries name
// fractional layers 0.3, 0.7, 1.2, 1.8, 2.4 and 2.7 of one 4-layer array (each layer one flat
// colour), so rounding and truncating the layer pick different colours; none is near a tie.
#include "tools/scenes/scene_common.h"

namespace tessera::scenes {

void buildArrayLayers(CommandList& cl, int w, int h) {
  beginFrame(cl, w, h, false, {0, 0, 0, 1});
  TextureDesc d;
  d.kind = TextureKind::Tex2DArray;
  d.width = d.height = 4;
  d.layers = 4;
  const ResourceId array = cl.createTexture(d);
  const std::array<uint8_t, 4> colours[4] = {
      {230, 60, 60, 255}, {60, 200, 60, 255}, {60, 90, 230, 255}, {230, 210, 40, 255}};
  for (uint32_t l = 0; l < 4; ++l) cl.uploadTexture(array, 0, l, checker(4, 4, 4, colours[l], colours[l]).rgba);
  const float layers[6] = {0.3f, 0.7f, 1.2f, 1.8f, 2.4f, 2.7f};
  std::vector<float> tam;
  for (float r : layers) tam.insert(tam.end(), {0.0f, r});
  std::span<const uint8_t> tamBytes(reinterpret_cast<const uint8_t*>(tam.data()), tam.size() * sizeof(float));
  TextureDesc td;
  td.kind = TextureKind::Buffer;
  td.format = Format::RG32F;
  td.width = uint32_t(tam.size() / 2);
  td.buffer = cl.createBuffer(BufferKind::Texel, tamBytes);
  Mesh m;
  for (int i = 0; i < 6; ++i) {
    const float x0 = float(i) + 0.1f, z = float(i);
    m.quad({x0, 0.1f, 0}, {x0 + 0.8f, 0.1f, 0}, {x0 + 0.8f, 0.9f, 0}, {x0, 0.9f, 0}, {0, 0, z, 0}, {1, 0, z, 0},
           {1, 1, z, 0}, {0, 1, z, 0});
  }
  const uint32_t n = bindMesh(cl, m);
  cl.useProgram(cl.createProgram("texarray_batch"));
  setMatrix(cl, 0, ortho(0, 6, 0, 1, -1, 1));
  cl.bindTexture(0, cl.createTexture(td));
  cl.bindTexture(1, array);
  SamplerState s;
  s.minFilter = Filter::Nearest;
  s.magFilter = Filter::Nearest;
  cl.bindSampler(1, cl.createSampler(s));
  cl.drawIndexed(0, n);
}

}  // namespace tessera::scenes
