#include "rtta/rtta_record.h"

#include <algorithm>
#include <fmt/format.h>
#include <map>
#include <utility>

#include "base/error.h"
#include "batching/tab_resources.h"
#include "raster/limits.h"
#include "raster/programs/atlas_ao.h"
#include "rtta/record_buffer.h"
#include "rtta/transform.h"

namespace tessera::rtta {

const char* modeName(Mode m) { return m == Mode::Std ? "std" : m == Mode::Rtt ? "rtt" : "rtta"; }
const char* texturingName(Texturing t) { return t == Texturing::Bind ? "bind" : "tab"; }
const char* compositeName(Composite c) {
  switch (c) {
    case Composite::Depth: return "depth";
    case Composite::Transparent: return "transparent";
    case Composite::Ghosted: return "ghosted";
    case Composite::GhostedAo: return "ghosted-ao";
  }
  return "?";
}

int32_t defaultAtlasSide(int32_t viewportSide, int32_t border) {
  const int32_t need = borderedRegion({0, 0, viewportSide, 1}, border).width();
  int32_t s = 2;
  while (s < need) s *= 2;
  return s;
}

namespace {

template <class T>
std::span<const uint8_t> asBytes(const std::vector<T>& v) {
  return {reinterpret_cast<const uint8_t*>(v.data()), v.size() * sizeof(T)};
}

// A run of consecutive meshes drawn by one draw: same texture (-1 = the white texel) and factor.
struct DrawRun {
  int64_t texture = -1;
  std::array<float, 4> factor{1, 1, 1, 1};
  uint32_t first = 0, count = 0;
};

int64_t textureOf(const batching::TabMesh& m) { return m.textures.empty() ? -1 : int64_t(m.textures[0]); }

// Runs over every mesh, or (unbatchedOnly) over the meshes TAB's output batches do not hold.
std::vector<DrawRun> drawRuns(const batching::TabScene& s, bool unbatchedOnly = false) {
  std::vector<DrawRun> runs;
  for (const batching::TabMesh& m : s.meshes) {
    if (m.vertexCount == 0 || (unbatchedOnly && m.kind == batching::MeshKind::Batched)) continue;
    const int64_t t = textureOf(m);
    if (!runs.empty() && runs.back().texture == t && runs.back().factor == m.factor &&
        runs.back().first + runs.back().count == m.firstVertex) {
      runs.back().count += m.vertexCount;
      continue;
    }
    runs.push_back({t, m.factor, m.firstVertex, m.vertexCount});
  }
  return runs;
}

class Recorder {
 public:
  Recorder(const RttaScene& s, CommandList& cl) : s_(s), cl_(cl) {}

