#include "raster/cpu_backend.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <type_traits>
#include <unordered_set>

#include "raster/depth_signature.h"
#include "raster/provenance.h"
#include "raster/tolerances.h"
#include "raster/rast.h"
#include "raster/setup.h"
#include "raster/storage_pool.h"
#include "raster/validate.h"

namespace tessera {

using namespace detail;

namespace detail {

void Scene::begin(const TargetView& t) {
  reset();
  target = t;
  tilesX = (t.width + kTileSize - 1) / kTileSize;
  tilesY = (t.height + kTileSize - 1) / kTileSize;
  bins.resize(size_t(tilesX) * size_t(tilesY));  // reset() emptied them; their capacity stays for reuse
  binSegment.assign(bins.size(), 0);
}

void Scene::reset(bool keepSegments) {
  states.clear();
  triangles = 0;
  for (auto& b : triBlocks) {
    b.clear();
    spareBlocks.push_back(std::move(b));
  }
  triBlocks.clear();
  blocks.clear();
  clears.clear();
  for (auto& b : bins) b.clear();
  if (!keepSegments) std::fill(binSegment.begin(), binSegment.end(), 0);
}


std::vector<TriSetup> Scene::takeSpareBlock() {
  if (spareBlocks.empty()) return {};
  std::vector<TriSetup> b = std::move(spareBlocks.back());
  spareBlocks.pop_back();
  return b;
}

void PipelineStats::add(const PipelineStats& o) {
  primitives_assembled += o.primitives_assembled;
  primitives_dropped_by_program += o.primitives_dropped_by_program;
  primitives_culled += o.primitives_culled;
  primitives_clipped += o.primitives_clipped;
  triangles_binned += o.triangles_binned;
  quads_shaded += o.quads_shaded;
  fragments_shaded += o.fragments_shaded;
  helper_invocations += o.helper_invocations;
  fragments_depth_failed += o.fragments_depth_failed;
  fragments_discarded += o.fragments_discarded;
  pixels_written += o.pixels_written;
  tiles_rasterized += o.tiles_rasterized;
}

}  // namespace detail

namespace {

Rect intersect(const Rect& a, const Rect& b) {
  const int32_t x0 = std::max(a.x, b.x), y0 = std::max(a.y, b.y);
  const int64_t x1 = std::min<int64_t>(int64_t(a.x) + a.w, int64_t(b.x) + b.w);
  const int64_t y1 = std::min<int64_t>(int64_t(a.y) + a.h, int64_t(b.y) + b.h);
  return Rect{x0, y0, int32_t(std::max<int64_t>(0, x1 - x0)), int32_t(std::max<int64_t>(0, y1 - y0))};
}

// Vertices shaded per parallel task; vertex shading has no cross-vertex state, so any split gives
// the same bytes.
constexpr size_t kVertexChunk = 1024;
// Triangles set up per parallel task.
constexpr size_t kSetupChunk = 256;
// A chunk's output is one block of Scene::triBlocks, addressed by the 16-bit TileCmd::slot: clipping
// turns one triangle into at most kMaxClipPolygon - 2.
static_assert(kSetupChunk * (kMaxClipPolygon - 2) <= 65536, "TileCmd::slot cannot address a chunk's block");

// An array that draws append to and setup empties, kept across frames and left uninitialised: every
// element setup reads, a draw has written first. (A std::vector zero-fills on growth, which for a
// setup-bound draw, 300k vertices and 80 MB of VertexIn + VertexOut, cost more than the whole
// pipeline.) Growing copies what is there; the element types are trivially copyable.
template <class T>
struct AppendArray {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_default_constructible_v<T>);
  std::unique_ptr<T[]> data;
  size_t size = 0, capacity = 0;
  // n more elements at the end (their address holds until the next append).
  T* append(size_t n) {
    if (size + n > capacity) {
      const size_t grown = std::max(size + n, capacity * 2);
      std::unique_ptr<T[]> next(new T[grown]);
      if (size > 0) std::memcpy(next.get(), data.get(), size * sizeof(T));
      data = std::move(next);
      capacity = grown;
    }
    T* p = data.get() + size;
    size += n;
    return p;
  }
  void clear() { size = 0; }
};

// Triangles whose setup waits for the next setupPending(). Small draws (a city block: 257 draws of
// about 80 triangles) then share one parallel setup instead of each running its one chunk on the
// calling thread; a draw that brings the total to this bound is set up at once, which bounds memory.
// Large draws go in slices of this size (draw(); kSingleThreadScene at one thread). 16384 keeps a
// slice's vertices (about 50k, 13 MB of VertexIn + VertexOut) within the last-level cache:
// tiny_tris_1m took 247 ms at 65536 and 233 ms at 16384, 8192 or 4096 (1 thread, one scene per
// frame); city_block did not change.
constexpr size_t kPendingTriangles = 16384;

// The set-up triangles a scene holds before it is rasterized, whatever comes next: a flush for memory.
// A TriSetup is 472 bytes, so a frame of ten million triangles binned whole would hold 4.7 GB of them.
// The bytes are those of one scene: every tile applies its commands in submission order, and this
// scene's commands all precede the next one's; the hierarchical Z and visibility runs start afresh per
// tile pass, and both are exact. tiles_rasterized counts bins per upload segment, which a flush for
// memory continues.
constexpr size_t kSceneTriangles = size_t(1) << 20;
// At one thread, slices and scenes of this size instead: what setup writes is still in the cache when
// the tiles read it (tiny_tris_1m 181 -> 166 ms, tiny_tris_100k 19.7 -> 18.6 ms). Not with more
// threads: a scene's recycled triangle blocks and vertices were then last written by the other core,
// and every cut cost about 3 ms of cache-line transfers there (tiny_tris_1m at 2 threads: 90 ms as one
// scene, 130-141 ms in scenes of 65536, up to 165 ms in scenes of 8192; docs/bench.md).
constexpr size_t kSingleThreadScene = 8192;
static_assert(kSingleThreadScene % kSetupChunk == 0 && kPendingTriangles % kSetupChunk == 0,
              "a slice boundary is a chunk boundary");

}  // namespace

