#include "raster/rast.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "raster/fragops.h"
#include "raster/provenance.h"
#include "raster/sample.h"
#include "raster/tolerances.h"

namespace tessera::detail {
namespace {


// Encodes a clear value as one texel of format f.
void encodeClear(Format f, const std::array<uint32_t, 4>& bits, uint8_t out[16]) {
  float v[4];
  std::memcpy(v, bits.data(), sizeof v);
  switch (f) {
    case Format::RGBA8:
      for (int k = 0; k < 4; ++k) out[k] = toUnorm8(v[k]);
      break;
    case Format::R8: out[0] = toUnorm8(v[0]); break;
    case Format::RG32F: std::memcpy(out, v, 8); break;
    case Format::RGBA32F: std::memcpy(out, v, 16); break;
    case Format::R32UI: std::memcpy(out, bits.data(), 4); break;
    case Format::D32F: {
      // glClearDepth clamps to [0, 1] (GL 4.6 §17.4.3); NaN clears to 0.
      float z = v[0] > 0.0f ? (v[0] < 1.0f ? v[0] : 1.0f) : 0.0f;
      std::memcpy(out, &z, 4);
      break;
    }
    default: break;
  }
}

void runClear(const Scene& scene, const ClearCmd& c, TextureData* tex, const TileRect& tile) {
  if (!tex) return;
  const int32_t x0 = std::max(tile.x0, c.rect.x), x1 = std::min(tile.x1, c.rect.x + c.rect.w - 1);
  const int32_t y0 = std::max(tile.y0, c.rect.y), y1 = std::min(tile.y1, c.rect.y + c.rect.h - 1);
  if (x0 > x1 || y0 > y1) return;
  uint8_t value[16] = {};
  encodeClear(tex->desc.format, c.bits, value);
  // Provenance: a clear is exact, except that GL may convert a unorm clear colour in float32, where
  // c * 255 can round onto a .5 tie (0.9f * 255 = 229.5 in float, 229.4999... exactly): then either
  // neighbour is legal (OUTPUT_ROUNDING). Two candidates, never the range between (there is none
  // for one byte: the neighbours are adjacent).
  uint8_t clo[16], chi[16];
  std::memcpy(clo, value, 16);
  std::memcpy(chi, value, 16);
  uint16_t ccls = 0;
  if (tex->prov && isUnorm(tex->desc.format)) {
    float v[4];
    std::memcpy(v, c.bits.data(), sizeof v);
    for (int k = 0; k < channelCount(tex->desc.format); ++k) {
      const double x = (v[k] > 0.0f ? (v[k] < 1.0f ? double(v[k]) : 1.0) : 0.0) * 255.0;
      const double tol = x * tolerance::kClearRel;  // one float32 rounding of c * 255
      const int lo = std::max(0, int(std::ceil(x - tol - 0.5))), hi = std::min(255, int(std::floor(x + tol + 0.5)));
      if (lo != value[k] || hi != value[k]) ccls = kOutputRounding;
      clo[k] = uint8_t(std::min<int>(lo, value[k])), chi[k] = uint8_t(std::max<int>(hi, value[k]));
    }
  }
  const uint32_t bpp = texelBytes(tex->desc.format);
  // One row of the tile's span, built once: a row is then a single copy instead of a library call
  // per texel (the copy size bpp is not a compile-time constant).
  const size_t rowBytes = size_t(x1 - x0 + 1) * bpp;
  uint8_t span[size_t(kTileSize) * 16];
  for (size_t o = 0; o < rowBytes; o += bpp) std::memcpy(span + o, value, bpp);
  const TargetView& t = scene.target;
  const uint32_t l0 = t.layer == kLayered ? 0 : t.layer, l1 = t.layer == kLayered ? t.layerCount : t.layer + 1;
  for (uint32_t layer = l0; layer < l1; ++layer)
    for (int32_t y = y0; y <= y1; ++y) {
      std::memcpy(tex->texel(t.level, layer, uint32_t(x0), uint32_t(y)), span, rowBytes);
      if (tex->prov) {
        Provenance& pv = *tex->prov;
        for (int32_t x = x0; x <= x1; ++x) {
          std::memcpy(pv.lo->texel(t.level, layer, uint32_t(x), uint32_t(y)), clo, bpp);
          std::memcpy(pv.hi->texel(t.level, layer, uint32_t(x), uint32_t(y)), chi, bpp);
          const size_t idx = pv.index(*tex, t.level, layer, uint32_t(x), uint32_t(y));
          pv.classes[t.level][idx] = ccls;
          pv.flags[t.level][idx] = 0;
          pv.candidates[t.level][idx].clear();
        }
      }
    }
}

// The LOD probe: a colour clear of attachment 0 leaves no lookup behind in the pixels it covers.
void clearLod(const Scene& scene, const ClearCmd& c, const TileRect& tile) {
  const uint32_t l0 = scene.target.layer == kLayered ? 0 : scene.target.layer;
  const uint32_t l1 = scene.target.layer == kLayered ? uint32_t(scene.lod->size()) : l0 + 1;
  const int32_t x0 = std::max(tile.x0, c.rect.x), x1 = std::min(tile.x1, c.rect.x + c.rect.w - 1);
  const int32_t y0 = std::max(tile.y0, c.rect.y), y1 = std::min(tile.y1, c.rect.y + c.rect.h - 1);
  for (uint32_t l = l0; l < l1 && l < scene.lod->size(); ++l)
    for (int32_t y = y0; y <= y1; ++y)
      for (int32_t x = x0; x <= x1; ++x) (*scene.lod)[l].at(x, y) = LodPixel{};
}

class TriangleRasterizer {
 public:
  TriangleRasterizer(const Scene& scene, const TriSetup& t, RastScratch& s, PipelineStats& stats)
      : scene_(scene), t_(t), ds_(*scene.states[t.drawState]), s_(s), stats_(stats),
        lateDepth_(ds_.program->writesDepth()), unorm8Quad_(s.unorm8Quad) {
    beginPlanCache();  // a new triangle: no lambda or plan of another one is reused (sample.h)
    const TargetView& tv = scene.target;
    depth_ = Plane::of(tv.depth, tv.level, t.layer);
    // Only the attachments the program writes are ever addressed (flush() loops to colorOutputs).
    for (int a = 0; a < ds_.colorOutputs; ++a) color_[a] = Plane::of(tv.color[size_t(a)], tv.level, t.layer);
  }