  // Texture t of the scene (-1: a 1x1 white texel) and its sampler, created (and uploaded) on first use.
  ResourceId texture(int64_t t) {
    auto [it, fresh] = textures_.emplace(t, kNone);
    if (fresh) {
      if (t < 0) {
        TextureDesc d;
        d.width = d.height = 1;
        it->second = cl_.createTexture(d);
        const std::vector<uint8_t> white{255, 255, 255, 255};
        cl_.uploadTexture(it->second, 0, 0, white);
      } else {
        it->second = batching::recordTexture2D(cl_, s_.tab, uint32_t(t));
      }
    }
    return it->second;
  }
  uint32_t samplerKey(int64_t t) const {
    const batching::TabTexture* tex = t < 0 ? nullptr : &s_.tab.textures[size_t(t)];
    return tex ? uint32_t(tex->wrapS) * 16 + uint32_t(tex->wrapT) : 0;
  }
  ResourceId sampler(int64_t t) {
    auto [it, fresh] = samplers_.emplace(samplerKey(t), kNone);
    if (fresh) {
      const batching::TabTexture* tex = t < 0 ? nullptr : &s_.tab.textures[size_t(t)];
      it->second = cl_.createSampler(tex ? batching::tabSampler(tex->wrapS, tex->wrapT)
                                         : batching::tabSampler(batching::WrapMode::Repeat, batching::WrapMode::Repeat));
    }
    return it->second;
  }
  // Binds texture t and its sampler on `unit`, each only when it changes (so the counters see the
  // binds a state-tracking renderer would issue, and no more).
  void bind(uint32_t unit, int64_t t) {
    if (bound_ == t) return;
    bound_ = t;
    cl_.bindTexture(unit, texture(t));
    if (samplerKey(t) != boundSampler_) {
      boundSampler_ = samplerKey(t);
      cl_.bindSampler(unit, sampler(t));
    }
  }
  // Creates and uploads every texture and sampler before the first draw (the frame's resources all
  // come first), without binding anything.
  void createAll(const std::vector<DrawRun>& runs) {
    for (const DrawRun& r : runs) texture(r.texture), sampler(r.texture);
  }
  void tint(const std::array<float, 4>& f) {
    if (haveTint_ && tint_ == f) return;
    haveTint_ = true;
    tint_ = f;
    cl_.setUniforms(7, f);
  }
  void resetUniformCache() { haveTint_ = false; }
  // After another program bound its own textures, samplers and uniforms.
  void resetBindings() {
    bound_ = -2;
    boundSampler_ = ~0u;
    haveTint_ = false;
  }

