#include "raster/rast.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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

// Every attachment the draw's program writes is RGBA8 or absent (flush()'s whole-quad write).
bool allRgba8(const Scene& scene, const DrawState& ds) {
  for (int a = 0; a < ds.colorOutputs; ++a) {
    const TextureData* tex = scene.target.color[size_t(a)];
    if (tex && tex->desc.format != Format::RGBA8) return false;
  }
  return true;
}

// How a triangle is walked. Immediate: coverage, depth, shading and writes, as GL orders them.
// A visibility run (rasterizeTile) walks each of its triangles twice instead: Visibility does the
// coverage, the early depth test, the depth writes and every counter, and records in
// RastScratch::owner which triangle's fragment last passed at each pixel; Owned then shades, in the
// same triangle order, only the quads with a pixel the triangle still owns (shadeOwned: the quads are
// read from the owner map, not walked again), and writes only those pixels' colours. The bytes are
// Immediate's: without blending every passing fragment replaces the colour, so a pixel ends with its
// last passing fragment's colour; without discard or gl_FragDepth a fragment's depth test and write do
// not depend on its shading; and a pixel's shaded value depends only on its quad's four interpolated
// positions, which do not depend on the live mask (helper pixels are computed the same way).
enum class Walk : uint8_t { Immediate, Visibility, Owned };
static_assert(size_t(Walk::Owned) + 1 == std::size(DrawConsts{}.edgesRead), "DrawConsts has an entry per walk");

// One class per walk (a template parameter, so the immediate walk carries no test of it).
template <Walk walk_>
class TriangleRasterizer {
 public:
  TriangleRasterizer(const Scene& scene, const TriSetup& t, RastScratch& s, PipelineStats& stats, uint16_t id = 0)
      : TriangleRasterizer(scene, t, s, stats, id, drawConsts(scene, t, s)) {}

 private:
  TriangleRasterizer(const Scene& scene, const TriSetup& t, RastScratch& s, PipelineStats& stats, uint16_t id,
                     const DrawConsts& c)
      : scene_(scene), t_(t), ds_(*scene.states[t.drawState]), s_(s), stats_(stats),
        lateDepth_(c.lateDepth), sourceOver_(c.sourceOver), unorm8Quad_(s.unorm8Quad),
        unblendedRgba8_(c.unblendedRgba8), sourceOverRgba8_(c.sourceOverRgba8), plainRgba8_(c.plainRgba8),
        // The LOD probe shades quad by quad, and a late depth test needs no early one: both stay per quad.
        gathered_(s.quadDepths && s.quadVaryings && !lateDepth_ && !scene.lod),
        needDepths_(c.depthsRead[size_t(walk_)]), edgesRead_(c.edgesRead[size_t(walk_)]), depth_(c.depth), color_(c.color),
        id_(id), writesDepth_(walk_ != Walk::Owned && c.depthWrite), hizFloor_(occlusionFloor(c)) {
    beginPlanCache();  // a new triangle: no lambda or plan of another one is reused (sample.h)
    if (gathered_) {
      // The scalar code's conversions of the triangle's constants (rast.h), each exact.
      // (A fixed-size copy: element by element, GCC 12 made it a library call, as the two may alias.)
      static_assert(sizeof plane_.invW == sizeof t.invW);
      std::memcpy(plane_.invW, t.invW, sizeof plane_.invW);
      for (int i = 0; i < 3; ++i) {
        plane_.z[i] = double(t.z[i]);
        if constexpr (walk_ != Walk::Visibility)  // Visibility interpolates depth only
          for (int k = 0; k < ds_.varyings; ++k) plane_.var[i][k] = double(t.var[i][k]);
      }
      plane_.area2 = double(t.area2);
      plane_.varyings = ds_.varyings;
    }
  }

  // The draw's DrawConsts (rast.h) for triangle t: RastScratch::drawConsts, made again when the draw or
  // the layer changes (rasterizeTile resets it per tile: a scene's draw indices restart).
  static const DrawConsts& drawConsts(const Scene& scene, const TriSetup& t, RastScratch& s) {
    DrawConsts& c = s.drawConsts;
    if (c.state == t.drawState && c.layer == t.layer) return c;
    const DrawState& ds = *scene.states[t.drawState];
    const TargetView& tv = scene.target;
    c.state = t.drawState, c.layer = t.layer;
    c.lateDepth = ds.program->writesDepth();
    c.sourceOver = isSourceOver(ds.blend);
    c.unblendedRgba8 = !ds.blend.enabled && allRgba8(scene, ds);
    c.sourceOverRgba8 = c.sourceOver && allRgba8(scene, ds);
    c.plainRgba8 = c.unblendedRgba8 && !c.lateDepth && !scene.lod && ds.colorOutputs == 1 && tv.color[0] &&
                   tv.color[0]->desc.format == Format::RGBA8;
    const bool depthTest = ds.depth.test && tv.depth;
    // Quad::z is read by the early depth test and the depth writes (Visibility's in a visibility run,
    // which walks a block without a depth test through visibleBlock instead), and by a program that
    // reads gl_FragCoord.z; nothing else reads it (runGathered).
    const bool fragDepth = ds.program->readsFragDepth();
    for (Walk w : {Walk::Immediate, Walk::Visibility, Walk::Owned}) {
      const size_t k = size_t(w);
      c.depthsRead[k] = w == Walk::Visibility || (w == Walk::Immediate && depthTest) || fragDepth;
      c.edgesRead[k] = c.depthsRead[k] || ds.varyings > 0;
    }
    c.depthWrite = depthTest && ds.depth.write;
    // See occlusionFloor.
    c.hizEligible = !c.lateDepth && s.quadDepths && !scene.provenance && tv.layer != kLayered && depthTest &&
                    (ds.depth.func == CompareFunc::Less || ds.depth.func == CompareFunc::LEqual);
    c.depth = Plane::of(tv.depth, tv.level, t.layer);
    for (int a = 0; a < ds.colorOutputs; ++a) c.color[a] = Plane::of(tv.color[size_t(a)], tv.level, t.layer);
    return c;
  }