  void run(const TileRect& tile) {
    const int32_t x0 = std::max(t_.minX, tile.x0), x1 = std::min(t_.maxX, tile.x1);
    const int32_t y0 = std::max(t_.minY, tile.y0), y1 = std::min(t_.maxY, tile.y1);
    if (x0 > x1 || y0 > y1) return;
    for (int32_t by = y0 & ~(kBlockSize - 1); by <= y1; by += kBlockSize)
      for (int32_t bx = x0 & ~(kBlockSize - 1); bx <= x1; bx += kBlockSize) block(bx, by, x0, y0, x1, y1);
    flush();
  }

 private:
  static constexpr int64_t kStep = kSubpixelOne;  // one pixel in sub-pixels

  // One (level, layer) image of an attachment, addressed like TextureData::texel() without
  // recomputing the level's size per pixel.
  struct Plane {
    uint8_t* base = nullptr;
    uint64_t rowBytes = 0;
    uint32_t bpp = 0;
    Format format = Format::RGBA8;
    static Plane of(TextureData* tex, uint32_t level, uint32_t layer) {
      if (!tex) return {};
      const uint32_t bpp = texelBytes(tex->desc.format);
      return {tex->texel(level, layer, 0, 0), uint64_t(levelWidth(tex->desc, level)) * bpp, bpp, tex->desc.format};
    }
    uint8_t* at(int32_t x, int32_t y) const { return base + uint64_t(uint32_t(y)) * rowBytes + uint64_t(uint32_t(x)) * bpp; }
    float depth(int32_t x, int32_t y) const {
      float z;
      std::memcpy(&z, at(x, y), sizeof z);
      return z;
    }
  };

