#include "mta/frame_recorder.h"

#include <cstring>

#include "raster/texture.h"

namespace tessera::mta {

uint64_t MipChain::bytes() const {
  uint64_t b = 0;
  for (const auto& l : levels) b += l.size();
  return b;
}

TextureCache::TextureCache(const PagingFile& file, const Residency* residency, uint64_t fileCacheBytes)
    : file_(file), residency_(residency), fileCacheBytes_(fileCacheBytes) {}

void TextureCache::prune() {
  if (!residency_) return;
  for (auto it = entries_.begin(); it != entries_.end();) {
    bool stale = false;
    for (auto [b, gen] : it->second.blocks) stale |= !residency_->resident(b) || residency_->generation(b) != gen;
    if (stale) {
      bytes_ -= it->second.chain->bytes();
      it = entries_.erase(it);
    } else {
      ++it;
    }
  }
}

// The bytes of a block, valid until the next call: resident data, or (file mode) one of the last few
// blocks read.
std::span<const uint8_t> TextureCache::blockBytes(uint32_t block) {
  if (!residency_) {
    // Original blocks pack many images in first-use order, so the images of one leaf mostly share a
    // block: keep the last few read (each read verifies the block's SHA-256, which dominated `mta runs`).
    for (const auto& [b, bytes] : recentBlocks_)
      if (b == block) return bytes;
    if (recentBlocks_.size() == 4) recentBlocks_.erase(recentBlocks_.begin());
    recentBlocks_.emplace_back(block, file_.readBlock(block));
    return recentBlocks_.back().second;
  }
  const auto span = residency_->data(block);
  if (span.empty()) throw Error("texture cache: internal error: block " + std::to_string(block) + " is not in memory");
  return span;
}

const MipChain& TextureCache::store(uint64_t key, std::shared_ptr<MipChain> chain, std::vector<std::pair<uint32_t, uint64_t>> blocks) {
  if (!residency_ && bytes_ + chain->bytes() > fileCacheBytes_) {
    entries_.clear();  // comparison runs: a crude bound is enough, the file is the backing store
    bytes_ = 0;
  }
  bytes_ += chain->bytes();
  Entry& e = entries_[key];
  e.chain = std::move(chain);
  e.blocks = std::move(blocks);
  return *e.chain;
}

namespace {

std::vector<uint8_t> toRGBA(const uint8_t* src, size_t texels, uint32_t channels) {
  std::vector<uint8_t> out(texels * 4);
  for (size_t i = 0; i < texels; ++i) {
    out[i * 4 + 0] = src[i * channels + 0];
    out[i * 4 + 1] = src[i * channels + 1];
    out[i * 4 + 2] = src[i * channels + 2];
    out[i * 4 + 3] = channels == 4 ? src[i * channels + 3] : 255;
  }
  return out;
}

}  // namespace

const MipChain& TextureCache::atlas(uint8_t tree, uint32_t node) {
  const uint64_t key = (uint64_t(1) << 62) | (uint64_t(tree) << 32) | node;
  if (auto it = entries_.find(key); it != entries_.end()) return *it->second.chain;
  const MtaMeta& m = file_.meta();
  const uint32_t block = m.trees[tree].atlasBlocks[size_t(node) * m.layerCount];
  const std::span<const uint8_t> raw = blockBytes(block);
  const uint32_t a = m.params.atlasSize;
  auto chain = std::make_shared<MipChain>();
  chain->width = chain->height = a;
  chain->levels = buildMipChainRGBA8(a, a, toRGBA(raw.data(), size_t(a) * a, m.trees[tree].channels()));
  return store(key, std::move(chain), {{block, residency_ ? residency_->generation(block) : 0}});
}

const MipChain& TextureCache::image(uint32_t image) {
  const uint64_t key = (uint64_t(2) << 62) | image;
  if (auto it = entries_.find(key); it != entries_.end()) return *it->second.chain;
  const MtaMeta& m = file_.meta();
  const ImageRecord& r = m.images[image];
  std::vector<uint8_t> texels(size_t(r.width) * r.height * r.channels);
  std::vector<std::pair<uint32_t, uint64_t>> blocks;
  const size_t rowBytes = size_t(r.width) * r.channels;
  for (uint32_t k = 0; k < r.pieceCount; ++k) {
    const PieceRecord& p = m.pieces[r.firstPiece + k];
    const std::span<const uint8_t> bytes = blockBytes(p.block);
    std::memcpy(texels.data() + size_t(p.row0) * rowBytes, bytes.data() + p.offset, size_t(p.rows) * rowBytes);
    blocks.emplace_back(p.block, residency_ ? residency_->generation(p.block) : 0);
  }
  auto chain = std::make_shared<MipChain>();
  chain->width = r.width;
  chain->height = r.height;
  // Stored top row first with v = 0 there; uploaded as is, GL's t = 0 row is v = 0 (docs/mta-format.md).
  chain->levels = buildMipChainRGBA8(r.width, r.height, toRGBA(texels.data(), size_t(r.width) * r.height, r.channels));
  return store(key, std::move(chain), std::move(blocks));
}

namespace {

constexpr uint32_t kStride = sizeof(RuntimeVertex);
static_assert(sizeof(RuntimeVertex) == 36);

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
  d.width = c.width;
  d.height = c.height;
  d.levels = uint32_t(c.levels.size());
  const ResourceId id = cl.createTexture(d);
  for (uint32_t l = 0; l < c.levels.size(); ++l) cl.uploadTexture(id, l, 0, c.levels[l]);
  return id;
}

void setTextureMatrix(CommandList& cl, float s) {
  const float m[12] = {s, 0, 0, 0, 0, s, 0, 0, 0, 0, 1, 0};
  cl.setUniforms(4, m);
}

}  // namespace