 public:
  void run(const TileRect& tile) {
    const int32_t x0 = std::max(t_.minX, tile.x0), x1 = std::min(t_.maxX, tile.x1);
    const int32_t y0 = std::max(t_.minY, tile.y0), y1 = std::min(t_.maxY, tile.y1);
    if (x0 > x1 || y0 > y1) return;
    xLast_ = tile.x1, yLast_ = tile.y1;
    tileX0_ = tile.x0, tileY0_ = tile.y0;
    setQuadSteps();
    for (int i = 0; i < 3; ++i) edges_.dx[i] = quadStep_[i][1], edges_.dy[i] = quadStep_[i][2], edges_.bias[i] = t_.bias[i];
    if constexpr (walk_ == Walk::Visibility) {
      // A box the triangle covers whole, with no depth test (a full-screen layer's tiles): every block's
      // mask would be the box's part of it, and visibleBlock's work per block is then visibleBox's.
      if (!(ds_.depth.test && scene_.target.depth) && x1 - x0 + 1 >= kBlockSize && y1 - y0 + 1 >= kBlockSize &&
          coversBox(x0, y0, x1, y1))
        return visibleBox(x0, y0, x1, y1);  // (a Visibility walk batches no quads: nothing to flush)
    }
    // A small box inside one block (x0 and x1 >= 0 agree above the block's bits). Not under "reference"
    // (no quadDepths kernel), which walks every block: tests compare the two (SmallBox.*).
    if (x1 - x0 < kSmallBox && y1 - y0 < kSmallBox && (x0 ^ x1) < kBlockSize && (y0 ^ y1) < kBlockSize &&
        s_.quadDepths) {
      smallBox(x0, y0, x1, y1);
    } else {
      edges_.setSteps();
      for (int32_t by = y0 & ~(kBlockSize - 1); by <= y1; by += kBlockSize)
        for (int32_t bx = x0 & ~(kBlockSize - 1); bx <= x1; bx += kBlockSize) block(bx, by, x0, y0, x1, y1);
    }
    flush();
  }

  // Walk::Owned: shades the quads the triangle owns pixels of (mask: those pixels), in the tile.
  // A quad's edge values are the ones block() steps to (edgeAt is exact integer arithmetic).
  void shadeOwned(const TileRect& tile, const RastScratch::OwnedQuad* quads, size_t n) {
    xLast_ = tile.x1, yLast_ = tile.y1;
    tileX0_ = tile.x0, tileY0_ = tile.y0;
    setQuadSteps();
    for (size_t j = 0; j < n; ++j) {
      const RastScratch::OwnedQuad& oq = quads[j];
      if (edgesRead_) {
        const int64_t eq[3] = {edgeAt(0, oq.x, oq.y), edgeAt(1, oq.x, oq.y), edgeAt(2, oq.x, oq.y)};
        gather(oq.x, oq.y, oq.mask, eq);
      } else {
        gatherQuad(oq.x, oq.y, oq.mask);
      }
      if (pending_ == QuadPixels::kMax / 4) runGathered();
    }
    runGathered();
    flush();
  }

 private:
  static constexpr int64_t kStep = kSubpixelOne;  // one pixel in sub-pixels
  // The largest box (pixels per side, in one block) that run() tests pixel by pixel (smallBox).
  static constexpr int32_t kSmallBox = 4;

