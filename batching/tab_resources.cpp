#include "batching/tab_resources.h"

#include <vector>

namespace tessera::batching {

namespace {
Wrap toWrap(WrapMode w) {
  switch (w) {
    case WrapMode::Repeat: return Wrap::Repeat;
    case WrapMode::ClampToEdge: return Wrap::ClampToEdge;
    case WrapMode::MirroredRepeat: return Wrap::MirroredRepeat;
  }
  return Wrap::Repeat;
}
}  // namespace

SamplerState tabSampler(WrapMode s, WrapMode t) {
  SamplerState st;
  st.wrapS = toWrap(s);
  st.wrapT = toWrap(t);
  st.minFilter = Filter::LinearMipmapLinear;
  st.magFilter = Filter::Linear;
  return st;
}

ResourceId recordTexture2D(CommandList& cl, const TabScene& s, uint32_t t) {
  const TabTexture& tex = s.textures[t];
  TextureDesc d;
  d.width = tex.width;
  d.height = tex.height;
  d.levels = uint32_t(tex.levels.size());
  const ResourceId id = cl.createTexture(d);
  for (uint32_t l = 0; l < tex.levels.size(); ++l) cl.uploadTexture(id, l, 0, tex.levels[l]);
  return id;
}

ResourceId recordTextureArray(CommandList& cl, const TabScene& s, uint32_t a) {
  const TextureArray& ta = s.arrays[a];
  TextureDesc d;
  d.kind = TextureKind::Tex2DArray;
  d.width = ta.key.width;
  d.height = ta.key.height;
  d.layers = uint32_t(ta.layers.size());
  d.levels = fullMipCount(d.width, d.height);
  const ResourceId id = cl.createTexture(d);
  for (uint32_t layer = 0; layer < ta.layers.size(); ++layer) {
    const TabTexture& tex = s.textures[ta.layers[layer]];
    for (uint32_t l = 0; l < d.levels; ++l) cl.uploadTexture(id, l, layer, tex.levels[l]);
  }
  return id;
}

ResourceId recordTam(CommandList& cl, const OutputBatch& b, bool opaqueMaterials) {
  std::vector<float> texels;
  texels.reserve(b.tam.size() * 8);
  for (const TamEntry& e : b.tam) {
    const float cutoff = opaqueMaterials ? 0.0f : e.alphaCutoff;
    const float opaque = opaqueMaterials || e.opaque ? 1.0f : 0.0f;
    texels.insert(texels.end(), {float(e.array), float(e.layer), cutoff, opaque});
    texels.insert(texels.end(), e.factor.begin(), e.factor.end());
  }
  const ResourceId buf = cl.createBuffer(
      BufferKind::Texel, {reinterpret_cast<const uint8_t*>(texels.data()), texels.size() * sizeof(float)});
  TextureDesc d;
  d.kind = TextureKind::Buffer;
  d.format = Format::RGBA32F;
  d.width = uint32_t(b.tam.size() * 2);
  d.buffer = buf;
  return cl.createTexture(d);
}

}  // namespace tessera::batching