struct CpuBackend::Impl {
  RenderOptions options;
  // Resources by id (one shared id space, as in the command list).
  std::vector<std::unique_ptr<TextureData>> textures;
  std::vector<std::unique_ptr<BufferData>> buffers;
  std::vector<SamplerState> samplers;
  std::vector<const Program*> programs;
  std::map<ResourceId, std::array<Vec4, kMaxUniformSlots>> uniforms;  // per program object (GL 4.6 §7.6)

  // Current state.
  std::array<ResourceId, kMaxTextureUnits> unitTexture{};
  std::array<ResourceId, kMaxTextureUnits> unitSampler{};
  ResourceId program = kNone, vertexBuffer = kNone, indexBuffer = kNone;
  IndexType indexType = IndexType::U16;
  VertexLayout layout;
  Rect viewport;
  ScissorState scissor;
  DepthState depth;
  BlendState blend;
  RasterState raster;
  RenderTarget target;
  bool targetBound = false;
  uint64_t drawSerial = 0;  // draws issued so far (provenance: DrawState::drawSerial)
  // Provenance: the depth epoch (raster/depth_signature.h), advanced by every clear, render-target
  // change and texture upload.
  uint32_t depthEpoch = 1;

  Scene scene;
  PipelineStats stats;
  std::vector<SetupSink> sinks;  // reused across draws
  // Draws not yet set up (setupPending): their parameters, indices and vertices, in order. Their
  // vertices are shaded together too (shadePending), so that the small draws of a frame share the
  // threads instead of each shading its one chunk on one of them.
  struct PendingDraw {
    SetupParams params;
    uint32_t triCount = 0;
    uint32_t firstTri = 0;    // the slice's first triangle within its draw (draw() slices large draws)
    bool dense = false;
    uint32_t lo = 0;          // dense: the lowest index, vertex i of the draw is at lo + i
    size_t idx = 0, vtx = 0;  // offsets into pendingIdx and pendingIn / pendingOut
    size_t shadeCount = 0;    // vertices to shade: lo .. lo + shadeCount - 1 (dense) or every index
    // What fetchGroup reads, as the draw saw it: the bound vertex buffer and layout may change before
    // the vertices are shaded; the buffer's bytes cannot (an upload flushes first).
    const BufferData* vertexBuffer = nullptr;
    VertexLayout layout;
    size_t firstChunk = 0;    // setupPending: the draw's first chunk among all pending chunks
    uint64_t segment = 0;     // Scene::segment when the draw was issued
  };
  std::vector<PendingDraw> pending;
  // The textures and buffers that the scene's and the pending draws' work reads after draw() returns:
  // every bound unit's texture (and a buffer texture's buffer) and the vertex buffer. An upload to
  // one of them, or to the render target, flushes first; any other upload cannot change what the
  // unexecuted work reads, so the scene grows on and a later draw may hide an earlier one's fragments
  // before they are shaded (rast.cpp's visibility runs). Index buffers are read inside draw().
  std::unordered_set<const void*> sceneReads;
  struct VertexChunk {
    size_t draw, begin, end;  // vertices [begin, end) of pending[draw]
  };
  std::vector<VertexChunk> vertexChunks;  // shadePending's tasks, reused
  size_t pendingTris = 0;
  AppendArray<uint32_t> pendingIdx;
  AppendArray<VertexIn> pendingIn;
  AppendArray<VertexOut> pendingOut;
  // Per vertex of pendingOut, its outcode and window position (window_simd.h), one array per member.
  struct PendingWindows {
    AppendArray<int64_t> x, y;
    AppendArray<double> invW;
    AppendArray<float> z;
    AppendArray<uint32_t> code;
    void append(size_t n) { x.append(n), y.append(n), invW.append(n), z.append(n), code.append(n); }
    void clear() { x.clear(), y.clear(), invW.clear(), z.clear(), code.clear(); }
    VertexWindows at(size_t i) { return {x.data.get() + i, y.data.get() + i, invW.data.get() + i, z.data.get() + i,
                                         code.data.get() + i}; }
  } pendingWin;
  // Texel and buffer storage of the previous frame (storage_pool.h); what this frame does not take is
  // released when it ends (CpuBackend::execute).
  StoragePool storage;
  tbb::enumerable_thread_specific<RastScratch> scratch;
  StageTimes times;
  uint64_t binTicks = 0;  // appendToScene runs on the calling thread
  uint64_t scenesRasterized = 0;  // StageTimes::scenes
  // The slice of a large draw and the scene's bound in set-up triangles, chosen per execute() by its
  // thread count (kSingleThreadScene).
  size_t sliceTriangles = kPendingTriangles, sceneBound = kSceneTriangles;
  // LOD probe: per (colour attachment 0, level), one map per layer.
  std::map<std::pair<const TextureData*, uint32_t>, std::vector<LodMap>> lodMaps;
  // The previous frame's LOD maps (about 42 MB at 640x480): reused like `storage`, released likewise.
  std::vector<std::vector<LodPixel>> spareLod;

  std::vector<LodPixel> takeLodPixels(size_t n) {
    size_t best = spareLod.size();
    for (size_t i = 0; i < spareLod.size(); ++i)
      if (spareLod[i].capacity() >= n && (best == spareLod.size() || spareLod[i].capacity() < spareLod[best].capacity())) best = i;
    if (best == spareLod.size()) return std::vector<LodPixel>(n);
    std::vector<LodPixel> v = std::move(spareLod[best]);
    spareLod[best] = std::move(spareLod.back());
    spareLod.pop_back();
    v.assign(n, LodPixel{});  // every pixel empty, as in a new map
    return v;
  }

  void resize(ResourceId id) {
    const size_t n = size_t(id) + 1;
    if (textures.size() < n) {
      textures.resize(n);
      buffers.resize(n);
      samplers.resize(n);
      programs.resize(n, nullptr);
    }
  }

  TargetView resolveTarget(const RenderTarget& t) {
    TargetView v;
    v.level = t.level;
    v.layer = t.layer;
    uint32_t layers = ~0u;
    auto take = [&](ResourceId id) -> TextureData* {
      if (id == kNone) return nullptr;
      TextureData* tex = textures[id].get();
      v.width = int32_t(levelWidth(tex->desc, t.level));
      v.height = int32_t(levelHeight(tex->desc, t.level));
      layers = std::min(layers, tex->desc.layers);
      return tex;
    };
    for (int a = 0; a < kMaxColorAttachments; ++a) v.color[size_t(a)] = take(t.color[size_t(a)]);
    v.depth = take(t.depth);
    v.layerCount = layers == ~0u ? 1 : layers;
    return v;
  }