 private:
  const RttaScene& s_;
  CommandList& cl_;
  std::map<int64_t, ResourceId> textures_;
  std::map<uint32_t, ResourceId> samplers_;
  int64_t bound_ = -2;
  uint32_t boundSampler_ = ~0u;
  std::array<float, 4> tint_{};
  bool haveTint_ = false;
};

// bytes == nullptr: the on-screen 2D target; otherwise an off-screen array target (a layered target
// needs array textures even with one layer) whose bytes are added up.
ResourceId target(CommandList& cl, Format f, uint32_t w, uint32_t h, uint32_t layers, uint64_t* bytes) {
  TextureDesc d;
  d.kind = bytes ? TextureKind::Tex2DArray : TextureKind::Tex2D;
  d.format = f;
  d.width = w;
  d.height = h;
  d.layers = layers;
  if (bytes) *bytes += uint64_t(w) * h * layers * texelBytes(f);
  return cl.createTexture(d);
}

ResourceId recordBufferTexture(CommandList& cl, const std::vector<float>& texels) {
  TextureDesc d;
  d.kind = TextureKind::Buffer;
  d.format = Format::RGBA32F;
  d.width = uint32_t(texels.size() / 4);
  d.buffer = cl.createBuffer(BufferKind::Texel, asBytes(texels));
  return cl.createTexture(d);
}

std::vector<float> matrixSlots(const glm::mat4& m) {
  std::vector<float> u(16);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) u[size_t(c) * 4 + r] = m[c][r];
  return u;
}

// texcoordComponents: 2 (s, t) for the bind programs, 3 (s, t, i_TAM) for atlas_capture_tab.
VertexLayout sceneLayout(uint8_t texcoordComponents = 2) {
  VertexLayout l;
  l.stride = sizeof(RttaVertex);
  l.attribs[0] = {0, 3, AttribType::F32, 0};
  l.attribs[1] = {1, texcoordComponents, AttribType::F32, 12};
  l.attribs[2] = {2, 1, AttribType::U32, 24};
  return l;
}

// Sprite vertex: clip position (x, y, 0, 1) and (dx, dy, layer, 0) for atlas_sprite.
struct SpriteVertex {
  float x, y, z, w;
  float dx, dy, layer, pad;
};

void addSprite(std::vector<SpriteVertex>& v, const PixelRect& screen, const Rect& vp, int32_t dx, int32_t dy,
               int32_t layer) {
  const float x0 = float(windowToNdc(screen.x0, vp.x, vp.w)), x1 = float(windowToNdc(screen.x1, vp.x, vp.w));
  const float y0 = float(windowToNdc(screen.y0, vp.y, vp.h)), y1 = float(windowToNdc(screen.y1, vp.y, vp.h));
  const float fdx = float(dx), fdy = float(dy), fl = float(layer);
  const SpriteVertex c[4] = {{x0, y0, 0, 1, fdx, fdy, fl, 0}, {x1, y0, 0, 1, fdx, fdy, fl, 0},
                             {x1, y1, 0, 1, fdx, fdy, fl, 0}, {x0, y1, 0, 1, fdx, fdy, fl, 0}};
  for (int k : {0, 1, 2, 0, 2, 3}) v.push_back(c[k]);
}

// The window depths z_w (depth range [0, 1]) of a box's corners: (min, max), clamped to [0, 1]; a corner
// behind the eye (w <= 0) makes the span the whole range.
std::pair<double, double> windowDepthRange(const Box3& b, const glm::mat4& mvp) {
  double lo = 1.0, hi = 0.0;
  for (int c = 0; c < 8; ++c) {
    const glm::dvec4 v{(c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z, 1.0};
    const glm::dvec4 clip = glm::dmat4(mvp) * v;
    if (!(clip.w > 0.0)) return {0.0, 1.0};
    const double z = std::clamp(0.5 * (clip.z / clip.w) + 0.5, 0.0, 1.0);
    lo = std::min(lo, z), hi = std::max(hi, z);
  }
  return {lo, hi};
}

}  // namespace

RttaFrame recordRttaFrame(const RttaScene& scene, const RttaView& view, const RttaOptions& o) {
  RttaFrame f;
  CommandList& cl = f.list;
  Recorder rec(scene, cl);
  const Rect vp{0, 0, int32_t(view.width), int32_t(view.height)};
  const std::vector<DrawRun> runs = drawRuns(scene.tab);
  const size_t nObj = scene.objectNames.size();

  // Algorithm 1, lines 1-9, for every mode (RTT and STD report the same regions).
  f.records = parameterize(scene.objectBounds, view.mvp, vp, o.params);

  // --- resources ---
  f.screen = target(cl, Format::RGBA8, view.width, view.height, 1, nullptr);
  const ResourceId screenDepth = f.screenDepth = target(cl, Format::D32F, view.width, view.height, 1, nullptr);
  const ResourceId vb = cl.createBuffer(BufferKind::Vertex, asBytes(scene.vertices));
  const bool tab = o.mode == Mode::Rtta && o.texturing == Texturing::Tab;
  rec.createAll(tab ? drawRuns(scene.tab, true) : runs);
  const ResourceId texturedProg = o.mode == Mode::Std ? cl.createProgram("textured") : kNone;
  const ResourceId captureProg = o.mode == Mode::Std ? kNone : cl.createProgram("atlas_capture");
  const ResourceId spriteProg = o.mode == Mode::Std || o.captureOnly ? kNone : cl.createProgram("atlas_sprite");
  const bool ao = o.composite == Composite::GhostedAo && spriteProg != kNone;
  const ResourceId aoProg = ao ? cl.createProgram("atlas_sprite_ao") : kNone;
  if (ao && o.mode == Mode::Rtta && o.params.border < programs::kAoRadius)
    throw Error(fmt::format("--composite ghosted-ao: --border {} is narrower than the occlusion kernel's radius {}, so "
                            "the kernel would read a neighbour's atlas region",
                            o.params.border, programs::kAoRadius));
  if (o.atlasInput && (o.mode != Mode::Rtta || o.captureOnly))
    throw Error("an uploaded atlas replaces RTTA's capture: it needs --mode rtta and a composite");
  const std::vector<float> mvp = matrixSlots(view.mvp);

  std::vector<uint32_t> visible;
  for (const Record& r : f.records)
    if (r.visible()) visible.push_back(r.id);

  ResourceId recBuf = kNone;
  uint32_t layers = 0;
  if (o.mode == Mode::Rtta) {
    const int32_t tw = o.atlasWidth ? o.atlasWidth : defaultAtlasSide(vp.w, o.params.border);
    const int32_t th = o.atlasHeight ? o.atlasHeight : defaultAtlasSide(vp.h, o.params.border);
    validateAtlas(tw, th, vp, o.params.border);
    f.atlas = atlasPackaging(f.records, tw, th);
    f.inexactTransforms = computeTransforms(f.records, f.atlas, vp);
    layers = std::max<uint32_t>({o.allocatedLayers, uint32_t(f.atlas.layers), 1u});
    if (layers > uint32_t(kMaxArrayLayers))
      throw Error(fmt::format("{} allocated atlas layers: at most {}", layers, kMaxArrayLayers));
    recBuf = recordBufferTexture(cl, encodeRecordBuffer(f.records));
  } else if (o.mode == Mode::Rtt) {
    if (visible.size() > size_t(kMaxArrayLayers))
      throw Error(fmt::format("RTT: {} visible objects need {} viewport-sized layers, at most {}", visible.size(),
                              visible.size(), kMaxArrayLayers));
    f.atlas = {vp.w, vp.h, int32_t(visible.size())};
    layers = std::max<uint32_t>(uint32_t(visible.size()), 1u);
    // Identity records: RTT renders each object where it is on screen.
    std::vector<Record> identity(nObj);
    for (size_t i = 0; i < nObj; ++i) identity[i].id = uint32_t(i), identity[i].layer = 0;
    recBuf = recordBufferTexture(cl, encodeRecordBuffer(identity));
  }
  f.allocatedLayers = layers;
  // --texturing tab: every output batch's arrays (with their samplers) and TAM, before the first draw.
  struct BatchRes {
    std::vector<ResourceId> arrays, samplers;
    ResourceId tam = kNone;
  };
  std::vector<BatchRes> batchRes;
  ResourceId tabProg = kNone;
  if (tab) {
    bool anyBatched = false;
    for (const batching::TabMesh& m : scene.tab.meshes) anyBatched = anyBatched || m.kind == batching::MeshKind::Batched;
    if (anyBatched && scene.tab.batches.empty())
      throw Error("--texturing tab: the scene has no output batches (run TAB's Algorithm 1 first)");
    tabProg = cl.createProgram("atlas_capture_tab");
    std::map<uint32_t, ResourceId> samplers;
    for (const batching::OutputBatch& b : scene.tab.batches) {
      BatchRes r;
      for (uint32_t a : b.arrays) {
        r.arrays.push_back(batching::recordTextureArray(cl, scene.tab, a));
        const batching::ArrayKey& k = scene.tab.arrays[a].key;
        auto [it, fresh] = samplers.emplace(uint32_t(k.wrapS) * 16 + uint32_t(k.wrapT), kNone);
        if (fresh) it->second = cl.createSampler(batching::tabSampler(k.wrapS, k.wrapT));
        r.samplers.push_back(it->second);
      }
      r.tam = batching::recordTam(cl, b, true);
      batchRes.push_back(std::move(r));
    }
  }
  if (o.mode != Mode::Std) {
    const uint32_t w = o.mode == Mode::Rtta ? uint32_t(f.atlas.width) : view.width;
    const uint32_t h = o.mode == Mode::Rtta ? uint32_t(f.atlas.height) : view.height;
    f.captureColor = target(cl, Format::RGBA8, w, h, layers, &f.targetBytes);
    f.captureDepth = target(cl, Format::RG32F, w, h, layers, &f.targetBytes);
    if (o.atlasInput) {
      const AtlasImages& in = *o.atlasInput;
      if (in.color.size() != layers || in.depth.size() != layers)
        throw Error(fmt::format("uploaded atlas: {} colour and {} depth layers, the frame's atlas has {}",
                                in.color.size(), in.depth.size(), layers));
      for (uint32_t l = 0; l < layers; ++l) {
        if (in.color[l].size() != size_t(w) * h * 4 || in.depth[l].size() != size_t(w) * h * 8)
          throw Error(fmt::format("uploaded atlas layer {}: {} colour and {} depth bytes, a {}x{} layer needs {} and {}",
                                  l, in.color[l].size(), in.depth[l].size(), w, h, size_t(w) * h * 4,
                                  size_t(w) * h * 8));
        cl.uploadTexture(f.captureColor, 0, l, in.color[l]);
        cl.uploadTexture(f.captureDepth, 0, l, in.depth[l]);
      }
    }
  }
  const ResourceId captureZ =
      o.mode == Mode::Std ? kNone
                          : target(cl, Format::D32F, o.mode == Mode::Rtta ? uint32_t(f.atlas.width) : view.width,
                                   o.mode == Mode::Rtta ? uint32_t(f.atlas.height) : view.height, layers, &f.targetBytes);

  cl.bindVertexBuffer(vb);
  cl.setVertexLayout(sceneLayout());
  DepthState depthOn;
  depthOn.test = true;

  if (o.mode == Mode::Std) {
    RenderTarget rt;
    rt.color[0] = f.screen;
    rt.depth = screenDepth;
    cl.setRenderTarget(rt);
    cl.setViewport(vp);
    cl.clearColor(0, view.clear);
    cl.clearDepth(1.0f);
    cl.setDepthState(depthOn);
    cl.useProgram(texturedProg);
    cl.setUniforms(0, mvp);
    const std::vector<float> texMatrixAndAlpha{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    cl.setUniforms(4, texMatrixAndAlpha);
    const std::vector<float> opaque{0, 0, 1, 0};  // bias 0, no alpha test, alpha forced to 1
    cl.setUniforms(8, opaque);
    for (const DrawRun& r : runs) {
      rec.bind(0, r.texture);
      rec.tint(r.factor);
      cl.draw(r.first, r.count);
    }
    return f;
  }

  // --- capture ---
  // RTTA: four clip planes on the undisplaced position keep every object inside its own region (§3.1).
  // RTT renders each object where it is on its own layer, with no neighbour to protect: no planes, so
  // a layer is exactly the object rendered alone.
  RasterState clip;
  clip.clipMask = o.mode == Mode::Rtta ? 0x0f : 0x00;
  cl.setRasterState(clip);
  cl.setDepthState(depthOn);
  cl.useProgram(captureProg);
  cl.setUniforms(0, mvp);
  cl.bindTexture(0, recBuf);
  auto clearCapture = [&] {
    cl.clearColor(0, kAtlasClear);
    cl.clearColor(1, kAtlasDepthClear);
    cl.clearDepth(1.0f);
  };
  if (o.mode == Mode::Rtta && o.atlasInput) {
    // The atlas was uploaded: no capture pass.
  } else if (o.mode == Mode::Rtta) {
    RenderTarget rt;
    rt.color[0] = f.captureColor;
    rt.color[1] = f.captureDepth;
    rt.depth = captureZ;
    rt.layer = kLayered;
    cl.setRenderTarget(rt);
    cl.setViewport({0, 0, f.atlas.width, f.atlas.height});
    clearCapture();
    if (tab) {
      // Algorithm 2 of TAB inside the capture: the record buffer on unit 9, so units 0-8 are a TAB draw's.
      cl.useProgram(tabProg);
      cl.setVertexLayout(sceneLayout(3));
      cl.setUniforms(0, mvp);
      const std::vector<float> materials{1, 0, 0, 0}, white{1, 1, 1, 1};
      cl.setUniforms(4, materials);
      cl.setUniforms(7, white);
      cl.bindTexture(9, recBuf);
      for (size_t b = 0; b < scene.tab.batches.size(); ++b) {
        const BatchRes& r = batchRes[b];
        cl.bindTexture(0, r.tam);
        for (size_t k = 0; k < r.arrays.size(); ++k) {
          cl.bindSampler(uint32_t(1 + k), r.samplers[k]);
          cl.bindTexture(uint32_t(1 + k), r.arrays[k]);
        }
        for (const batching::GeometryBatch& g : scene.tab.batches[b].geometry) cl.draw(g.firstVertex, g.vertexCount);
      }
      // The meshes TAB leaves unbatched (untextured, BLEND), as bind draws them.
      const std::vector<DrawRun> rest = drawRuns(scene.tab, true);
      if (!rest.empty()) {
        cl.useProgram(captureProg);
        cl.setVertexLayout(sceneLayout());
        cl.setUniforms(0, mvp);
        cl.bindTexture(0, recBuf);
        rec.resetBindings();
        for (const DrawRun& r : rest) {
          rec.bind(1, r.texture);
          rec.tint(r.factor);
          cl.draw(r.first, r.count);
        }
      }
    } else {
      for (const DrawRun& r : runs) {
        rec.bind(1, r.texture);
        rec.tint(r.factor);
        cl.draw(r.first, r.count);
      }
    }
  } else {
    cl.setViewport(vp);
    for (size_t layer = 0; layer < visible.size(); ++layer) {
      RenderTarget rt;
      rt.color[0] = f.captureColor;
      rt.color[1] = f.captureDepth;
      rt.depth = captureZ;
      rt.layer = uint32_t(layer);
      cl.setRenderTarget(rt);
      clearCapture();
      for (size_t m = 0; m < scene.tab.meshes.size(); ++m) {
        const batching::TabMesh& mesh = scene.tab.meshes[m];
        if (scene.meshObject[m] != visible[layer] || mesh.vertexCount == 0) continue;
        rec.bind(1, textureOf(mesh));
        rec.tint(mesh.factor);
        cl.draw(mesh.firstVertex, mesh.vertexCount);
      }
    }
  }
  if (o.captureOnly) return f;

  // --- composite ---
  std::vector<uint32_t> order = visible;
  std::vector<uint32_t> important = o.important;
  const bool ghosted = o.composite == Composite::Ghosted || o.composite == Composite::GhostedAo;
  if (ghosted && important.empty() && !visible.empty()) {
    uint32_t best = visible[0];
    for (uint32_t id : visible) {
      const PixelRect &a = f.records[id].inner, &b = f.records[best].inner;
      if (int64_t(a.width()) * a.height() > int64_t(b.width()) * b.height()) best = id;
    }
    important = {best};
  }
  for (uint32_t id : important)
    if (id >= nObj) throw Error(fmt::format("--important {}: there are only {} objects", id, nObj));
  f.important = important;
  auto isImportant = [&](uint32_t id) { return std::find(important.begin(), important.end(), id) != important.end(); };
  auto backToFront = [&](std::vector<uint32_t>& ids) {
    auto dist2 = [&](uint32_t id) {
      const glm::dvec3 c = (f.records[id].world.lo + f.records[id].world.hi) * 0.5 - view.eye;
      return c.x * c.x + c.y * c.y + c.z * c.z;
    };
    std::stable_sort(ids.begin(), ids.end(), [&](uint32_t a, uint32_t b) {
      const double da = dist2(a), db = dist2(b);
      return da != db ? da > db : a < b;
    });
  };

  std::vector<SpriteVertex> sprites;
  std::vector<std::pair<uint32_t, uint32_t>> spriteOf(nObj, {0, 0});  // first vertex, count
  for (size_t k = 0; k < visible.size(); ++k) {
    const Record& r = f.records[visible[k]];
    spriteOf[r.id] = {uint32_t(sprites.size()), 6};
    if (o.mode == Mode::Rtta)
      addSprite(sprites, r.viewport, vp, r.atlas.x0 - r.viewport.x0, r.atlas.y0 - r.viewport.y0, r.layer);
    else
      addSprite(sprites, r.viewport, vp, 0, 0, int32_t(k));
  }
  const ResourceId spriteVb = cl.createBuffer(BufferKind::Vertex, asBytes(sprites));
  RenderTarget screen;
  screen.color[0] = f.screen;
  screen.depth = screenDepth;
  cl.setRenderTarget(screen);
  cl.setViewport(vp);
  cl.setRasterState({});
  cl.clearColor(0, view.clear);
  cl.clearDepth(1.0f);
  cl.useProgram(spriteProg);
  cl.bindTexture(0, f.captureColor);
  cl.bindTexture(1, f.captureDepth);
  SamplerState nearest;
  nearest.minFilter = Filter::Nearest;
  nearest.magFilter = Filter::Nearest;
  const ResourceId nearestSampler = cl.createSampler(nearest);
  cl.bindSampler(0, nearestSampler);
  cl.bindSampler(1, nearestSampler);
  cl.bindVertexBuffer(spriteVb);
  VertexLayout sl;
  sl.stride = sizeof(SpriteVertex);
  sl.attribs[0] = {0, 4, AttribType::F32, 0};
  sl.attribs[2] = {2, 4, AttribType::F32, 16};
  cl.setVertexLayout(sl);
  rec.resetUniformCache();
  BlendState over;
  over.enabled = true;
  over.srcRgb = BlendFactor::SrcAlpha;
  over.dstRgb = BlendFactor::OneMinusSrcAlpha;
  over.srcAlpha = BlendFactor::One;
  over.dstAlpha = BlendFactor::OneMinusSrcAlpha;
  auto drawSprites = [&](const std::vector<uint32_t>& ids) {
    for (uint32_t id : ids) cl.draw(spriteOf[id].first, spriteOf[id].second);
  };
  if (o.composite == Composite::Depth) {
    cl.setDepthState(depthOn);
    rec.tint({1, 1, 1, 1});
    // One draw: the sprites are consecutive in id order.
    if (!sprites.empty()) cl.draw(0, uint32_t(sprites.size()));
  } else if (o.composite == Composite::Transparent) {
    cl.setBlendState(over);
    rec.tint({1, 1, 1, kTransparentAlpha});
    backToFront(order);
    drawSprites(order);
  } else {
    std::vector<uint32_t> front, rest;
    for (uint32_t id : visible) (isImportant(id) ? front : rest).push_back(id);
    cl.setDepthState(depthOn);
    if (ao) {
      // 3D: occlusion and edges on each important object's own region, then the ghosted rest.
      cl.useProgram(aoProg);
      cl.setUniforms(7, std::vector<float>{1, 1, 1, 1});
      cl.setUniforms(9, kEdgeColor);
      std::vector<float> factors(8, 0.0f);
      for (int k = 0; k <= 4; ++k) factors[size_t(k)] = 1.0f - float(k) / 8.0f;
      cl.setUniforms(10, factors);
      for (uint32_t id : front) {
        const auto [zlo, zhi] = windowDepthRange(f.records[id].world, view.mvp);
        const double span = zhi - zlo;
        cl.setUniforms(8, std::vector<float>{float(span * kAoBiasFraction), float(span * kAoEdgeFraction), 0, 0});
        cl.draw(spriteOf[id].first, spriteOf[id].second);
      }
      cl.useProgram(spriteProg);
      rec.resetUniformCache();
    } else {
      rec.tint(kHighlightTint);
      drawSprites(front);
    }
    cl.setDepthState({});
    cl.setBlendState(over);
    rec.tint({1, 1, 1, kGhostAlpha});
    backToFront(rest);
    drawSprites(rest);
  }
  return f;
}

}  // namespace tessera::rtta
