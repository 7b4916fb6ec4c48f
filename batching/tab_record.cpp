#include "batching/tab_record.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <vector>

#include "batching/tab_resources.h"
#include "raster/texture.h"

namespace tessera::batching {

const char* variantName(Variant v) { return v == Variant::Batched ? "batched" : "baseline"; }

namespace {

template <class T>
std::span<const uint8_t> asBytes(const std::vector<T>& v) {
  return {reinterpret_cast<const uint8_t*>(v.data()), v.size() * sizeof(T)};
}

// Records resources and state once; every bind goes through `Binder` so the baseline binds on change.
class Recorder {
 public:
  Recorder(const TabScene& s, CommandList& cl) : s_(s), cl_(cl) {}

  ResourceId sampler(WrapMode ws, WrapMode wt) {
    auto [it, fresh] = samplers_.emplace(uint32_t(ws) * 16 + uint32_t(wt), kNone);
    if (fresh) it->second = cl_.createSampler(tabSampler(ws, wt));
    return it->second;
  }
  ResourceId texture2D(uint32_t t) {
    auto [it, fresh] = textures_.emplace(t, kNone);
    if (fresh) it->second = recordTexture2D(cl_, s_, t);
    return it->second;
  }
  ResourceId textureArray(uint32_t a) { return recordTextureArray(cl_, s_, a); }
  ResourceId tam(const OutputBatch& b) { return recordTam(cl_, b); }