  void flush(bool forMemory = false) {
    setupPending();
    if (scene.empty()) return;
    ++scenesRasterized;
    const size_t tiles = scene.bins.size();
    tbb::enumerable_thread_specific<PipelineStats> local;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles, 1), [&](const tbb::blocked_range<size_t>& r) {
      RastScratch& s = scratch.local();
      PipelineStats& st = local.local();
      for (size_t i = r.begin(); i != r.end(); ++i) rasterizeTile(scene, i, s, st);
    });
    // Integer sums: the total does not depend on how tiles were spread over threads.
    for (const PipelineStats& st : local) stats.add(st);
    scene.reset(forMemory);
    sceneReads.clear();
  }

  // The resources a draw's unexecuted work reads (flushIfRead).
  void noteReads(const DrawState& ds) {
    for (const TexUnit& u : ds.ctx.units)
      if (u.tex) {
        sceneReads.insert(u.tex);
        if (u.tex->buffer) sceneReads.insert(u.tex->buffer);
      }
    sceneReads.insert(buffers[vertexBuffer].get());
  }

  // Flushes when unexecuted work reads `resource` (a TextureData or BufferData; sceneReads).
  void flushIfRead(const void* resource) {
    bool read = sceneReads.count(resource) != 0;
    for (const TextureData* c : scene.target.color) read = read || c == resource;
    read = read || scene.target.depth == resource;
    if (read) flush();
  }

  void setTarget(const RenderTarget& t) {
    if (targetBound && t == target) return;
    flush();
    ++depthEpoch;
    target = t;
    targetBound = true;
    scene.begin(resolveTarget(t));
    scene.provenance = options.provenance;
    scene.timeStages = options.stageTimes;
    scene.lod = nullptr;
    if (options.lodProbe && !options.provenance && scene.target.color[0]) {
      const TextureData* c = scene.target.color[0];
      std::vector<LodMap>& maps = lodMaps[{c, t.level}];
      const int32_t w = scene.target.width, h = scene.target.height;
      if (maps.size() != c->desc.layers || maps[0].width != w || maps[0].height != h) {
        maps.resize(c->desc.layers);
        for (LodMap& m : maps) m = LodMap{w, h, takeLodPixels(size_t(w) * size_t(h))};
      }
      scene.lod = &maps;
    }
    scene.edgeMarginSub = tolerance::edgeMarginSub(options.otherSubpixelBits);
    scene.vertexSnapPx = tolerance::vertexSnapPx(options.otherSubpixelBits);
    if (options.provenance)
      for (TextureData* c : scene.target.color)
        if (c && !c->prov) c->prov = std::make_shared<Provenance>(*c);
  }

  Rect clampRect() const {
    Rect r = intersect(viewport, Rect{0, 0, scene.target.width, scene.target.height});
    if (scissor.enabled) r = intersect(r, scissor.rect);
    return r;
  }

  void clear(TileOp op, uint32_t attachment, const std::array<uint32_t, 4>& bits) {
    setupPending();  // the pending draws' triangles go into the bins before the clear
    Rect r{0, 0, scene.target.width, scene.target.height};
    if (scissor.enabled) r = intersect(r, scissor.rect);
    if (r.w == 0 || r.h == 0) return;
    const uint32_t index = uint32_t(scene.clears.size());
    ++depthEpoch;
    scene.clears.push_back({attachment, bits, r});
    // Bin into every tile the rectangle touches, in order with the triangles.
    for (int32_t ty = r.y >> kTileOrder; ty <= (r.y + r.h - 1) >> kTileOrder; ++ty)
      for (int32_t tx = r.x >> kTileOrder; tx <= (r.x + r.w - 1) >> kTileOrder; ++tx)
        scene.push(size_t(ty) * size_t(scene.tilesX) + size_t(tx), {op, 0, index}, scene.segment, stats);
  }

  std::unique_ptr<DrawState> snapshot() {
    auto ds = std::make_unique<DrawState>();
    ds->program = programs[program];
    ds->uniforms = uniforms[program];
    ds->ctx.uniforms = ds->uniforms.data();
    for (int u = 0; u < kMaxTextureUnits; ++u) {
      TexUnit& tu = ds->ctx.units[size_t(u)];
      const ResourceId tid = unitTexture[size_t(u)];
      tu.tex = tid != kNone ? textures[tid].get() : nullptr;
      const ResourceId sid = unitSampler[size_t(u)];
      // No sampler object bound: the texture's own sampling state, which is GL's default (the
      // command list has no texture parameters).
      tu.sampler = SamplerQ::from(sid != kNone ? samplers[sid] : SamplerState{});
    }
    ds->depth = depth;
    ds->blend = blend;
    ds->varyings = ds->program->varyingCount();
    ds->clampRect = clampRect();
    ds->colorOutputs = std::min(ds->program->colorOutputs(), kMaxColorAttachments);
    if (options.provenance) ds->depthSigBase = depthSigBase(*ds);
    ds->depthEpoch = depthEpoch;
    return ds;
  }

  // The draw-wide part of the depth-writer signature (raster/depth_signature.h): the program, its
  // uniforms, the texture bindings, the viewport, the raster state, the depth-test enable, the blend
  // enable, the target's level and the epoch. Left out, as GL 4.6 Appendix A Rule 2 allows: the
  // framebuffer contents, write masks and scissor ("required"), and the depth function and blend
  // parameters ("strongly suggested", a pin: docs/crosscheck.md DEPTH_NEAR_EQUAL).
  uint64_t depthSigBase(const DrawState& ds) const {
    uint64_t h = sigMix(0x6a09e667f3bcc908ull, depthEpoch);
    h = sigMix(h, reinterpret_cast<uintptr_t>(ds.program));
    h = sigMixFloats(h, ds.uniforms[0].data(), size_t(kMaxUniformSlots) * 4);
    for (int u = 0; u < kMaxTextureUnits; ++u) h = sigMix(sigMix(h, unitTexture[size_t(u)]), unitSampler[size_t(u)]);
    for (int32_t v : {viewport.x, viewport.y, viewport.w, viewport.h}) h = sigMix(h, uint32_t(v));
    h = sigMix(h, uint64_t(raster.cull) | uint64_t(raster.frontCcw) << 8 | uint64_t(raster.clipMask) << 16);
    h = sigMix(h, uint64_t(ds.depth.test) | uint64_t(ds.blend.enabled) << 1);
    return sigMix(h, uint64_t(target.level) << 32 | target.layer);
  }

  // The signature of one primitive of the draw: the base, the position inputs of its vertices
  // (attribute 0) and their post-vertex-stage positions and clip distances, bitwise, and its layer.
  static uint64_t depthSig(const DrawState& ds, const VertexIn* (&in)[3], const VertexOut* const (&v)[3],
                           uint32_t layer) {
    if (ds.program->hasGeometryStage()) return 0;
    uint64_t h = ds.depthSigBase;
    for (int k = 0; k < 3; ++k) {
      h = sigMixFloats(h, in[k]->attr[0].data(), 4);
      h = sigMixFloats(h, v[k]->pos.data(), 4);
      h = sigMixFloats(h, v[k]->clip, kMaxClipDistances);
    }
    return sigFinish(sigMix(h, layer));
  }

  // Fetches the n vertices of a group whose indices are in in[i].vertexId (GL 4.6 §10.3: components
  // the layout leaves out read as (0, 0, 0, 1)). Attribute by attribute, each over the whole group
  // with its component count and type fixed: vertex by vertex, the branches on both were mispredicted
  // where a layout's attributes differ in them (a third of a setup-bound frame's vertex stage).
  // Attributes in the layout's order, so where two name one location the later one is what a vertex
  // keeps.
  // GL's value of an attribute the layout does not supply, (0, 0, 0, 1), in every attribute of in[0, n).
  static void fillDefaults(VertexIn* in, size_t n) {
    for (size_t i = 0; i < n; ++i)
      for (Vec4& v : in[i].attr) v = {0.0f, 0.0f, 0.0f, 1.0f};
  }

  // The layout's attributes of in[0, n) (vertexId set) at the locations in `locations` (a bit per
  // location), over GL's defaults that fillDefaults wrote: a location gets the same components from
  // every vertex, so what stays default stays default.
  static void fetchGroup(const BufferData& vb, const VertexLayout& layout, uint32_t locations, VertexIn* in,
                         size_t n) {
    for (const VertexAttrib& at : layout.attribs) {
      if (at.components == 0 || at.location >= kMaxAttribs || !(locations >> at.location & 1)) continue;
      const uint8_t* const src = vb.bytes.data() + at.offset;
      const bool u32 = at.type != AttribType::F32;
      switch (at.components) {
        case 1: u32 ? fetchAttrib<1, true>(src, layout.stride, at.location, in, n)
                    : fetchAttrib<1, false>(src, layout.stride, at.location, in, n); break;
        case 2: u32 ? fetchAttrib<2, true>(src, layout.stride, at.location, in, n)
                    : fetchAttrib<2, false>(src, layout.stride, at.location, in, n); break;
        case 3: u32 ? fetchAttrib<3, true>(src, layout.stride, at.location, in, n)
                    : fetchAttrib<3, false>(src, layout.stride, at.location, in, n); break;
        default: u32 ? fetchAttrib<4, true>(src, layout.stride, at.location, in, n)
                     : fetchAttrib<4, false>(src, layout.stride, at.location, in, n); break;
      }
    }
  }

  template <int components, bool u32>
  static void fetchAttrib(const uint8_t* src, uint64_t stride, uint8_t location, VertexIn* in, size_t n) {
    for (size_t i = 0; i < n; ++i) {
      const uint8_t* const s = src + uint64_t(in[i].vertexId) * stride;
      Vec4& v = in[i].attr[location];
      for (int k = 0; k < components; ++k) {
        if constexpr (u32) {
          uint32_t u;
          std::memcpy(&u, s + 4 * k, 4);
          v[size_t(k)] = float(u);  // exact: validation keeps U32 attributes below 2^24
        } else {
          std::memcpy(&v[size_t(k)], s + 4 * k, 4);
        }
      }
    }
  }

  // The n vertex indices from firstIndex on (validation has checked that they are in the buffer), in
  // one pass per type: this runs on the calling thread, before the parallel stages, and a buffer
  // lookup and type test per index were 1.5 % of a setup-bound frame.
  void readIndices(bool indexed, uint32_t firstIndex, uint32_t n, uint32_t* idx) const {
    if (!indexed) {
      for (uint32_t i = 0; i < n; ++i) idx[i] = firstIndex + i;
      return;
    }
    const uint8_t* const src = buffers[indexBuffer]->bytes.data();
    if (indexType == IndexType::U16) {
      for (uint32_t i = 0; i < n; ++i) {
        uint16_t v;
        std::memcpy(&v, src + (size_t(firstIndex) + i) * 2, 2);
        idx[i] = v;
      }
      return;
    }
    std::memcpy(idx, src + size_t(firstIndex) * 4, size_t(n) * 4);
  }

  void draw(const Draw& d) {
    const uint32_t triCount = d.count / 3;
    if (triCount == 0) return;
    uint32_t stateIndex = uint32_t(scene.states.size());
    scene.states.push_back(snapshot());
    scene.states.back()->drawSerial = drawSerial++;
    noteReads(*scene.states.back());
    const int varyings = scene.states.back()->varyings;  // the state moves if the scene is flushed

    const bool timing = scene.timeStages;
    // A large draw goes through in slices of at most sliceTriangles triangles, each with its own
    // vertices, so that what setup reads was shaded moments before (a one-million-triangle draw shaded
    // whole wrote 800 MB of vertices before setup read them back). A vertex two slices share is shaded
    // in both, with the same result: the vertex stage is a pure function of the index. Slices start at
    // multiples of kSetupChunk, so setup's chunks are the ones the whole draw would have.
    for (uint32_t firstTri = 0; firstTri < triCount; firstTri += uint32_t(sliceTriangles)) {
      const uint32_t sliceTris = std::min<uint32_t>(triCount - firstTri, uint32_t(sliceTriangles));
      // Vertex indices of the slice, then the distinct vertices to shade. Shading every index of the
      // slice's range keeps the vertex stage a pure function of the index.
      const uint32_t n = sliceTris * 3;
      const uint32_t firstIndex = d.first + 3 * firstTri;
      PendingDraw pd;
      pd.triCount = sliceTris;
      pd.firstTri = firstTri;
      pd.idx = pendingIdx.size;
      uint32_t* const idx = pendingIdx.append(n);
      readIndices(d.indexed, firstIndex, n, idx);
      uint32_t lo = idx[0], hi = idx[0];
      for (uint32_t i = 0; i < n; ++i) lo = std::min(lo, idx[i]), hi = std::max(hi, idx[i]);
      const bool dense = uint64_t(hi - lo) + 1 <= uint64_t(n) * 2;
      const size_t shadeCount = dense ? size_t(hi - lo) + 1 : size_t(n);
      pd.dense = dense, pd.lo = lo, pd.vtx = pendingIn.size, pd.shadeCount = shadeCount;
      pd.vertexBuffer = buffers[vertexBuffer].get();
      pd.layout = layout;
      pd.segment = scene.segment;
      // Filled by shadePending: the id, then fillDefaults and fetchGroup set every attribute; `out` is
      // zeroed per group.
      pendingIn.append(shadeCount);
      pendingOut.append(shadeCount);
      pendingWin.append(shadeCount);

      SetupParams& params = pd.params;
      params.viewport = viewport;
      params.clampRect = clampRect();
      params.raster = raster;
      params.stateIndex = stateIndex;
      params.varyings = varyings;
      params.provenance = options.provenance;
      params.timeStages = timing;
      pending.push_back(pd);
      pendingTris += sliceTris;
      // A bound below a slice (RenderOptions::sceneTriangles, for tests) also sets up sooner.
      if (pendingTris >= std::min(sliceTriangles, sceneBound)) setupPending();
      if (scene.triangles >= sceneBound) {
        // The draw's remaining slices go into the next scene, with a copy of its state.
        const bool more = firstTri + sliceTris < triCount;
        std::unique_ptr<DrawState> state;
        if (more) {
          state = std::make_unique<DrawState>(*scene.states[stateIndex]);
          state->ctx.uniforms = state->uniforms.data();
        }
        flush(true);
        if (more) {
          stateIndex = uint32_t(scene.states.size());
          scene.states.push_back(std::move(state));
          noteReads(*scene.states.back());
        }
      }
    }
  }

  // Shades the vertices of every pending draw (setupPending, first), all in one parallel loop over
  // chunks of at most kVertexChunk vertices of one draw. Vertex shading has no cross-vertex state and
  // each draw's program reads its own snapshot, so when and in which task a vertex is shaded does not
  // change a byte.
  void shadePending() {
    vertexChunks.clear();
    for (size_t d = 0; d < pending.size(); ++d)
      for (size_t b = 0; b < pending[d].shadeCount; b += kVertexChunk)
        vertexChunks.push_back({d, b, std::min(pending[d].shadeCount, b + kVertexChunk)});
    const bool timing = scene.timeStages;
    // Provenance mode's depth signatures (setupPending) read the triangles' VertexIns.
    const bool keepInputs = options.provenance;
    // What setup needs of each vertex's position (window_simd.h), once per vertex instead of once per
    // triangle that uses it, and in vector lanes.
    const WindowVerticesFn windowVertices = windowVerticesKernel();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, vertexChunks.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
      const uint64_t t0 = timing ? stageClock() : 0;
      for (size_t c = r.begin(); c != r.end(); ++c) {
        const VertexChunk& vc = vertexChunks[c];
        const PendingDraw& p = pending[vc.draw];
        const DrawState& ds = *scene.states[p.params.stateIndex];
        const uint32_t* const idx = pendingIdx.data.get() + p.idx;
        VertexIn* const in = pendingIn.data.get() + p.vtx + vc.begin;
        VertexOut* const out = pendingOut.data.get() + p.vtx + vc.begin;
        const VertexWindows win = pendingWin.at(p.vtx + vc.begin);
        const size_t n = vc.end - vc.begin;
        // In groups of kGroup vertices: fetch, clear the outputs (one fill per group: a fill per
        // 128-byte VertexOut compiled to a `rep stos` each, whose start-up cost made it over half of
        // the vertex stage of city_block), shade. Unless provenance mode reads them later, the inputs
        // go through a group buffer that stays in L1 instead of the slice's array (6 MB of VertexIn
        // written and evicted per slice of a setup-bound draw). The same values are shaded either way.
        // The group buffer's defaults are written once per chunk: one layout fills the same
        // components of it for every group, and the rest keep GL's defaults (each vertex's 128 bytes of
        // defaults were a sixth of a setup-bound frame's vertex stage).
        constexpr size_t kGroup = 64;
        VertexIn group[kGroup];
        // Only the locations the program reads (Program::attributesRead): fetching the two attributes
        // flat_color never reads was a fifth of a setup-bound frame's vertex stage (callgrind: 340 -> 272
        // instructions per triangle). Provenance mode's depth signature (depthSig) also reads location 0.
        const uint32_t locations = ds.program->attributesRead() | (keepInputs ? 1u : 0u);
        if (!keepInputs) fillDefaults(group, std::min(kGroup, n));
        for (size_t g = 0; g < n; g += kGroup) {
          const size_t m = std::min(kGroup, n - g);
          VertexIn* const gin = keepInputs ? in + g : group;
          if (keepInputs) fillDefaults(gin, m);
          for (size_t i = 0; i < m; ++i)
            gin[i].vertexId = p.dense ? p.lo + uint32_t(vc.begin + g + i) : idx[vc.begin + g + i];
          fetchGroup(*p.vertexBuffer, p.layout, locations, gin, m);
          std::memset(static_cast<void*>(out + g), 0, m * sizeof(VertexOut));
          ds.program->shadeVertices(std::span<const VertexIn>(gin, m), std::span<VertexOut>(out + g, m), ds.ctx);
          windowVertices(out + g, m, p.params.viewport, p.params.raster.clipMask, win.at(g));
        }
      }
      if (timing) scratch.local().ticks.t[kStageVertex] += stageClock() - t0;
    });
  }

  void setupPending() {
    if (pending.empty()) return;
    shadePending();
    size_t chunks = 0;
    for (PendingDraw& p : pending) {
      p.firstChunk = chunks;
      chunks += (size_t(p.triCount) + kSetupChunk - 1) / kSetupChunk;
    }
    if (sinks.size() < chunks) sinks.resize(chunks);
    // A sink whose block went into the scene gets a spare one, with the capacity of an earlier flush
    // or frame, so a steady sequence of frames allocates no triangle storage (serial: the spares are
    // shared).
    for (size_t c = 0; c < chunks; ++c)
      if (sinks[c].tris.capacity() == 0) sinks[c].tris = scene.takeSpareBlock();
    const bool layered = target.layer == kLayered;
    const bool timing = scene.timeStages;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1), [&](const tbb::blocked_range<size_t>& r) {
      const uint64_t setup0 = timing ? stageClock() : 0;
      for (size_t c = r.begin(); c != r.end(); ++c) {
        // The draw of chunk c: the last one whose first chunk is <= c.
        const auto it = std::upper_bound(pending.begin(), pending.end(), c,
                                         [](size_t x, const PendingDraw& p) { return x < p.firstChunk; });
        const PendingDraw& p = *(it - 1);
        const SetupParams& params = p.params;
        const DrawState& ds = *scene.states[params.stateIndex];
        const uint32_t* const idx = pendingIdx.data.get() + p.idx;
        const VertexIn* const in = pendingIn.data.get() + p.vtx;
        const VertexOut* const out = pendingOut.data.get() + p.vtx;
        const VertexWindows win = pendingWin.at(p.vtx);
        SetupSink& sink = sinks[c];
        sink.clear();
        sink.segment = p.segment;
        sink.tilesX = scene.tilesX;
        const bool geometryStage = ds.program->hasGeometryStage();  // once per chunk, not per triangle
        const uint32_t t0 = uint32_t((c - p.firstChunk) * kSetupChunk);
        const uint32_t t1 = std::min<uint32_t>(p.triCount, t0 + uint32_t(kSetupChunk));
        for (uint32_t t = t0; t < t1; ++t) {
          // The vertices in place; a program with a geometry stage changes its own copies.
          size_t vs[3];  // the vertices' places in the slice's arrays
          for (int k = 0; k < 3; ++k) vs[k] = p.dense ? idx[3 * t + uint32_t(k)] - p.lo : 3 * t + uint32_t(k);
          const VertexOut* vp[3] = {&out[vs[0]], &out[vs[1]], &out[vs[2]]};
          uint32_t layer = 0;
          const uint32_t primitiveId = p.firstTri + t;  // gl_PrimitiveID: the triangle's place in its draw
          VertexOut v[3];
          // A geometry stage's copies get records of their own (elements 0 to 2).
          int64_t gx[3], gy[3];
          double gInvW[3];
          float gz[3];
          uint32_t gcode[3];
          const VertexWindows gwin{gx, gy, gInvW, gz, gcode};
          if (geometryStage) {
            for (int k = 0; k < 3; ++k) v[k] = *vp[k], vp[k] = &v[k];
            if (!ds.program->shadeTriangle(v, primitiveId, layer, ds.ctx)) {
              ++sink.stats.primitives_assembled;
              ++sink.stats.primitives_dropped_by_program;
              continue;
            }
            // The program moved its copies: their records are made again.
            windowVerticesReference(v, 3, params.viewport, params.raster.clipMask, gwin);
          }
          if (layered) {
            // GL 4.6 §9.8: a layer outside the attachments gives undefined results; the oracle drops
            // the primitive (llvmpipe clamps), docs/spec-choices.md "Layered rendering".
            if (layer >= scene.target.layerCount) {
              ++sink.stats.primitives_assembled;
              ++sink.stats.primitives_dropped_by_program;
              continue;
            }
          } else {
            layer = target.layer;  // gl_Layer is ignored for a non-layered target
          }
          const size_t first = sink.tris.size();
          static constexpr size_t kCopies[3] = {0, 1, 2};
          setupTriangle(vp, geometryStage ? gwin : win, geometryStage ? kCopies : vs, primitiveId, layer, params, sink);
          if (params.provenance) {
            const VertexIn* vin[3] = {&in[vs[0]], &in[vs[1]], &in[vs[2]]};
            const uint64_t sig = depthSig(ds, vin, vp, layer);
            for (size_t i = first; i < sink.tris.size(); ++i) sink.tris[i].depthSig = sig;
          }
        }
      }
      if (timing) scratch.local().ticks.t[kStageSetup] += stageClock() - setup0;
    });
    const uint64_t bin0 = timing ? stageClock() : 0;
    for (size_t c = 0; c < chunks; ++c) appendToScene(sinks[c], scene, stats);
    if (timing) {
      binTicks += stageClock() - bin0;
      uint64_t clip = 0;
      for (size_t c = 0; c < chunks; ++c) clip += sinks[c].clipTicks;
      scratch.local().ticks.t[kStageClip] += clip;
    }
    pending.clear();
    pendingTris = 0;
    pendingIdx.clear(), pendingIn.clear(), pendingOut.clear(), pendingWin.clear();
  }

  // Takes over the capacity of an earlier frame's backend: the spare triangle blocks, the emptied
  // bins, the setup sinks and the per-draw vertex arrays. Only memory moves, no state: every one of
  // them is cleared or overwritten before it is read, so the frame renders as on a new backend.
  void adoptCapacity(Impl& old) {
    old.scene.reset();
    scene.spareBlocks = std::move(old.scene.spareBlocks);
    scene.bins = std::move(old.scene.bins);
    sinks = std::move(old.sinks);
    pendingIdx = std::move(old.pendingIdx);
    pendingIn = std::move(old.pendingIn);
    pendingOut = std::move(old.pendingOut);
    pendingWin = std::move(old.pendingWin);
    pendingIdx.clear(), pendingIn.clear(), pendingOut.clear(), pendingWin.clear();
    for (auto& t : old.textures)
      if (t)
        for (auto& level : t->levels) storage.give(std::move(level));
    for (auto& b : old.buffers)
      if (b) storage.give(std::move(b->bytes));
    for (auto& entry : old.lodMaps)
      for (LodMap& m : entry.second)
        if (m.pixels.capacity() > 0) spareLod.push_back(std::move(m.pixels));
  }

  bool executed = false;
  // Runs the list; resource commands are timed apart (StageTimes::resourcesMs), after the flush that
  // an upload forces, so the frame's time is the draws' and clears' whatever the list interleaves.
  void run(const CommandList& list) {
    using Clock = std::chrono::steady_clock;
    Clock::duration resources{};
    for (const Command& cmd : list.commands()) {
      const bool resource = std::holds_alternative<CreateTexture>(cmd) || std::holds_alternative<UploadTexture>(cmd) ||
                            std::holds_alternative<CreateBuffer>(cmd) || std::holds_alternative<UploadBuffer>(cmd) ||
                            std::holds_alternative<CreateSampler>(cmd) || std::holds_alternative<CreateProgram>(cmd);
      if (!resource) {
        std::visit([&](const auto& c) { apply(list, c); }, cmd);
        continue;
      }
      // A flush an upload needs is not resource time.
      if (const auto* u = std::get_if<UploadTexture>(&cmd)) flushIfRead(textures[u->id].get());
      if (const auto* u = std::get_if<UploadBuffer>(&cmd)) flushIfRead(buffers[u->id].get());
      const Clock::time_point t0 = Clock::now();
      std::visit([&](const auto& c) { apply(list, c); }, cmd);
      resources += Clock::now() - t0;
    }
    flush();
    times.resourcesMs = std::chrono::duration<double, std::milli>(resources).count();
  }

  void apply(const CommandList&, const CreateTexture& c) {
    resize(c.id);
    textures[c.id] = std::make_unique<TextureData>(c.desc, &storage);
    if (c.desc.kind == TextureKind::Buffer) textures[c.id]->buffer = buffers[c.desc.buffer].get();
  }
  void apply(const CommandList& l, const UploadTexture& c) {
    TextureData& t = *textures[c.id];
    flushIfRead(&t);  // unexecuted draws may sample the old contents
    ++scene.segment;
    auto src = l.bytes(c.data);
    ++depthEpoch;
    const uint64_t bytes = levelBytes(t.desc, c.level);
    if (t.desc.compression != BcFormat::None) {
      // S3TC blocks: decoded once here by the documented rule (bc_decode.h, spec-choices C1-C4); sampling
      // then reads RGBA8 like any other texture.
      const uint32_t w = levelWidth(t.desc, c.level), h = levelHeight(t.desc, c.level);
      // Straight into the level: a temporary level-sized buffer was a fresh zeroed mapping per upload
      // under ASan (CONTRIBUTING.md, "CI").
      uint8_t* const texels = t.levels[c.level].data() + bytes * c.layer;
      decodeBcLevelInto(t.desc.compression, w, h, src, std::span<uint8_t>(texels, size_t(bytes)));
      if (options.provenance) {
        // GL may round each interpolant to either integer around the extension's exact value, which is
        // within one unit of the oracle's nearest (docs/crosscheck.md, BC_INTERPOLANT): those channels get
        // [v - 1, v + 1] in the interval images, read by lookups like a rendered texture's.
        if (!t.prov) t.prov = std::make_shared<Provenance>(t);
        const std::vector<uint8_t> mask = bcInterpolantChannels(t.desc.compression, w, h, src);
        uint8_t* lo = t.prov->lo->levels[c.level].data() + bytes * c.layer;
        uint8_t* hi = t.prov->hi->levels[c.level].data() + bytes * c.layer;
        for (size_t i = 0; i < mask.size(); ++i)
          for (int ch = 0; ch < 4; ++ch) {
            const uint8_t v = texels[4 * i + size_t(ch)];
            const bool free = (mask[i] >> ch) & 1;
            lo[4 * i + size_t(ch)] = free && v > 0 ? uint8_t(v - 1) : v;
            hi[4 * i + size_t(ch)] = free && v < 255 ? uint8_t(v + 1) : v;
          }
      }
      return;
    }
    t.prov.reset();  // uploaded texels are exact: no interval any more
    std::memcpy(t.levels[c.level].data() + bytes * c.layer, src.data(), src.size());
  }
  void apply(const CommandList&, const CreateBuffer& c) {
    resize(c.id);
    buffers[c.id] = std::make_unique<BufferData>();
    buffers[c.id]->kind = c.kind;
    buffers[c.id]->bytes = storage.take(size_t(c.size));
  }
  void apply(const CommandList& l, const UploadBuffer& c) {
    flushIfRead(buffers[c.id].get());
    ++scene.segment;
    auto src = l.bytes(c.data);
    std::memcpy(buffers[c.id]->bytes.data() + c.offset, src.data(), src.size());
  }
  void apply(const CommandList&, const CreateSampler& c) {
    resize(c.id);
    samplers[c.id] = c.state;
  }
  void apply(const CommandList&, const CreateProgram& c) {
    resize(c.id);
    programs[c.id] = findProgram(c.name);
    uniforms[c.id] = {};
  }
  void apply(const CommandList&, const BindTexture& c) { unitTexture[c.unit] = c.texture; }
  void apply(const CommandList&, const BindSampler& c) { unitSampler[c.unit] = c.sampler; }
  void apply(const CommandList&, const UseProgram& c) { program = c.program; }
  void apply(const CommandList& l, const SetUniforms& c) {
    auto src = l.bytes(c.data);
    std::memcpy(uniforms[program].data() + c.slot, src.data(), src.size());
  }
  void apply(const CommandList&, const BindVertexBuffer& c) { vertexBuffer = c.buffer; }
  void apply(const CommandList&, const SetVertexLayout& c) { layout = c.layout; }
  void apply(const CommandList&, const BindIndexBuffer& c) { indexBuffer = c.buffer, indexType = c.type; }
  void apply(const CommandList&, const SetViewport& c) { viewport = c.rect; }
  void apply(const CommandList&, const SetScissor& c) { scissor = c.state; }
  void apply(const CommandList&, const SetDepthState& c) { depth = c.state; }
  void apply(const CommandList&, const SetBlendState& c) { blend = c.state; }
  void apply(const CommandList&, const SetRasterState& c) { raster = c.state; }
  void apply(const CommandList&, const SetRenderTarget& c) { setTarget(c.target); }
  void apply(const CommandList&, const ClearColor& c) { clear(TileOp::ClearColor, c.attachment, c.bits); }
  void apply(const CommandList&, const ClearDepth& c) {
    // glClear honours the depth write mask (GL 4.6 §17.4.3), whether or not the depth test is on.
    if (!depth.write) return;
    std::array<uint32_t, 4> bits{};
    std::memcpy(bits.data(), &c.depth, 4);
    clear(TileOp::ClearDepth, 0, bits);
  }
  void apply(const CommandList&, const Draw& d) { draw(d); }
  void apply(const CommandList&, const Marker&) {}
};