  using Plane = AttachmentPlane;

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
    BlockEdges& be = edges_;  // steps and bias set per triangle (run)
    for (int i = 0; i < 3; ++i) be.e0[i] = e0[i];
    // The covered pixels (raster/coverage_simd.h: bit 8 y + x), within the triangle's box and the tile.
    static_assert(kBlockSize == 8, "a block's coverage is one 64-bit mask");
    // Rows outside the box are not tested (a small triangle's block has few rows to test).
    be.rowBegin = std::max(y0 - by, 0), be.rowEnd = std::min(y1 - by + 1, kBlockSize);
    uint64_t mask = full ? ~uint64_t(0) : s_.blockCoverage(be);
    if (!inside) mask &= boxMask(bx, by, x0, y0, x1, y1);
    walkBlock(bx, by, mask);
  }

  // The box [x0, x1] x [y0, y1] (within the tile) of a small triangle, inside one block: block()'s
  // mask, with each pixel of the box tested by the fill rule on its exact edge values, instead of the
  // block's trivial tests, the kernel's step table and call, and the box mask (a one-pixel triangle's
  // box is 1 to 4 pixels; callgrind: about 190 instructions per such triangle instead of about 250).
  // The same bits: a bit is set iff its pixel is in the box and e_i - bias_i >= 0 for every edge,
  // which is what the kernel's mask ANDed with the box mask holds (a block the trivial test rejects
  // has no such pixel either).
  void smallBox(int32_t x0, int32_t y0, int32_t x1, int32_t y1) {
    const int32_t bx = x0 & ~(kBlockSize - 1), by = y0 & ~(kBlockSize - 1);
    const BlockEdges& be = edges_;
    int64_t row[3];
    for (int i = 0; i < 3; ++i) row[i] = edgeAt(i, x0, y0) - be.bias[i];
    uint64_t mask = 0;
    for (int32_t y = y0; y <= y1; ++y) {
      int64_t e[3] = {row[0], row[1], row[2]};
      for (int32_t x = x0; x <= x1; ++x) {
        // All three non-negative iff their OR is (exact int64 values, |e| < 2^55).
        mask |= uint64_t((e[0] | e[1] | e[2]) >= 0) << (8 * (y - by) + (x - bx));
        for (int i = 0; i < 3; ++i) e[i] += be.dx[i];
      }
      for (int i = 0; i < 3; ++i) row[i] += be.dy[i];
    }
    if (!mask) return;
    for (int i = 0; i < 3; ++i) edges_.e0[i] = edgeAt(i, bx, by);  // walkBlock steps from the block's origin
    walkBlock(bx, by, mask);
  }

  // The covered pixels `mask` (bit 8 y + x) of the block at (bx, by), edges_.e0 its edge values there:
  // the hierarchical Z test, then the quads with a covered pixel, in order.
  void walkBlock(int32_t bx, int32_t by, uint64_t mask) {
    if (!mask) return;
    const BlockEdges& be = edges_;
    const size_t b =
        size_t((by - tileY0_) / kBlockSize) * RastScratch::kBlocksPerRow + size_t((bx - tileX0_) / kBlockSize);
    if (hizFloor_ == hizFloor_ && occluded(b, bx, by)) {
      // Every covered pixel fails the early depth test, as the walk would have counted them.
      const uint64_t n = popcount64(mask);
      stats_.fragments_depth_failed += n;
      s_.hizBlocksSkipped += 1;
      s_.hizFragmentsSkipped += n;
      return;
    }
    if (writesDepth_) s_.hizKnown &= ~(uint64_t(1) << b);  // its largest stored depth may change
    if constexpr (walk_ == Walk::Visibility) {
      // Without a depth test every covered pixel passes: the block's ownership and counters come from
      // its mask alone, with no depth to interpolate.
      if (!(ds_.depth.test && scene_.target.depth)) return visibleBlock(bx, by, mask);
    }
    // The quads with a covered pixel, as the bit of their pixel 0 (8 ry + rx, ry and rx even), visited in
    // increasing order: row by row, left to right.
    const uint64_t firstPixels = (mask | mask >> 1 | mask >> 8 | mask >> 9) & 0x0055005500550055u;
    if (gathered_ && !edgesRead_) {  // the same walk, without the edge values nothing reads (gather)
      for (uint64_t quads = firstPixels; quads; quads &= quads - 1) {
        const int bit = std::countr_zero(quads);
        const uint64_t bits = mask >> bit;
        gatherQuad(bx + (bit & 7), by + (bit >> 3), uint8_t((bits & 3) | (bits >> 8 & 3) << 2));
      }
      return runGathered();
    }
    for (uint64_t quads = firstPixels; quads; quads &= quads - 1) {
      const int bit = std::countr_zero(quads);
      const int ry = bit >> 3, rx = bit & 7;
      // Quad pixel p = x + 2 y is bit 8 (ry + y) + rx + x of the mask.
      const uint64_t bits = mask >> bit;
      const uint8_t cov = uint8_t((bits & 3) | (bits >> 8 & 3) << 2);
      int64_t eq[3];  // the edge values at the quad's pixel 0
      for (int i = 0; i < 3; ++i) eq[i] = be.e0[i] + rx * be.dx[i] + ry * be.dy[i];
      if (gathered_) {
        gather(bx + rx, by + ry, cov, eq);
      } else {
        int64_t e[4][3];
        for (int i = 0; i < 3; ++i)
          for (int p = 0; p < 4; ++p) e[p][i] = eq[i] + quadStep_[i][p];
        quad(bx + rx, by + ry, cov, e);
      }
    }
    if (gathered_) runGathered();
  }

  // Hierarchical Z: the least depth a covered pixel of the triangle can have, if a block's fragments may
  // be found failing from it (occluded); NaN otherwise. Exact, not conservative by a tolerance: a
  // covered pixel has edge values e_i >= 0 (E_i - bias_i >= 0, bias_i in {0, 1}) that sum to area2,
  // so its exact depth sum(e_i z_i) / area2 is a convex combination of the vertex depths, >= min z_i.
  // With every z_i finite and >= 0, pixelDepth (rast.h; the kernels give its bits) adds non-negative
  // terms, so its double is the exact value times at most (1 - 2^-53)^6 / (1 + 2^-53): far closer to
  // min z_i than half a float ulp, and the rounding to float cannot go below min z_i. Only for the
  // walks that run the early test on the interpolated depth (not a program's gl_FragDepth), with the
  // kernels (the "reference" target walks every block: the tests compare the two), one owner of the
  // target's depth per tile (not a layered target) and not in provenance mode.
  float occlusionFloor(const DrawConsts& c) const {
    constexpr float kNone = std::numeric_limits<float>::quiet_NaN();
    if (walk_ == Walk::Owned || !c.hizEligible) return kNone;
    for (int i = 0; i < 3; ++i)
      if (!(t_.z[i] >= 0.0f && t_.z[i] <= std::numeric_limits<float>::max())) return kNone;
    return std::min(std::min(t_.z[0], t_.z[1]), t_.z[2]);
  }

  // Whether every covered pixel of block b (at bx, by) fails the depth test: each has a depth >=
  // hizFloor_, and LESS fails for a stored depth <= it, LEQUAL for one < it. A stored NaN fails both
  // whatever the incoming depth, so the block's bound is its largest non-NaN depth.
  bool occluded(size_t b, int32_t bx, int32_t by) {
    if (!(s_.hizKnown >> b & 1)) {
      s_.hizMax[b] = storedDepthMax(bx, by);
      s_.hizKnown |= uint64_t(1) << b;
    }
    const float zmax = s_.hizMax[b];
    return ds_.depth.func == CompareFunc::Less ? hizFloor_ >= zmax : hizFloor_ > zmax;
  }

  // The largest non-NaN depth stored in the block at (bx, by) within the target; -inf if none. Per
  // column first, then across the columns. Only the skip decision depends on it, never a byte: any
  // upper bound of the block's non-NaN depths is sound, and this one is exact.
  float storedDepthMax(int32_t bx, int32_t by) const {
    const int32_t w = std::min(kBlockSize, xLast_ - bx + 1), h = std::min(kBlockSize, yLast_ - by + 1);
    constexpr float kLow = -std::numeric_limits<float>::infinity();
#if defined(__SSE2__)
    if (w == kBlockSize) {
      // A whole row is two vectors. MAXPS(a, b) returns b when a is NaN, so a NaN keeps the column's
      // maximum, as in the scalar loop below (which a compiler does not vectorize).
      __m128 lo = _mm_set1_ps(kLow), hi = lo;
      for (int32_t y = 0; y < h; ++y) {
        const float* row = reinterpret_cast<const float*>(depth_.at(bx, by + y));
        lo = _mm_max_ps(_mm_loadu_ps(row), lo);
        hi = _mm_max_ps(_mm_loadu_ps(row + 4), hi);
      }
      __m128 m = _mm_max_ps(lo, hi);  // no NaN is left
      m = _mm_max_ps(m, _mm_shuffle_ps(m, m, _MM_SHUFFLE(1, 0, 3, 2)));
      m = _mm_max_ps(m, _mm_shuffle_ps(m, m, _MM_SHUFFLE(2, 3, 0, 1)));
      return _mm_cvtss_f32(m);
    }
#endif
    float col[kBlockSize];
    for (float& c : col) c = kLow;
    for (int32_t y = 0; y < h; ++y) {
      const uint8_t* src = depth_.at(bx, by + y);
      for (int32_t x = 0; x < w; ++x) {
        float v;
        std::memcpy(&v, src + sizeof(float) * size_t(x), sizeof v);
        col[x] = v > col[x] ? v : col[x];  // a NaN keeps col
      }
    }
    float m = col[0];
    for (int32_t x = 1; x < w; ++x) m = col[x] > m ? col[x] : m;
    return m;
  }

  // The pixels of the block at (bx, by) inside [x0, x1] x [y0, y1], as a coverage mask.
  static uint64_t boxMask(int32_t bx, int32_t by, int32_t x0, int32_t y0, int32_t x1, int32_t y1) {
    const int32_t cx0 = std::max(x0 - bx, 0), cx1 = std::min(x1 - bx, kBlockSize - 1);
    const int32_t cy0 = std::max(y0 - by, 0), cy1 = std::min(y1 - by, kBlockSize - 1);
    if (cx0 > cx1 || cy0 > cy1) return 0;
    const uint64_t row = ((uint64_t(2) << cx1) - 1) & ~((uint64_t(1) << cx0) - 1);  // bits cx0..cx1
    // Bit 0 of each of the rows cy0..cy1 (0x01 per byte, as many bytes as rows); times `row` (< 256)
    // that copies the row into each of them without a carry between bytes.
    const uint64_t rows = 0x0101010101010101u & (~uint64_t(0) >> (56 - 8 * (cy1 - cy0)));
    return (row * rows) << (8 * cy0);
  }

  // Walk::Visibility's whole work on the block's gathered quads (their depths in s_.z): the early
  // depth test, the depth writes, the ownership, and the counters quad() and flush() would have
  // counted (no pixel is discarded, so every live pixel is shaded and written).
  void recordVisible(size_t np) {
    const bool depthTest = ds_.depth.test && scene_.target.depth;
    uint64_t quads = 0, live = 0, failed = 0;
    for (size_t j = 0; j < np; ++j) {
      const RastScratch::PendingQuad& pq = s_.pending[j];
      const float* z = s_.z + 4 * j;
      const uint8_t pass = depthTest ? uint8_t(pq.coverage & depthPassMask(pq.x, pq.y, z)) : pq.coverage;
      failed += quadPixels(uint32_t(pq.coverage & ~pass));
      if (!pass) continue;
      quads += 1;
      live += quadPixels(pass);
      uint16_t* own = s_.owner + size_t(pq.y - tileY0_) * kTileSize + size_t(pq.x - tileX0_);
      if (pass == 0xF) {  // the common case: both rows' two pixels at once
        if (writesDepth_) {
          std::memcpy(depth_.at(pq.x, pq.y), z, 2 * sizeof(float));
          std::memcpy(depth_.at(pq.x, pq.y + 1), z + 2, 2 * sizeof(float));
        }
        const uint16_t ids[2] = {id_, id_};
        std::memcpy(own, ids, sizeof ids);
        std::memcpy(own + kTileSize, ids, sizeof ids);
        continue;
      }
      for (int p = 0; p < 4; ++p) {
        if (!(pass >> p & 1)) continue;
        if (writesDepth_) std::memcpy(depth_.at(pq.x + (p & 1), pq.y + (p >> 1)), &z[p], sizeof(float));
        own[size_t(p >> 1) * kTileSize + size_t(p & 1)] = id_;
      }
    }
    stats_.fragments_depth_failed += failed;
    stats_.quads_shaded += quads;
    stats_.fragments_shaded += live;
    stats_.helper_invocations += 4 * quads - live;
    stats_.pixels_written += live;
  }

  // Walk::Visibility without a depth test: the covered pixels of the block at (bx, by) (mask, bit
  // 8 y + x) all pass; recordVisible's ownership and counters for each of its quads.
  void visibleBlock(int32_t bx, int32_t by, uint64_t mask) {
    if (!mask) return;
    uint16_t* row = s_.owner + size_t(by - tileY0_) * kTileSize + size_t(bx - tileX0_);
    const uint16_t ids[kBlockSize] = {id_, id_, id_, id_, id_, id_, id_, id_};
    for (int y = 0; y < kBlockSize; ++y, row += kTileSize) {
      const uint32_t bits = uint32_t(mask >> (8 * y)) & 0xffu;
      if (bits == 0xffu) {  // a whole row in one copy
        std::memcpy(row, ids, sizeof ids);
        continue;
      }
      for (int x = 0; x < kBlockSize; ++x)
        if (bits >> x & 1) row[x] = id_;
    }
    // The counters of its quads: those with a covered pixel, and their covered pixels.
    const uint64_t quads = popcount64((mask | mask >> 1 | mask >> 8 | mask >> 9) & 0x0055005500550055u);
    const uint64_t n = popcount64(mask);
    stats_.quads_shaded += quads;
    stats_.fragments_shaded += n;
    stats_.helper_invocations += 4 * quads - n;
    stats_.pixels_written += n;
  }

  // Whether the triangle covers every pixel of the box [x0, x1] x [y0, y1]: the fill rule's test
  // (e_i - bias_i >= 0 for every edge, as the coverage kernel applies it) at the box's four corner
  // pixels. Each edge function is linear, so its least value over the box's pixel centres is at a
  // corner; exact int64 values (edgeAt).
  bool coversBox(int32_t x0, int32_t y0, int32_t x1, int32_t y1) const {
    const int32_t xs[2] = {x0, x1}, ys[2] = {y0, y1};
    for (int c = 0; c < 4; ++c) {
      const int32_t x = xs[c & 1], y = ys[c >> 1];
      for (int i = 0; i < 3; ++i)
        if (edgeAt(i, x, y) - t_.bias[i] < 0) return false;
    }
    return true;
  }

  // Walk::Visibility without a depth test, over a box the triangle covers whole (coversBox): the sum of
  // visibleBlock over the box's blocks, each with the box's part of it as its mask. The owner map takes
  // the id row by row; the counters come in closed form: every pixel of the box passes, and the quads
  // are the 2x2 ones (at even x and y: blocks start at multiples of 8) that hold a pixel of it.
  void visibleBox(int32_t x0, int32_t y0, int32_t x1, int32_t y1) {
    const size_t w = size_t(x1 - x0 + 1);
    uint16_t* row = s_.owner + size_t(y0 - tileY0_) * kTileSize + size_t(x0 - tileX0_);
    for (int32_t y = y0; y <= y1; ++y, row += kTileSize) std::fill_n(row, w, id_);
    const uint64_t n = uint64_t(w) * uint64_t(y1 - y0 + 1);
    const uint64_t quads = uint64_t((x1 >> 1) - (x0 >> 1) + 1) * uint64_t((y1 >> 1) - (y0 >> 1) + 1);
    stats_.quads_shaded += quads;
    stats_.fragments_shaded += n;
    stats_.helper_invocations += 4 * quads - n;
    stats_.pixels_written += n;
  }

  // The early depth test of a quad's four pixels as a mask (bit p: pixel p passes), without a branch
  // per pixel. A quad may reach past the last column or row of the target (odd sizes); those pixels are
  // never covered, and their stored depth is read at the last valid one instead, then masked away.
  uint8_t depthPassMask(const Quad& q) const { return depthPassMask(q.x, q.y, q.z); }
  uint8_t depthPassMask(int32_t x, int32_t y, const float* z) const {
#if defined(__SSE2__)
    // LESS and LEQUAL, the usual functions, on a quad inside the target: the four comparisons at once
    // (about 1.5 % of city_block at 720p). CMPLTPS and CMPLEPS are IEEE's ordered < and <=, false
    // with a NaN on either side, as depthPasses. The "reference" target (no quadDepths kernel) takes
    // the scalar steps below, which tests/raster/test_hierarchical_z.cpp compares with it (ties,
    // stored NaNs, quads past an odd-sized target's last column and row).
    const CompareFunc f = ds_.depth.func;
    if ((f == CompareFunc::Less || f == CompareFunc::LEqual) && x < xLast_ && y < yLast_ && s_.quadDepths) {
      // Pixels 0 and 1 (row y), then 2 and 3 (row y + 1): two 8-byte loads.
      const __m128 stored = _mm_castpd_ps(_mm_loadh_pd(_mm_load_sd(reinterpret_cast<const double*>(depth_.at(x, y))),
                                                       reinterpret_cast<const double*>(depth_.at(x, y + 1))));
      const __m128 in = _mm_loadu_ps(z);
      const __m128 pass = f == CompareFunc::Less ? _mm_cmplt_ps(in, stored) : _mm_cmple_ps(in, stored);
      return uint8_t(_mm_movemask_ps(pass));
    }
#endif
    const int32_t xr = std::min(x + 1, xLast_), yu = std::min(y + 1, yLast_);
    const float stored[4] = {depth_.depth(x, y), depth_.depth(xr, y), depth_.depth(x, yu), depth_.depth(xr, yu)};
    uint32_t pass = 0;
    for (int p = 0; p < 4; ++p) pass |= uint32_t(depthPasses(ds_.depth.func, z[p], stored[p])) << p;
    return uint8_t(pass);
  }

  // The edge steps from a quad's pixel 0 to its pixels 0..3: 0, one right, one up, both (exact integers).
  void setQuadSteps() {
    for (int i = 0; i < 3; ++i) {
      const int64_t dx = t_.a[i] * kStep, dy = t_.b[i] * kStep;
      quadStep_[i][0] = 0, quadStep_[i][1] = dx, quadStep_[i][2] = dy, quadStep_[i][3] = dx + dy;
    }
  }

  // Appends a covered quad of the block to the kernels' input (RastScratch::px, pixel 4 j + p), from
  // the edge values eq at its pixel 0: four consecutive values per edge, which compile to vector adds.
  // Only the depth and varying kernels read them (runGathered): a draw with neither, such as a flat
  // colour without a depth test, appends the quad alone with gatherQuad (edgesRead_; about 34 of a
  // one-pixel triangle's 1,900 instructions, callgrind).
  void gatherQuad(int32_t qx, int32_t qy, uint8_t cov) { s_.pending[pending_++] = {qx, qy, cov}; }
  void gather(int32_t qx, int32_t qy, uint8_t cov, const int64_t (&eq)[3]) {
    const size_t j = pending_;
    gatherQuad(qx, qy, cov);
    for (int i = 0; i < 3; ++i) {
      int64_t* dst = s_.px.e[i] + 4 * j;
      for (int p = 0; p < 4; ++p) dst[p] = eq[i] + quadStep_[i][p];
    }
  }

  // The block's gathered quads, in the order quad() would have taken them, with the same results:
  // depths of all their pixels in one kernel call, the early depth test per pixel, then the varyings
  // of the quads that kept a pixel in a second call. A triangle covers a pixel once, so testing a
  // block's quads before any of them is written sees the depths quad() would see.
  void runGathered() {
    const size_t np = pending_;
    if (!np) return;
    pending_ = 0;
    // The block's quads go into one batch (batches are only a grouping of program calls).
    if (count_ + np > RastScratch::kBatch) flush();
    QuadPixels& px = s_.px;
    // Quad::z is read by the early depth test and the depth writes, and by a program that reads
    // gl_FragCoord.z (DrawConsts::depthsRead); nothing else reads it (the LOD probe and a program
    // writing gl_FragDepth take quad(), provenance mode its own walk). Without those its interpolation
    // is skipped (a third of a one-pixel triangle's interpolation and conversion work), and the quads'
    // z stays whatever an earlier batch left: never read.
    const bool depthTest = ds_.depth.test && scene_.target.depth;
    const bool needDepths = needDepths_;
    if (needDepths) s_.quadDepths(px, 4 * np, plane_, s_.z);
    if constexpr (walk_ == Walk::Visibility) return recordVisible(np);
    size_t kept = 0;
    for (size_t j = 0; j < np; ++j) {
      const size_t n = count_ + kept;
      Quad& q = s_.quads[n];
      const RastScratch::PendingQuad& pq = s_.pending[j];
      q.x = pq.x, q.y = pq.y, q.coverage = pq.coverage;
      if (needDepths) std::memcpy(q.z, s_.z + 4 * j, sizeof q.z);
      uint8_t live = pq.coverage;
      if (depthTest && walk_ != Walk::Owned) {
        live &= depthPassMask(q);
        stats_.fragments_depth_failed += quadPixels(uint32_t(pq.coverage & ~live));
        if (!live) continue;
      }
      s_.live[n] = live;
      s_.outs[n].discard = 0;
      if (kept != j)  // close the gap left by quads that failed depth
        for (int i = 0; i < 3; ++i) std::memcpy(px.e[i] + 4 * kept, px.e[i] + 4 * j, 4 * sizeof(int64_t));
      ++kept;
    }
    if (kept && ds_.varyings) {  // (the kernel returns at once without varyings: no call)
      s_.quadVaryings(px, 4 * kept, plane_, s_.var);
      for (size_t l = 0; l < kept; ++l) {
        Quad& q = s_.quads[count_ + l];
        for (int p = 0; p < 4; ++p)
          for (int k = 0; k < ds_.varyings; ++k) q.var[p][k] = s_.var[size_t(k) * QuadPixels::kMax + 4 * l + size_t(p)];
      }
    }
    count_ += kept;
    if (count_ == RastScratch::kBatch) flush();
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
      live &= depthPassMask(q);
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

  // The unorm8 bytes of a quad's 16 colour values (unorm8Quad_), through the thread's memo of its
  // last conversion (RastScratch::UnormMemo): a constant colour, as a flat-coloured draw writes,
  // converts once instead of per quad. A triangle stops asking the memo at its first miss, so a
  // textured one pays one comparison. Off under "reference" (quadDepths unset): every conversion runs.
  void quadUnorm8(const float* values, uint8_t* out) {
    if (unormMemo_ && s_.quadDepths) return s_.unormMemo.convert(unorm8Quad_, values, out, unormMemo_);
    unorm8Quad_(values, out);
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
    // Walk::Owned: the depths and counters were written by the triangle's Visibility walk.
    const bool owned = walk_ == Walk::Owned;
    const bool depthWrite = depthTest && ds_.depth.write && !owned;
    if (plainRgba8_) {
      writePlainRgba8(depthWrite);
    } else {
      writeQuads(depthTest, depthWrite);
    }
    if (timing) {
      s_.ticks.t[kStageShade] += shade1 - shade0;
      s_.ticks.t[kStageFragops] += stageClock() - shade1;
    }
    count_ = 0;
  }

  // The plain draw's writes (DrawConsts::plainRgba8): writeQuads with what the draw rules out taken out
  // (late depth, blending, other formats, more outputs, the LOD probe), so the same bytes and counters.
  // The general loop re-reads the draw's output count and planes per quad, as its byte writes may alias
  // them; a constant colour's quad cost about 167 instructions there (callgrind, fill_flat_720p).
  void writePlainRgba8(bool depthWrite) {
    constexpr bool owned = walk_ == Walk::Owned;
    uint8_t* const base = color_[0].base;
    const uint64_t rowBytes = color_[0].rowBytes;
    for (size_t n = 0; n < count_; ++n) {
      const Quad& q = s_.quads[n];
      const uint8_t live = s_.live[n], keep = uint8_t(live & ~s_.outs[n].discard);
      if (!owned) {
        stats_.quads_shaded += 1;
        stats_.fragments_shaded += quadPixels(uint32_t(live));
        stats_.helper_invocations += 4 - quadPixels(uint32_t(live));
        stats_.fragments_discarded += quadPixels(uint32_t(live & s_.outs[n].discard));
      }
      if (!keep) continue;
      uint8_t unorm[16];
      quadUnorm8(s_.outs[n].color[0][0].f, unorm);
      uint8_t* const row0 = base + uint64_t(uint32_t(q.y)) * rowBytes + uint64_t(uint32_t(q.x)) * 4;
      if (keep == 0xF) {
        if (depthWrite) {
          std::memcpy(depth_.at(q.x, q.y), q.z, 2 * sizeof(float));
          std::memcpy(depth_.at(q.x, q.y + 1), q.z + 2, 2 * sizeof(float));
        }
        std::memcpy(row0, unorm, 8);
        std::memcpy(row0 + rowBytes, unorm + 8, 8);
        if (!owned) stats_.pixels_written += 4;
        continue;
      }
      if (q.x < xLast_ && q.y < yLast_) {
        const uint64_t m0 = kRowPixels[keep & 3], m1 = kRowPixels[keep >> 2];
        if (depthWrite) mergeRows(depth_, q.x, q.y, q.z, m0, m1);
        mergeRows(color_[0], q.x, q.y, unorm, m0, m1);
        if (!owned) stats_.pixels_written += quadPixels(keep);
        continue;
      }
      for (int p = 0; p < 4; ++p) {
        if (!(keep >> p & 1)) continue;
        const int32_t x = q.x + (p & 1), y = q.y + (p >> 1);
        if (depthWrite) std::memcpy(depth_.at(x, y), &q.z[p], sizeof(float));
        std::memcpy(color_[0].at(x, y), unorm + 4 * p, 4);
        if (!owned) ++stats_.pixels_written;
      }
    }
  }

  // The 64-bit mask of a row's two RGBA8 (or float) pixels from their two keep bits (pixel 0 low).
  static constexpr uint64_t kRowPixels[4] = {0, 0xFFFFFFFFu, 0xFFFFFFFF00000000u, ~uint64_t(0)};
  static_assert(std::endian::native == std::endian::little, "pixel 0 of a row is its low 4 bytes");

  // flush()'s writes of the shaded quads for any draw: the late depth test, then each attachment's
  // write (raster/fragops.h), with the counters.
  void writeQuads(bool depthTest, bool depthWrite) {
    const bool owned = walk_ == Walk::Owned;
    for (size_t n = 0; n < count_; ++n) {
      const Quad& q = s_.quads[n];
      uint8_t keep = uint8_t(s_.live[n] & ~s_.outs[n].discard);
      if (!owned) {
        stats_.quads_shaded += 1;
        stats_.fragments_shaded += quadPixels(uint32_t(s_.live[n]));
        stats_.helper_invocations += 4 - quadPixels(uint32_t(s_.live[n]));
        stats_.fragments_discarded += quadPixels(uint32_t(s_.live[n] & s_.outs[n].discard));
      }
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
            quadUnorm8(s_.outs[n].color[a][0].f, unorm[a]);
      if (keep == 0xF && (unblendedRgba8_ || sourceOverRgba8_)) {
        // The common write of a whole quad: each row's two pixels in one copy, unblended or blended
        // source over four pixels at once (raster/fragops_simd.h: blendSourceOverRgba8's bytes). The
        // pixels of a quad are distinct, so the order of their writes is not observable.
        if (depthWrite) {
          std::memcpy(depth_.at(q.x, q.y), z, 2 * sizeof(float));
          std::memcpy(depth_.at(q.x, q.y + 1), z + 2, 2 * sizeof(float));
        }
        for (int a = 0; a < ds_.colorOutputs; ++a) {
          if (!color_[a].base) continue;
          if (sourceOverRgba8_) {
            s_.blendSourceOverQuad(s_.outs[n].color[a][0].f, color_[a].at(q.x, q.y), color_[a].at(q.x, q.y + 1));
            continue;
          }
          std::memcpy(color_[a].at(q.x, q.y), unorm[a], 8);
          std::memcpy(color_[a].at(q.x, q.y + 1), unorm[a] + 8, 8);
        }
        if (!owned) stats_.pixels_written += 4;
        if (scene_.lod) recordLod(q, keep);
        continue;
      }
      if (keep && unblendedRgba8_ && q.x < xLast_ && q.y < yLast_) {
        // A partly covered quad inside the target, unblended RGBA8: its kept pixels merged into the two
        // rows under a mask, with no branch per pixel. The other pixels get their own bytes back: the
        // tile owns them, and nothing else writes them meanwhile.
        const uint64_t m0 = kRowPixels[keep & 3], m1 = kRowPixels[keep >> 2];
        if (depthWrite) mergeRows(depth_, q.x, q.y, z, m0, m1);
        for (int a = 0; a < ds_.colorOutputs; ++a)
          if (color_[a].base) mergeRows(color_[a], q.x, q.y, unorm[a], m0, m1);
        if (!owned) stats_.pixels_written += quadPixels(keep);
        if (scene_.lod) recordLod(q, keep);
        continue;
      }
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
          } else if (c.format == Format::RGBA8 && sourceOver_) {
            blendSourceOverRgba8(s_.outs[n].color[a][p].f, texel);  // writeFragment's bytes (fragops.h)
          } else {
            writeFragment(c.format, texel, s_.outs[n].color[a][p].u, ds_.blend);
          }
        }
        if (!owned) ++stats_.pixels_written;
      }
      if (scene_.lod) recordLod(q, keep);
    }
  }

  // The 8 bytes of each of a quad's two rows in `plane` (at x, y and x, y + 1): those under mask m0 (row
  // y) and m1 (row y + 1) from src (16 bytes, row y first), the others kept.
  static void mergeRows(const Plane& plane, int32_t x, int32_t y, const void* src, uint64_t m0, uint64_t m1) {
    uint64_t s[2], r0, r1;
    std::memcpy(s, src, sizeof s);
    std::memcpy(&r0, plane.at(x, y), 8);
    std::memcpy(&r1, plane.at(x, y + 1), 8);
    r0 = (r0 & ~m0) | (s[0] & m0), r1 = (r1 & ~m1) | (s[1] & m1);
    std::memcpy(plane.at(x, y), &r0, 8);
    std::memcpy(plane.at(x, y + 1), &r1, 8);
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
  const bool sourceOver_;  // blending is SRC_ALPHA, ONE_MINUS_SRC_ALPHA, ADD (blendSourceOverRgba8)
  const Unorm8QuadFn unorm8Quad_;  // the running SIMD target's unorm8 conversion (RastScratch)
  bool unormMemo_ = true;  // quadUnorm8 asks the memo until its first miss
  const bool unblendedRgba8_;  // no blending, and every written attachment is RGBA8 or absent
  const bool sourceOverRgba8_;  // source-over blending, and every written attachment is RGBA8 or absent
  const bool plainRgba8_;  // DrawConsts::plainRgba8: flush writes through writePlainRgba8
  const bool gathered_;  // blocks' quads go through the interpolation kernels (runGathered)
  const bool needDepths_;  // DrawConsts::depthsRead of this walk: runGathered interpolates Quad::z
  const bool edgesRead_;   // DrawConsts::edgesRead of this walk: gather makes the quads' edge values
  const Plane depth_;
  // Not value-initialised: zeroing it (with the rest of the object, a `rep stos` of about 1 KB per
  // triangle) was 15 % of a one-pixel triangle's walk. The constructor sets what the kernels read (the
  // varyings up to the draw's count) whenever gathered_ is set, and nothing reads it otherwise.
  InterpolationPlane plane_;
  size_t pending_ = 0;  // quads gathered from the block being walked
  int32_t xLast_ = 0, yLast_ = 0;  // the tile's last column and row (inside the target)
  BlockEdges edges_;  // the coverage kernel's input (raster/coverage_simd.h)
  int64_t quadStep_[3][4];  // setQuadSteps
  // The draw's colour planes, in RastScratch::drawConsts: a walk runs to its end before the next
  // triangle's may remake them (copying them cost 16 instructions per one-pixel triangle).
  const Plane* const color_;
  size_t count_ = 0;
  // Visibility and Owned (last, so the immediate walk's members keep their place).
  const uint16_t id_;  // 1 + the triangle's index in its visibility run
  int32_t tileX0_ = 0, tileY0_ = 0;  // the tile's first column and row (RastScratch::owner's origin)
  // Hierarchical Z (occluded).
  const bool writesDepth_;  // the walk may write depth in the blocks it visits
  const float hizFloor_;    // occlusionFloor(): NaN when blocks are always walked
};