 private:
  const TabScene& s_;
  CommandList& cl_;
  std::map<uint32_t, ResourceId> samplers_, textures_;
};

VertexLayout layout(int texcoordComponents) {
  VertexLayout l;
  l.stride = sizeof(Vertex);
  l.attribs[0] = {0, 3, AttribType::F32, 0};
  l.attribs[1] = {1, uint8_t(texcoordComponents), AttribType::F32, 12};
  return l;
}

// The `textured` program's per-mesh uniforms: tint (slot 7) and (bias, alpha cutoff, opaque) (slot 8).
struct Material {
  std::array<float, 4> tint{1, 1, 1, 1};
  std::array<float, 4> alpha{0, 0, 0, 0};
  bool operator==(const Material&) const = default;
};
Material materialOf(const TabMesh& m) {
  Material mat;
  mat.tint = m.factor;
  mat.alpha = {0.0f, m.alphaMode == AlphaMode::Mask ? m.alphaCutoff : 0.0f, m.alphaMode == AlphaMode::Blend ? 0.0f : 1.0f, 0.0f};
  return mat;
}

}  // namespace

CommandList recordTabFrame(const TabScene& s, Variant variant, const TabView& view, TabDraws* drawsOut) {
  CommandList cl;
  recordTabFrame(s, variant, view, cl, drawsOut);
  return cl;
}

void recordTabFrame(const TabScene& s, Variant variant, const TabView& view, CommandList& cl, TabDraws* drawsOut) {
  cl.clear();
  Recorder rec(s, cl);
  TabDraws draws;
  auto target = [&](Format f) {
    TextureDesc d;
    d.format = f;
    d.width = view.width;
    d.height = view.height;
    return cl.createTexture(d);
  };
  RenderTarget rt;
  rt.color[0] = target(Format::RGBA8);
  rt.depth = target(Format::D32F);

  // --- resources, all before the first draw ---
  const ResourceId vb = cl.createBuffer(BufferKind::Vertex, asBytes(s.vertices));
  std::vector<uint32_t> untextured, blend, batched;
  for (uint32_t i = 0; i < s.meshes.size(); ++i)
    (s.meshes[i].kind == MeshKind::Batched ? batched : s.meshes[i].kind == MeshKind::Untextured ? untextured : blend).push_back(i);
  ResourceId flatVb = kNone;
  uint32_t flatVertices = 0;
  if (!untextured.empty()) {
    std::vector<float> v;  // x, y, z, r, g, b, a
    for (uint32_t i : untextured) {
      const TabMesh& m = s.meshes[i];
      for (uint32_t k = 0; k < m.vertexCount; ++k) {
        const Vertex& p = s.vertices[size_t(m.firstVertex) + k];
        v.insert(v.end(), {p.x, p.y, p.z, m.factor[0], m.factor[1], m.factor[2], m.factor[3]});
      }
      flatVertices += m.vertexCount;
    }
    flatVb = cl.createBuffer(BufferKind::Vertex, asBytes(v));
  }
  const ResourceId textured = (variant == Variant::Baseline || !blend.empty()) ? cl.createProgram("textured") : kNone;
  const ResourceId flat = flatVb != kNone ? cl.createProgram("vertex_color") : kNone;
  // Meshes drawn with `textured` (the baseline's batched meshes, every BLEND mesh): their unit-0 texture.
  std::vector<ResourceId> meshTexture(s.meshes.size(), kNone), meshSampler(s.meshes.size(), kNone);
  auto prepareTextured = [&](uint32_t i) {
    const uint32_t t = s.meshes[i].textures.at(0);
    meshTexture[i] = rec.texture2D(t);
    meshSampler[i] = rec.sampler(s.textures[t].wrapS, s.textures[t].wrapT);
  };
  if (variant == Variant::Baseline)
    for (uint32_t i : batched) prepareTextured(i);
  for (uint32_t i : blend) prepareTextured(i);
  struct BatchRes {
    std::vector<ResourceId> arrays, samplers;
    ResourceId tam = kNone;
  };
  std::vector<BatchRes> batchRes;
  ResourceId texarray = kNone;
  if (variant == Variant::Batched && !s.batches.empty()) {
    texarray = cl.createProgram("texarray_batch");
    for (const OutputBatch& b : s.batches) {
      BatchRes r;
      for (uint32_t a : b.arrays) {
        r.arrays.push_back(rec.textureArray(a));
        r.samplers.push_back(rec.sampler(s.arrays[a].key.wrapS, s.arrays[a].key.wrapT));
      }
      r.tam = rec.tam(b);
      batchRes.push_back(std::move(r));
    }
  }

  // --- the frame ---
  cl.setRenderTarget(rt);
  cl.setViewport({0, 0, int(view.width), int(view.height)});
  cl.clearColor(0, view.clear);
  cl.clearDepth(1.0f);
  DepthState ds;
  ds.test = true;
  cl.setDepthState(ds);
  const std::span<const float> mvp(&view.mvp[0][0], 16);

  if (flatVb != kNone) {
    cl.marker("untextured");
    cl.bindVertexBuffer(flatVb);
    VertexLayout l;
    l.stride = 28;
    l.attribs[0] = {0, 3, AttribType::F32, 0};
    l.attribs[1] = {1, 4, AttribType::F32, 12};
    cl.setVertexLayout(l);
    cl.useProgram(flat);
    cl.setUniforms(0, mvp);
    cl.draw(0, flatVertices);
    draws.untextured = 1;
  }
  cl.bindVertexBuffer(vb);
  Material current;
  bool materialSet = false;
  ResourceId boundTex = kNone, boundSmp = kNone;
  auto drawTexturedMesh = [&](uint32_t i) {
    const TabMesh& m = s.meshes[i];
    const Material mat = materialOf(m);
    if (!materialSet || !(mat.tint == current.tint)) cl.setUniforms(7, mat.tint);
    if (!materialSet || !(mat.alpha == current.alpha)) cl.setUniforms(8, mat.alpha);
    current = mat, materialSet = true;
    if (meshSampler[i] != boundSmp) cl.bindSampler(0, boundSmp = meshSampler[i]);
    if (meshTexture[i] != boundTex) cl.bindTexture(0, boundTex = meshTexture[i]);
    cl.draw(m.firstVertex, m.vertexCount);
  };
  auto useTextured = [&] {
    cl.setVertexLayout(layout(2));
    cl.useProgram(textured);
    cl.setUniforms(0, mvp);
    static const float kIdentity[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    cl.setUniforms(4, kIdentity);
  };
  if (variant == Variant::Baseline && !batched.empty()) {
    cl.marker("baseline");
    useTextured();
    for (uint32_t i : batched) drawTexturedMesh(i), ++draws.textured;
  } else if (variant == Variant::Batched && !s.batches.empty()) {
    cl.marker("batched");
    cl.setVertexLayout(layout(3));
    static const float kMaterialLayout[4] = {1, 0, 0, 0};
    for (size_t bi = 0; bi < s.batches.size(); ++bi) {  // Algorithm 2
      const BatchRes& r = batchRes[bi];
      for (size_t a = 0; a < r.arrays.size(); ++a) {
        cl.bindTexture(uint32_t(1 + a), r.arrays[a]);  // texture state change
        cl.bindSampler(uint32_t(1 + a), r.samplers[a]);
      }
      cl.bindTexture(0, r.tam);
      cl.useProgram(texarray);
      if (bi == 0) {
        cl.setUniforms(0, mvp);
        cl.setUniforms(4, kMaterialLayout);
      }
      for (const GeometryBatch& g : s.batches[bi].geometry) cl.draw(g.firstVertex, g.vertexCount), ++draws.textured;
    }
  }
  if (!blend.empty()) {
    cl.marker("blend");
    std::vector<std::pair<double, uint32_t>> order;
    for (uint32_t i : blend) {
      const TabMesh& m = s.meshes[i];
      glm::dvec3 lo(1e300), hi(-1e300);
      for (uint32_t k = 0; k < m.vertexCount; ++k) {
        const Vertex& p = s.vertices[size_t(m.firstVertex) + k];
        lo = glm::min(lo, glm::dvec3(p.x, p.y, p.z));
        hi = glm::max(hi, glm::dvec3(p.x, p.y, p.z));
      }
      const glm::dvec3 c = (lo + hi) * 0.5, d = c - view.eye;
      order.emplace_back(d.x * d.x + d.y * d.y + d.z * d.z, i);
    }
    std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    useTextured();
    if (variant == Variant::Batched) boundTex = boundSmp = kNone;  // unit 0 held the TAM
    materialSet = false;
    BlendState bs;
    bs.enabled = true;
    bs.srcRgb = BlendFactor::SrcAlpha, bs.dstRgb = BlendFactor::OneMinusSrcAlpha;
    bs.srcAlpha = BlendFactor::One, bs.dstAlpha = BlendFactor::OneMinusSrcAlpha;
    cl.setBlendState(bs);
    DepthState nw = ds;
    nw.write = false;
    cl.setDepthState(nw);
    for (const auto& [dist, i] : order) drawTexturedMesh(i), ++draws.blend;
  }
  if (drawsOut) *drawsOut = draws;
}

}  // namespace tessera::batching