CpuBackend::CpuBackend(RenderOptions options) : impl_(std::make_unique<Impl>()) { impl_->options = options; }
CpuBackend::~CpuBackend() = default;

void CpuBackend::execute(const CommandList& list, std::string_view frameName) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  validateOrThrow(list, frameName, impl_->options.limits);
  const Clock::time_point validated = Clock::now();
  // A list is a whole frame that starts from GL's initial state (command_list.h): nothing of an earlier
  // execute() may leak into it, so a backend reused for a sequence of frames starts afresh each time.
  if (impl_->executed) {
    auto next = std::make_unique<Impl>();
    next->options = impl_->options;
    next->adoptCapacity(*impl_);  // memory only: a sequence of frames does not pay first-touch pages again
    impl_ = std::move(next);
  }
  impl_->executed = true;
  const int threads = impl_->options.threads > 0 ? impl_->options.threads : tbb::this_task_arena::max_concurrency();
  impl_->sliceTriangles = threads == 1 ? kSingleThreadScene : kPendingTriangles;
  impl_->sceneBound = impl_->options.sceneTriangles ? impl_->options.sceneTriangles
                      : threads == 1                ? kSingleThreadScene
                                                    : kSceneTriangles;
  // oneTBB caps its workers at the machine's concurrency unless a global_control allows more: an arena
  // of 7 on 2 cores then runs on 2 threads and warns. Tests ask for more threads than cores on purpose
  // (tiles spread over threads that preempt each other), so raise the cap for this frame.
  std::optional<tbb::global_control> allowThreads;
  if (threads > tbb::info::default_concurrency())
    allowThreads.emplace(tbb::global_control::max_allowed_parallelism, size_t(threads));
  tbb::task_arena arena(threads);
  const uint64_t tick0 = stageClock();
  arena.execute([&] { impl_->run(list); });
  impl_->storage.release();  // the previous frame's storage that this one did not reuse
  std::vector<std::vector<LodPixel>>().swap(impl_->spareLod);
  const uint64_t ticks = stageClock() - tick0;
  const Clock::time_point end = Clock::now();
  StageTimes& st = impl_->times;
  st.validateMs = std::chrono::duration<double, std::milli>(validated - start).count();
  const double runMs = std::chrono::duration<double, std::milli>(end - validated).count();
  st.frameMs = std::max(0.0, runMs - st.resourcesMs);
  st.perStage = impl_->options.stageTimes;
  st.hizBlocksSkipped = st.hizFragmentsSkipped = st.provPlansSkipped = st.provGridsShared = 0;
  st.scenes = impl_->scenesRasterized;
  for (const RastScratch& s : impl_->scratch) {
    st.hizBlocksSkipped += s.hizBlocksSkipped;
    st.hizFragmentsSkipped += s.hizFragmentsSkipped;
    st.provPlansSkipped += s.provPlansSkipped;
    st.provGridsShared += s.provGridsShared;
  }
  if (st.perStage) {
    // Ticks to milliseconds with the run's own wall time as the reference clock.
    const double msPerTick = ticks > 0 ? runMs / double(ticks) : 0.0;
    StageTicks sum;
    for (const RastScratch& s : impl_->scratch)
      for (int k = 0; k < kStageCount; ++k) sum.t[k] += s.ticks.t[k];
    const auto ms = [&](uint64_t t) { return double(t) * msPerTick; };
    st.vertexMs = ms(sum.t[kStageVertex]);
    st.clipMs = ms(sum.t[kStageClip]);
    st.setupMs = ms(sum.t[kStageSetup] - std::min(sum.t[kStageSetup], sum.t[kStageClip]));
    st.binMs = ms(impl_->binTicks);
    const uint64_t inTile = sum.t[kStageShade] + sum.t[kStageFragops];
    st.rastMs = ms(sum.t[kStageTile] - std::min(sum.t[kStageTile], inTile));
    st.shadeMs = ms(sum.t[kStageShade] - std::min(sum.t[kStageShade], sum.t[kStageSample]));
    st.sampleMs = ms(sum.t[kStageSample]);
    st.fragopsMs = ms(sum.t[kStageFragops]);
  }
}