// The mean bounding-box pixels per triangle from which a run is walked twice (rasterizeTile).
constexpr uint64_t kVisibilityMinBoxPixels = 32;
// The times the run's bounding boxes, clipped to the tile, must cover it (a box holds about twice its
// triangle's pixels, so 3 is about one and a half layers of fragments).
constexpr uint64_t kVisibilityMinTileCover = 3;

// The pixels of the bounding boxes of triangles bin[first, last), each clipped to the tile.
uint64_t tileBoxPixels(const Scene& scene, const std::vector<TileCmd>& bin, size_t first, size_t last,
                       const TileRect& tile) {
  uint64_t sum = 0;
  for (size_t i = first; i < last; ++i) {
    const TriSetup& t = scene.tri(bin[i]);
    const int32_t w = std::min(t.maxX, tile.x1) - std::max(t.minX, tile.x0) + 1;
    const int32_t h = std::min(t.maxY, tile.y1) - std::max(t.minY, tile.y0) + 1;
    if (w > 0 && h > 0) sum += uint64_t(w) * uint64_t(h);
  }
  return sum;
}

// A triangle may join a visibility run (TriangleRasterizer's Walk): its fragments' fate is decided by
// coverage and the early depth test alone (no blending, no discard, no gl_FragDepth), it takes the
// kernels' path (runGathered), nothing records per-quad lookups (the LOD probe) and one owner map
// covers its pixels (not a layered target, whose triangles choose their layer).
bool joinsVisibilityRun(const Scene& scene, const RastScratch& s, const DrawState& ds) {
  return !scene.provenance && !scene.lod && scene.target.layer != kLayered && s.quadDepths && s.quadVaryings &&
         !ds.blend.enabled && !ds.program->writesDepth() && !ds.program->mayDiscard(ds.ctx);
}