  int64_t edgeAt(int i, int32_t x, int32_t y) const {
    return t_.a[i] * ((int64_t(x) << kSubpixelBits) + kSubpixelHalf) +
           t_.b[i] * ((int64_t(y) << kSubpixelBits) + kSubpixelHalf) + t_.c[i];
  }

  void block(int32_t bx, int32_t by, int32_t x0, int32_t y0, int32_t x1, int32_t y1) {
    // Trivial reject / accept of the 8x8 block from each edge's extreme values over its samples.
    int64_t e0[3];
    bool full = true;
    constexpr int64_t span = int64_t(kBlockSize - 1) * kStep;
    for (int i = 0; i < 3; ++i) {
      e0[i] = edgeAt(i, bx, by);
      const int64_t hi = std::max<int64_t>(t_.a[i], 0) * span + std::max<int64_t>(t_.b[i], 0) * span;
      const int64_t lo = std::min<int64_t>(t_.a[i], 0) * span + std::min<int64_t>(t_.b[i], 0) * span;
      if (e0[i] - t_.bias[i] + hi < 0) return;
      if (e0[i] - t_.bias[i] + lo < 0) full = false;
    }
    const bool inside = bx >= x0 && by >= y0 && bx + kBlockSize - 1 <= x1 && by + kBlockSize - 1 <= y1;
    // Edge values step by exact integer increments: one pixel right adds a * kStep, one up b * kStep.
    int64_t dx[3], dy[3], eRow[3];
    for (int i = 0; i < 3; ++i) dx[i] = t_.a[i] * kStep, dy[i] = t_.b[i] * kStep, eRow[i] = e0[i];
    for (int32_t qy = by; qy < by + kBlockSize; qy += 2) {
      int64_t eq[3] = {eRow[0], eRow[1], eRow[2]};
      for (int i = 0; i < 3; ++i) eRow[i] += 2 * dy[i];
      if (qy + 1 < y0 || qy > y1) continue;
      for (int32_t qx = bx; qx < bx + kBlockSize; qx += 2) {
        int64_t e[4][3];
        for (int i = 0; i < 3; ++i) {
          e[0][i] = eq[i], e[1][i] = eq[i] + dx[i], e[2][i] = eq[i] + dy[i], e[3][i] = eq[i] + dx[i] + dy[i];
          eq[i] += 2 * dx[i];
        }
        if (qx + 1 < x0 || qx > x1) continue;
        uint8_t cov = 0xf;
        if (!full)
          for (int p = 0; p < 4; ++p)
            if (e[p][0] < t_.bias[0] || e[p][1] < t_.bias[1] || e[p][2] < t_.bias[2]) cov &= uint8_t(~(1u << p));
        if (!inside)
          for (int p = 0; p < 4; ++p) {
            const int32_t px = qx + (p & 1), py = qy + (p >> 1);
            if (px < x0 || px > x1 || py < y0 || py > y1) cov &= uint8_t(~(1u << p));
          }
        if (cov) quad(qx, qy, cov, e);
      }
    }
  }

  void quad(int32_t qx, int32_t qy, uint8_t cov, const int64_t (&e)[4][3]) {
    const size_t n = count_;
    Quad& q = s_.quads[n];
    q.x = qx, q.y = qy, q.coverage = cov;
    uint8_t live = cov;
    // Quad::z is gl_FragCoord.z and the value the depth test compares (the same float). The varyings
    // wait until the early depth test has kept a pixel.
    interpolateQuadDepth(t_, e, q.z);
    const TargetView& tv = scene_.target;
    if (ds_.depth.test && tv.depth && !lateDepth_) {
      for (int p = 0; p < 4; ++p) {
        if (!(live >> p & 1)) continue;
        const float stored = depth_.depth(qx + (p & 1), qy + (p >> 1));
        if (!depthPasses(ds_.depth.func, q.z[p], stored)) live &= uint8_t(~(1u << p));
      }
      stats_.fragments_depth_failed += quadPixels(uint32_t(cov & ~live));
      if (!live) return;  // no pixel can change: skip shading (no side effects are lost)
    }
    interpolateQuadVaryings(t_, ds_.varyings, e, q.var);
    s_.live[n] = live;
    s_.outs[n].discard = 0;
    // A program that writes depth and leaves a pixel alone keeps the interpolated depth (F11).
    if (lateDepth_) std::memcpy(s_.outs[n].depth, q.z, sizeof q.z);
    // The LOD probe shades one quad per call, so the sampler's log holds exactly that quad's lookups.
    if (++count_ == RastScratch::kBatch || scene_.lod) flush();
  }

