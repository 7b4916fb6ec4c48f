#include "mta/frame_recorder.h"

#include <map>

#include "base/error.h"
#include "raster/texture.h"

namespace tessera::mta {

namespace {

constexpr uint32_t kStride = sizeof(RuntimeVertex), kLayeredStride = sizeof(LayeredVertex);
static_assert(sizeof(RuntimeVertex) == 36 && sizeof(LayeredVertex) == 44);

// "textured_layers" reads (s0, t0, s1, t1) from attribute 1 (runtime_geometry.h LayeredVertex).
VertexLayout layeredLayout(bool atlasCoords) {
  VertexLayout l;
  l.stride = kLayeredStride;
  l.attribs[0] = {0, 3, AttribType::F32, 0};
  l.attribs[1] = {1, 4, AttribType::F32, atlasCoords ? 12u : 28u};
  return l;
}

VertexLayout layout(bool atlasCoords, bool id) {
  VertexLayout l;
  l.stride = kStride;
  l.attribs[0] = {0, 3, AttribType::F32, 0};
  if (id) l.attribs[2] = {2, 1, AttribType::U32, 28};
  else l.attribs[1] = {1, 2, AttribType::F32, atlasCoords ? 12u : 20u};
  return l;
}

Wrap toWrap(model::Wrap w) {
  switch (w) {
    case model::Wrap::Repeat: return Wrap::Repeat;
    case model::Wrap::ClampToEdge: return Wrap::ClampToEdge;
    case model::Wrap::MirroredRepeat: return Wrap::MirroredRepeat;
  }
  return Wrap::Repeat;
}

ResourceId upload(CommandList& cl, const MipChain& c) {
  TextureDesc d;
  d.kind = TextureKind::Tex2D;
  d.format = Format::RGBA8;
  d.compression = c.compression;  // S3TC files: the blocks as stored; the oracle decodes, GL takes them as they are
  d.width = c.width;
  d.height = c.height;
  d.levels = uint32_t(c.levels.size());
  const ResourceId id = cl.createTexture(d);
  for (uint32_t l = 0; l < c.levels.size(); ++l) cl.uploadTexture(id, l, 0, c.levels[l]);
  return id;
}

// Layer 0's matrix (slots 4-6), and layer 1's (slots 9-11) when it is drawn: the same, as both layers
// are sampled at the same coordinates scaled by the same 2^level.
void setTextureMatrix(CommandList& cl, float s, bool layered) {
  const float m[12] = {s, 0, 0, 0, 0, s, 0, 0, 0, 0, 1, 0};
  cl.setUniforms(4, m);
  if (layered) cl.setUniforms(9, m);
}

}  // namespace

RecordedFrame recordFrame(const MtaMeta& meta, const RuntimeGeometry& geometry, const FramePlan& plan, const ViewParams& view,
                          TextureCache& textures, const RecordParams& params) {
  RecordedFrame f;
  recordFrame(meta, geometry, plan, view, textures, params, f);
  return f;
}

void recordFrame(const MtaMeta& meta, const RuntimeGeometry& geometry, const FramePlan& plan, const ViewParams& view,
                 TextureCache& textures, const RecordParams& params, RecordedFrame& f) {
  f.list.clear();
  f.drawTexture.clear();
  CommandList& cl = f.list;
  const int w = int(params.width), h = int(params.height);
  auto target = [&](Format fmt) {
    TextureDesc d;
    d.format = fmt;
    d.width = params.width;
    d.height = params.height;
    return cl.createTexture(d);
  };
  RenderTarget rt;
  rt.color[0] = target(params.idFrame ? Format::R32UI : Format::RGBA8);
  if (params.idFrame) rt.color[1] = target(Format::R32UI);
  rt.depth = target(Format::D32F);
  cl.setRenderTarget(rt);
  cl.setViewport({0, 0, w, h});
  if (params.idFrame) {
    cl.clearColorUint(0, {0xffffffffu, 0, 0, 0});
    cl.clearColorUint(1, {0xffffffffu, 0, 0, 0});
  } else {
    cl.clearColor(0, params.clear);
  }
  cl.clearDepth(1.0f);
  DepthState ds;
  ds.test = true;
  cl.setDepthState(ds);
  // The id frame draws the same triangles from the plain array whether or not the file has a layer 1.
  const bool layered = recordsLayer1(meta) && !params.idFrame;
  if (layered && geometry.layered.size() != geometry.vertices.size())
    throw Error("frame recorder: internal error: the file has a layer 1 but the runtime geometry has no layered vertices");
  if (layered) {
    const auto* vb = reinterpret_cast<const uint8_t*>(geometry.layered.data());
    cl.bindVertexBuffer(
        cl.createBuffer(BufferKind::Vertex, std::span<const uint8_t>(vb, geometry.layered.size() * kLayeredStride)));
  } else {
    const auto* vb = reinterpret_cast<const uint8_t*>(geometry.vertices.data());
    cl.bindVertexBuffer(cl.createBuffer(BufferKind::Vertex, std::span<const uint8_t>(vb, geometry.vertices.size() * kStride)));
  }
  cl.useProgram(cl.createProgram(params.idFrame ? "object_id" : layered ? "textured_layers" : "textured"));
  const auto mvp = viewProjection(view.camera, params.width, params.height);
  cl.setUniforms(0, std::span<const float>(&mvp[0][0], 16));  // glm::mat4: 4 contiguous columns

  f.drawTexture.resize(plan.draws.size());
  if (params.idFrame) {
    cl.setVertexLayout(layout(false, true));
    for (const PlannedDraw& d : plan.draws) cl.draw(d.first * 3, d.count * 3);
    return;
  }
  const float white[4] = {1, 1, 1, 1}, zero[4] = {0, 0, 0, 0};
  cl.setUniforms(7, white);
  cl.setUniforms(8, zero);
  if (layered) {
    // Strength 1, R-only (frame_recorder.h says why).
    const float occlusion[4] = {1, 1, 0, 0};
    cl.setUniforms(12, occlusion);
  }
  float matrixScale = -1.0f;
  int layoutKind = -1;  // 1 atlas coords, 0 original coords
  ResourceId boundSampler = kNone, boundTexture = kNone, boundSampler1 = kNone, boundTexture1 = kNone;
  bool tintGrey = false;
  std::map<uint64_t, ResourceId> texIds, samplerIds;
  auto sampler = [&](Wrap s, Wrap t) {
    const uint64_t key = uint64_t(s) * 16 + uint64_t(t);
    auto [it, fresh] = samplerIds.emplace(key, kNone);
    if (fresh) {
      SamplerState st;
      st.wrapS = s;
      st.wrapT = t;
      st.minFilter = Filter::LinearMipmapLinear;
      st.magFilter = Filter::Linear;
      it->second = cl.createSampler(st);
    }
    return it->second;
  };
  static const MipChain kWhite = [] {
    MipChain c;
    c.width = c.height = 1;
    c.levels = {{255, 255, 255, 255}};
    return c;
  }();
  // Resources first: every texture the frame binds is created and uploaded before the first draw, as a
  // renderer holding its textures would have them (and uploads between draws would split the oracle's
  // tile work into batches, which made the comparison runs' timings depend on upload order).
  struct Binding {
    ResourceId texture = kNone, sampler = kNone;
    ResourceId texture1 = kNone, sampler1 = kNone;  // unit 1 (files with a layer 1)
    float scale = 1.0f;
    bool grey = false;  // untextured triangles
  };
  std::vector<Binding> bind(plan.draws.size());
  for (size_t i = 0; i < plan.draws.size(); ++i) {
    const PlannedDraw& d = plan.draws[i];
    const MipChain* chain = nullptr;
    uint64_t key = 0;
    Wrap ws = Wrap::Repeat, wt = Wrap::Repeat;
    if (d.source == DrawSource::Atlas) {
      chain = &textures.atlas(d.tree, d.node);
      key = (uint64_t(1) << 62) | (uint64_t(d.tree) << 32) | d.node;
      bind[i].scale = meta.trees[d.tree].nodes[d.node].textureScale();
    } else if (d.source == DrawSource::Original) {
      const SceneTexture& st = meta.textures[uint32_t(d.texture)];
      chain = &textures.image(st.image);
      key = (uint64_t(2) << 62) | st.image;
      ws = toWrap(st.wrapS);
      wt = toWrap(st.wrapT);
    } else {
      chain = &kWhite;
      key = uint64_t(3) << 62;
      bind[i].grey = d.source == DrawSource::Untextured;
    }
    auto [it, fresh] = texIds.emplace(key, kNone);
    if (fresh) it->second = upload(cl, *chain);
    bind[i].texture = it->second;
    bind[i].sampler = sampler(ws, wt);
    // Before unit 1's chain is asked for: in file mode that call may drop `chain` (texture_cache.h).
    f.drawTexture[i] = BoundTexture{chain->width, chain->height, uint32_t(chain->levels.size()), double(bind[i].scale)};
    if (layered) {
      // Unit 1: the node's layer-1 atlas (keyed apart from its layer 0 by bit 40), the original's layer-1
      // texture (an image, keyed as on unit 0, so an image bound on both units is uploaded once), or white.
      const MipChain* chain1 = &kWhite;
      uint64_t key1 = uint64_t(3) << 62;
      Wrap ws1 = Wrap::Repeat, wt1 = Wrap::Repeat;
      if (d.source == DrawSource::Atlas) {
        chain1 = &textures.atlas(d.tree, d.node, 1);
        key1 = (uint64_t(1) << 62) | (uint64_t(1) << 40) | (uint64_t(d.tree) << 32) | d.node;
      } else if (d.source == DrawSource::Original && d.texture1 >= 0) {
        const SceneTexture& st = meta.textures[uint32_t(d.texture1)];
        chain1 = &textures.image(st.image);
        key1 = (uint64_t(2) << 62) | st.image;
        ws1 = toWrap(st.wrapS);
        wt1 = toWrap(st.wrapT);
      }
      auto [it1, fresh1] = texIds.emplace(key1, kNone);
      if (fresh1) it1->second = upload(cl, *chain1);
      bind[i].texture1 = it1->second;
      bind[i].sampler1 = sampler(ws1, wt1);
    }
  }
  for (size_t i = 0; i < plan.draws.size(); ++i) {
    const PlannedDraw& d = plan.draws[i];
    const int wantLayout = d.source == DrawSource::Atlas ? 1 : 0;
    if (wantLayout != layoutKind) {
      cl.setVertexLayout(layered ? layeredLayout(wantLayout == 1) : layout(wantLayout == 1, false));
      layoutKind = wantLayout;
    }
    if (bind[i].grey != tintGrey) {
      static const float kGrey[4] = {0.62f, 0.6f, 0.55f, 1.0f}, kWhiteTint[4] = {1, 1, 1, 1};
      cl.setUniforms(7, bind[i].grey ? kGrey : kWhiteTint);
      tintGrey = bind[i].grey;
    }
    if (bind[i].scale != matrixScale) {
      setTextureMatrix(cl, bind[i].scale, layered);
      matrixScale = bind[i].scale;
    }
    // Binds only when the unit's binding changes, as a renderer tracking its state would.
    if (bind[i].sampler != boundSampler) cl.bindSampler(0, boundSampler = bind[i].sampler);
    if (bind[i].texture != boundTexture) cl.bindTexture(0, boundTexture = bind[i].texture);
    if (layered) {
      if (bind[i].sampler1 != boundSampler1) cl.bindSampler(1, boundSampler1 = bind[i].sampler1);
      if (bind[i].texture1 != boundTexture1) cl.bindTexture(1, boundTexture1 = bind[i].texture1);
    }
    cl.draw(d.first * 3, d.count * 3);
  }
}

}  // namespace tessera::mta