// Fetches the TriSetup of bin[i] ahead of its use: a bin visits the triangle arena in submission
// order with gaps, so each TriSetup (several cache lines) would otherwise miss the cache on its first
// read. Always inlined: GCC 12 finds a function whose only effect is a prefetch pure and deletes the
// call (the prefetches then vanished from the binary: tiny_tris_100k lost 12 %).
[[gnu::always_inline]] inline void prefetchTriangle(const Scene& scene, const std::vector<TileCmd>& bin, size_t i) {
  if (i >= bin.size() || bin[i].op != TileOp::Triangle) return;
  const char* next = reinterpret_cast<const char*>(&scene.tri(bin[i]));
  for (size_t line = 0; line < sizeof(TriSetup); line += 64) __builtin_prefetch(next + line);
}

// The quads of the tile with a pixel in RastScratch::owner, grouped by owner in s.ownedQuads: the
// quads of id k are [s.ownedStart[k], s.ownedStart[k + 1]), each with the pixels k owns in it.
// A quad's two rows are read as one 32-bit word each (pixel 0 in the low half), so the common quad, one
// owner or none, costs two loads and two comparisons; the entries go to arrays sized once for a whole
// tile, written by index (with four ids read per pixel and a push_back per quad, the grouping was 16 %
// of fill_flat_720p's instructions).
void groupOwnedQuads(const TileRect& tile, size_t ids, RastScratch& s) {
  // At most one entry per owner of each of a quad's four pixels.
  constexpr size_t kMaxEntries = size_t(kTileSize / 2) * size_t(kTileSize / 2) * 4;
  if (s.ownedTemp.size() < kMaxEntries) s.ownedTemp.resize(kMaxEntries), s.ownedQuads.resize(kMaxEntries);
  s.ownedStart.assign(ids + 2, 0);
  RastScratch::OwnedQuad* const temp = s.ownedTemp.data();
  uint32_t* const count = s.ownedStart.data() + 1;  // count[id]: the entries of id
  size_t n = 0;
  const int32_t w = tile.x1 - tile.x0 + 1, h = tile.y1 - tile.y0 + 1;
  static_assert(std::endian::native == std::endian::little, "pixel 0 of a quad's row is the word's low half");
  for (int32_t ry = 0; ry < h; ry += 2) {
    // A quad past the target's last row or column reads owner 0 there: nothing owns it (the map is
    // kTileSize square, so the row and column after a tile's odd last one are inside it).
    const uint16_t* const row = s.owner + size_t(ry) * kTileSize;
    for (int32_t rx = 0; rx < w; rx += 2) {
      uint32_t top, bottom;
      std::memcpy(&top, row + rx, sizeof top);
      std::memcpy(&bottom, row + kTileSize + rx, sizeof bottom);
      const int32_t x = tile.x0 + rx, y = tile.y0 + ry;
      if (top == bottom && top >> 16 == (top & 0xFFFF)) {  // the common case: one owner or none
        if (top) {
          const uint16_t id = uint16_t(top);
          temp[n++] = {x, y, uint8_t(0xF), id};
          ++count[id];
        }
        continue;
      }
      const uint16_t id[4] = {uint16_t(top), uint16_t(top >> 16), uint16_t(bottom), uint16_t(bottom >> 16)};
      for (int p = 0; p < 4; ++p) {
        if (!id[p]) continue;
        int q = 0;
        while (id[q] != id[p]) ++q;
        if (q < p) continue;  // counted with its first pixel
        uint8_t mask = 0;
        for (int r = p; r < 4; ++r) mask |= uint8_t(id[r] == id[p]) << r;
        temp[n++] = {x, y, mask, id[p]};
        ++count[id[p]];
      }
    }
  }
  for (size_t k = 1; k < s.ownedStart.size(); ++k) s.ownedStart[k] += s.ownedStart[k - 1];
  s.ownedFill.assign(s.ownedStart.begin(), s.ownedStart.end() - 1);
  for (size_t k = 0; k < n; ++k) s.ownedQuads[s.ownedFill[temp[k].id]++] = temp[k];
}