  void flush() {
    if (!count_) return;
    QuadBatch batch{s_.quads.data(), s_.outs.data(), count_, {}, t_.primitiveId, t_.layer, t_.frontFacing};
    std::memcpy(batch.flat, t_.flat, sizeof batch.flat);
    if (scene_.lod) s_.lodLog.count = 0;
    const bool timing = scene_.timeStages;
    const uint64_t shade0 = timing ? stageClock() : 0;
    ds_.program->shadeQuads(batch, ds_.ctx);
    const uint64_t shade1 = timing ? stageClock() : 0;
    const TargetView& tv = scene_.target;
    const bool depthTest = ds_.depth.test && tv.depth;
    const bool depthWrite = depthTest && ds_.depth.write;
    for (size_t n = 0; n < count_; ++n) {
      const Quad& q = s_.quads[n];
      uint8_t keep = uint8_t(s_.live[n] & ~s_.outs[n].discard);
      stats_.quads_shaded += 1;
      stats_.fragments_shaded += quadPixels(uint32_t(s_.live[n]));
      stats_.helper_invocations += 4 - quadPixels(uint32_t(s_.live[n]));
      stats_.fragments_discarded += quadPixels(uint32_t(s_.live[n] & s_.outs[n].discard));
      // The fragment's depth: the program's gl_FragDepth, clamped (spec-choices F11), tested late.
      float z[4];
      for (int p = 0; p < 4; ++p) z[p] = lateDepth_ ? clampFragDepth(s_.outs[n].depth[p]) : q.z[p];
      if (lateDepth_ && depthTest) {
        const uint8_t before = keep;
        for (int p = 0; p < 4; ++p)
          if ((keep >> p & 1) &&
              !depthPasses(ds_.depth.func, z[p], depth_.depth(q.x + (p & 1), q.y + (p >> 1))))
            keep &= uint8_t(~(1u << p));
        stats_.fragments_depth_failed += quadPixels(uint32_t(before & ~keep));
      }
      // writeFragment's unblended RGBA8 case, the common write: the quad's 16 values converted at once
      // (raster/fragops_simd.h: toUnorm8's bytes).
      static_assert(sizeof(QuadOut::Value) == 4 * sizeof(float), "a quad's colours are 16 packed floats");
      uint8_t unorm[kMaxColorAttachments][16];
      if (keep && !ds_.blend.enabled)
        for (int a = 0; a < ds_.colorOutputs; ++a)
          if (color_[a].base && color_[a].format == Format::RGBA8)
            unorm8Quad_(s_.outs[n].color[a][0].f, unorm[a]);
      for (int p = 0; p < 4; ++p) {
        if (!(keep >> p & 1)) continue;
        const int32_t x = q.x + (p & 1), y = q.y + (p >> 1);
        if (depthWrite) std::memcpy(depth_.at(x, y), &z[p], sizeof(float));
        for (int a = 0; a < ds_.colorOutputs; ++a) {
          const Plane& c = color_[a];
          if (!c.base) continue;
          uint8_t* texel = c.at(x, y);
          if (c.format == Format::RGBA8 && !ds_.blend.enabled) {
            std::memcpy(texel, unorm[a] + 4 * p, 4);
          } else {
            writeFragment(c.format, texel, s_.outs[n].color[a][p].u, ds_.blend);
          }
        }
        ++stats_.pixels_written;
      }
      if (scene_.lod) recordLod(q, keep);
    }
    if (timing) {
      s_.ticks.t[kStageShade] += shade1 - shade0;
      s_.ticks.t[kStageFragops] += stageClock() - shade1;
    }
    count_ = 0;
  }