const TextureData* CpuBackend::texture(ResourceId id) const {
  return id < impl_->textures.size() ? impl_->textures[id].get() : nullptr;
}

std::vector<PresentedImage> CpuBackend::presented() const {
  std::vector<PresentedImage> out;
  if (!impl_->targetBound) return out;
  const RenderTarget& t = impl_->target;
  for (uint32_t a = 0; a < kMaxColorAttachments; ++a) {
    const ResourceId id = t.color[a];
    if (id == kNone) continue;
    const TextureData& tex = *impl_->textures[id];
    if (t.layer == kLayered) {
      for (uint32_t l = 0; l < tex.desc.layers; ++l) out.push_back({id, a, t.level, l});
    } else {
      out.push_back({id, a, t.level, t.layer});
    }
  }
  return out;
}

const PipelineStats& CpuBackend::stats() const { return impl_->stats; }
const StageTimes& CpuBackend::stageTimes() const { return impl_->times; }

const RenderOptions& CpuBackend::options() const { return impl_->options; }

const LodMap* CpuBackend::lodMap(const PresentedImage& p) const {
  if (p.texture >= impl_->textures.size() || !impl_->textures[p.texture]) return nullptr;
  const auto it = impl_->lodMaps.find({impl_->textures[p.texture].get(), p.level});
  if (it == impl_->lodMaps.end() || p.layer >= it->second.size()) return nullptr;
  return &it->second[p.layer];
}

}  // namespace tessera