// The triangles bin[first, last) as one visibility run: every one walked for visibility, then each
// that owns a pixel at the end shades the quads it owns (Walk says why the bytes and counters are the
// immediate walk's).
void runVisibility(const Scene& scene, const std::vector<TileCmd>& bin, size_t first, size_t last,
                   const TileRect& tile, RastScratch& s, PipelineStats& stats) {
  std::memset(s.owner, 0, sizeof s.owner);
  for (size_t i = first; i < last; ++i) {
    prefetchTriangle(scene, bin, i + 2);
    TriangleRasterizer<Walk::Visibility>(scene, scene.tri(bin[i]), s, stats, uint16_t(i - first + 1)).run(tile);
  }
  groupOwnedQuads(tile, last - first, s);
  for (size_t i = first; i < last; ++i) {
    const uint16_t id = uint16_t(i - first + 1);
    const uint32_t b = s.ownedStart[id], e = s.ownedStart[size_t(id) + 1];
    if (b == e) continue;
    TriangleRasterizer<Walk::Owned>(scene, scene.tri(bin[i]), s, stats, id).shadeOwned(tile, &s.ownedQuads[b], e - b);
  }
}

}  // namespace

void rasterizeTile(const Scene& scene, size_t tileIndex, RastScratch& scratch, PipelineStats& stats) {
  const auto& bin = scene.bins[tileIndex];
  if (bin.empty()) return;
  if (scene.lod) setLodQuadLog(&scratch.lodLog);
  const uint64_t tile0 = scene.timeStages ? stageClock() : 0;
  if (scene.timeStages) setSampleTicks(&scratch.ticks.t[kStageSample]);
  // The SIMD kernels once per tile (a dispatch calls into libhwy; the target cannot change mid-frame).
  scratch.unorm8Quad = unorm8QuadKernel();
  scratch.blendSourceOverQuad = blendSourceOverQuadKernel();
  scratch.quadDepths = quadDepthsKernel();
  scratch.quadVaryings = quadVaryingsKernel();
  scratch.blockCoverage = blockCoverageKernel();
  bindSampleKernels();
  scratch.hizKnown = 0;  // the depth target may have changed since this thread's last tile
  scratch.drawConsts.state = UINT32_MAX;  // and the scene's draws are others
  const int32_t tx = int32_t(tileIndex % size_t(scene.tilesX)), ty = int32_t(tileIndex / size_t(scene.tilesX));
  const TileRect tile{tx * kTileSize, ty * kTileSize, std::min((tx + 1) * kTileSize, scene.target.width) - 1,
                      std::min((ty + 1) * kTileSize, scene.target.height) - 1};
  // Whether the last draw state asked about joins a visibility run (triangles of a draw are adjacent).
  uint32_t askedState = UINT32_MAX;
  bool joins = false;
  const auto joinsRun = [&](const TileCmd& c) {
    if (c.op != TileOp::Triangle) return false;
    const uint32_t state = scene.blocks[c.index].drawState;
    if (state != askedState) askedState = state, joins = joinsVisibilityRun(scene, scratch, *scene.states[state]);
    return joins;
  };
  const uint64_t tilePixels = uint64_t(tile.x1 - tile.x0 + 1) * uint64_t(tile.y1 - tile.y0 + 1);
  size_t immediateUntil = 0;  // the end of a run found too small to walk twice: its triangles go one by one
  for (size_t ci = 0; ci < bin.size(); ++ci) {
    const TileCmd& cmd = bin[ci];
    if (ci >= immediateUntil && joinsRun(cmd)) {
      // The run: this triangle and the ones after it that join, up to the owner map's 65535 ids.
      size_t last = ci + 1;
      uint64_t boxPixels = scene.blocks[cmd.index].meanBoxPixels;
      while (last < bin.size() && last - ci < UINT16_MAX && joinsRun(bin[last]))
        boxPixels += scene.blocks[bin[last++].index].meanBoxPixels;
      // Speed only (the bytes are the same either way): the second walk pays where triangles are large
      // enough that a skipped quad saves more than a triangle's second setup costs (one-pixel triangles
      // lost 50 %), and where their boxes cover the tile often enough that fragments are likely hidden
      // (a full-screen textured quad, drawn once, lost 16 %).
      if (last - ci > 1 && boxPixels >= kVisibilityMinBoxPixels * (last - ci) &&
          tileBoxPixels(scene, bin, ci, last, tile) >= kVisibilityMinTileCover * tilePixels) {
        runVisibility(scene, bin, ci, last, tile, scratch, stats);
        ci = last - 1;
        continue;
      }
      immediateUntil = last;
    }
    // The triangle after the next one is fetched while this one runs.
    prefetchTriangle(scene, bin, ci + 2);
    switch (cmd.op) {
      case TileOp::Triangle: {
        if (scene.provenance) {
          rasterizeTriangleProvenance(scene, scene.tri(cmd), tile, stats);
          break;
        }
        TriangleRasterizer<Walk::Immediate> r(scene, scene.tri(cmd), scratch, stats);
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
        scratch.hizKnown = 0;
        break;
    }
  }
  endPlanCache();
  unbindSampleKernels();
  if (scene.provenance) {
    ShadeProvenance& sp = shadeProvenance();
    scratch.provPlansSkipped += sp.plansSkipped, scratch.provGridsShared += sp.gridsShared;
    sp.plansSkipped = sp.gridsShared = 0;
  }
  if (scene.lod) setLodQuadLog(nullptr);  // vertex stages on this thread must not append to it
  if (scene.timeStages) {
    setSampleTicks(nullptr);
    scratch.ticks.t[kStageTile] += stageClock() - tile0;
  }
}

}  // namespace tessera::detail