  // The LOD probe: the kept pixels of the quad just shaded take its lookups (the last write wins).
  void recordLod(const Quad& q, uint8_t keep) {
    LodMap& map = (*scene_.lod)[t_.layer < scene_.lod->size() ? t_.layer : 0];
    const LodQuadLog& log = s_.lodLog;
    const int n = std::min(log.count, kLodLookupsPerPixel);
    const uintptr_t base = reinterpret_cast<uintptr_t>(ds_.ctx.units.data());
    for (int p = 0; p < 4; ++p) {
      if (!(keep >> p & 1)) continue;
      LodPixel& px = map.at(q.x + (p & 1), q.y + (p >> 1));
      px.count = uint8_t(std::min(log.count, 255));
      for (int i = 0; i < n; ++i) {
        const LodQuadLog::Entry& e = log.e[size_t(i)];
        px.look[size_t(i)] = e.look;
        const uintptr_t off = reinterpret_cast<uintptr_t>(e.unit) - base;
        px.look[size_t(i)].unit = uint8_t(off / sizeof(TexUnit) < size_t(kMaxTextureUnits) ? off / sizeof(TexUnit) : 255);
      }
      for (int i = n; i < kLodLookupsPerPixel; ++i) px.look[size_t(i)] = LodLookup{};
    }
  }

  const Scene& scene_;
  const TriSetup& t_;
  const DrawState& ds_;
  RastScratch& s_;
  PipelineStats& stats_;
  const bool lateDepth_;  // the program writes gl_FragDepth: the depth test runs after shading (F11)
  const Unorm8QuadFn unorm8Quad_;  // the running SIMD target's unorm8 conversion (RastScratch)
  Plane depth_;
  Plane color_[kMaxColorAttachments];
  size_t count_ = 0;
};

}  // namespace

void rasterizeTile(const Scene& scene, size_t tileIndex, RastScratch& scratch, PipelineStats& stats) {
  const auto& bin = scene.bins[tileIndex];
  if (bin.empty()) return;
  if (scene.lod) setLodQuadLog(&scratch.lodLog);
  const uint64_t tile0 = scene.timeStages ? stageClock() : 0;
  if (scene.timeStages) setSampleTicks(&scratch.ticks.t[kStageSample]);
  ++stats.tiles_rasterized;
  // The SIMD kernels once per tile (a dispatch calls into libhwy; the target cannot change mid-frame).
  scratch.unorm8Quad = unorm8QuadKernel();
  bindSampleKernels();
  const int32_t tx = int32_t(tileIndex % size_t(scene.tilesX)), ty = int32_t(tileIndex / size_t(scene.tilesX));
  const TileRect tile{tx * kTileSize, ty * kTileSize, std::min((tx + 1) * kTileSize, scene.target.width) - 1,
                      std::min((ty + 1) * kTileSize, scene.target.height) - 1};
  for (const TileCmd& cmd : bin) {
    switch (cmd.op) {
      case TileOp::Triangle: {
        if (scene.provenance) {
          rasterizeTriangleProvenance(scene, scene.tri(cmd), tile, stats);
          break;
        }
        TriangleRasterizer r(scene, scene.tri(cmd), scratch, stats);
        r.run(tile);
        break;
      }
      case TileOp::ClearColor: {
        const ClearCmd& c = scene.clears[cmd.index];
        runClear(scene, c, scene.target.color[c.attachment], tile);
        if (scene.lod && c.attachment == 0) clearLod(scene, c, tile);
        break;
      }
      case TileOp::ClearDepth:
        runClear(scene, scene.clears[cmd.index], scene.target.depth, tile);
        break;
    }
  }
  endPlanCache();
  unbindSampleKernels();
  if (scene.lod) setLodQuadLog(nullptr);  // vertex stages on this thread must not append to it
  if (scene.timeStages) {
    setSampleTicks(nullptr);
    scratch.ticks.t[kStageTile] += stageClock() - tile0;
  }
}

}  // namespace tessera::detail