RecordedFrame recordFrame(const MtaMeta& meta, const RuntimeGeometry& geometry, const FramePlan& plan, const ViewParams& view,
                          TextureCache& textures, const RecordParams& params) {
  RecordedFrame f;
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
  const auto* vb = reinterpret_cast<const uint8_t*>(geometry.vertices.data());
  cl.bindVertexBuffer(cl.createBuffer(BufferKind::Vertex, std::span<const uint8_t>(vb, geometry.vertices.size() * kStride)));
  cl.useProgram(cl.createProgram(params.idFrame ? "object_id" : "textured"));
  const auto mvp = viewProjection(view.camera, params.width, params.height);
  cl.setUniforms(0, std::span<const float>(&mvp[0][0], 16));  // glm::mat4: 4 contiguous columns

  f.drawTexture.resize(plan.draws.size());
  if (params.idFrame) {
    cl.setVertexLayout(layout(false, true));
    for (const PlannedDraw& d : plan.draws) cl.draw(d.first * 3, d.count * 3);
    return f;
  }
  const float white[4] = {1, 1, 1, 1}, zero[4] = {0, 0, 0, 0};
  cl.setUniforms(7, white);
  cl.setUniforms(8, zero);
  float matrixScale = -1.0f;
  int layoutKind = -1;  // 1 atlas coords, 0 original coords
  ResourceId boundSampler = kNone, boundTexture = kNone;
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
    f.drawTexture[i] = BoundTexture{chain->width, chain->height, uint32_t(chain->levels.size()), double(bind[i].scale)};
  }
  for (size_t i = 0; i < plan.draws.size(); ++i) {
    const PlannedDraw& d = plan.draws[i];
    const int wantLayout = d.source == DrawSource::Atlas ? 1 : 0;
    if (wantLayout != layoutKind) {
      cl.setVertexLayout(layout(wantLayout == 1, false));
      layoutKind = wantLayout;
    }
    if (bind[i].grey != tintGrey) {
      static const float kGrey[4] = {0.62f, 0.6f, 0.55f, 1.0f}, kWhiteTint[4] = {1, 1, 1, 1};
      cl.setUniforms(7, bind[i].grey ? kGrey : kWhiteTint);
      tintGrey = bind[i].grey;
    }
    if (bind[i].scale != matrixScale) {
      setTextureMatrix(cl, bind[i].scale);
      matrixScale = bind[i].scale;
    }
    // Binds only when the unit's binding changes, as a renderer tracking its state would.
    if (bind[i].sampler != boundSampler) cl.bindSampler(0, boundSampler = bind[i].sampler);
    if (bind[i].texture != boundTexture) cl.bindTexture(0, boundTexture = bind[i].texture);
    cl.draw(d.first * 3, d.count * 3);
  }
  return f;
}

}  // namespace tessera::mta
