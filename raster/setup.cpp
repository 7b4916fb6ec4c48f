#include "raster/setup.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <utility>

#include "raster/round.h"
#include "raster/stage_times.h"
#include "raster/tolerances.h"

namespace tessera::detail {

namespace {

struct WindowVertex {
  int64_t x, y;  // sub-pixels
  double invW;
  float z;
  const double* var;     // clipped varyings (double) or nullptr
  const float* varF;     // unclipped varyings (float) or nullptr
  bool original;         // a vertex of the primitive (false: made by clipping)
  double errSub;         // how far GL may put it from here (sub-pixels; 0 for an original vertex)
};

// floor(a / kSubpixelOne): C++20 defines >> of a negative value as the arithmetic shift, which is
// floor division by a power of two (a division with its sign correction was 38 instructions per
// triangle here).
static_assert(kSubpixelOne == (int64_t(1) << kSubpixelBits), "a pixel is a power of two of sub-pixels");
inline int64_t floorPixels(int64_t a) { return a >> kSubpixelBits; }

// Bins a snapped triangle given window vertices in submission order.
// `internal` flags the edges (w0 w1, w1 w2, w2 w0) that are fan diagonals of a clipped polygon.
// The vertices are taken by reference: copied by value, each 56-byte WindowVertex was read back as
// 16-byte words just after toWindow wrote it field by field, a failed store forwarding per word (a
// fifth of setupTriangle's time).
// One instance per mode (params.provenance) and source (made by clipping, or the primitive unclipped):
// the unclipped, fast-path instance has a single caller and is inlined, so its window vertices stay
// in registers and no provenance test is left in it (callgrind: binTriangle and its caller 549 -> 475
// instructions per one-pixel triangle).
template <bool kProvenance, bool kClipped>
void binTriangle(const WindowVertex& w0, const WindowVertex& w1, const WindowVertex& w2, const VertexOut& provoking,
                 uint32_t primitiveId, uint32_t layer, const SetupParams& params, SetupSink& sink, bool& binned,
                 std::array<bool, 3> internal = {false, false, false}) {
  PipelineStats& stats = sink.stats;
  // Doubled signed area from the snapped coordinates (GL 4.6 §14.6.1, eq. 14.8 in window space).
  const int64_t area2 = (w1.x - w0.x) * (w2.y - w0.y) - (w2.x - w0.x) * (w1.y - w0.y);
  if (area2 == 0) return;  // degenerate after snapping: no fragments (docs/spec-choices.md)
  const bool ccw = area2 > 0;
  const bool front = ccw == params.raster.frontCcw;
  if (params.raster.cull == CullMode::Back && !front) return;
  if (params.raster.cull == CullMode::Front && front) return;
  // Edge opposite vertex i in submission order: 0 = w1 w2, 1 = w2 w0, 2 = w0 w1.
  bool internalOpp[3] = {internal[1], internal[2], internal[0]};
  // The edge functions below assume counter-clockwise order.
  const WindowVertex* wv[3] = {&w0, ccw ? &w1 : &w2, ccw ? &w2 : &w1};
  if (!ccw) std::swap(internalOpp[1], internalOpp[2]);

  // Built in place at the end of the arena (a TriSetup is 472 bytes); removed again if no tile takes it.
  TriSetup& t = sink.tris.emplace_back(TriSetup::NoInit{});
  t.area2 = ccw ? area2 : -area2;
  // Vertex i + 1 and i + 2 (mod 3) as cyc[i + 1] and cyc[i + 2]; the provenance and varying members in
  // loops of their own. The loop below then unrolls without a modulo or a test per edge (with the
  // shift of floorPixels, binTriangle went from 540 to 442 instructions per one-pixel triangle).
  const WindowVertex* const cyc[5] = {wv[0], wv[1], wv[2], wv[0], wv[1]};
  for (int i = 0; i < 3; ++i) {
    // Edge opposite vertex i runs from vertex i+1 to vertex i+2.
    const WindowVertex& p = *cyc[i + 1];
    const WindowVertex& q = *cyc[i + 2];
    t.a[i] = p.y - q.y;
    t.b[i] = q.x - p.x;
    t.c[i] = p.x * q.y - q.x * p.y;
    // Fill rule: a sample exactly on an edge belongs to the triangle iff the edge is a left edge
    // (it runs downwards in y-up window space: a > 0) or a bottom edge (horizontal, running in +x:
    // a == 0 && b > 0). This is GL's "left + bottom" as rr and llvmpipe produce it.
    const bool inclusive = t.a[i] > 0 || (t.a[i] == 0 && t.b[i] > 0);
    t.bias[i] = inclusive ? 0 : 1;
    t.invW[i] = wv[i]->invW;
    t.z[i] = wv[i]->z;
  }
  if constexpr (kProvenance) {  // read by provenance mode only (TriSetup)
    for (int i = 0; i < 3; ++i) {
      const WindowVertex& p = *cyc[i + 1];
      const WindowVertex& q = *cyc[i + 2];
      t.vx[i] = wv[i]->x;
      t.vy[i] = wv[i]->y;
      t.edgeKind[i] = internalOpp[i] ? kEdgeInternal : (p.original && q.original) ? kEdgeOriginal : kEdgeClipped;
      t.clipMarginSub[i] = t.edgeKind[i] == kEdgeClipped ? std::max(p.errSub, q.errSub) : 0.0;
    }
  }
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < params.varyings; ++k) t.var[i][k] = kClipped ? float(wv[i]->var[k]) : wv[i]->varF[k];

  // Pixel bounds: pixel X is a candidate iff its centre X*256 + 128 lies within [min, max].
  const int64_t minx = std::min({w0.x, w1.x, w2.x}), maxx = std::max({w0.x, w1.x, w2.x});
  const int64_t miny = std::min({w0.y, w1.y, w2.y}), maxy = std::max({w0.y, w1.y, w2.y});
  const Rect& r = params.clampRect;
  // Provenance mode also visits pixels up to one pixel outside: they may be covered under another
  // legal snapping (EDGE_TIE), and further out as far as GL may put a vertex made by clipping
  // (CLIP_EDGE). Coverage itself stays exact; only the visited area grows.
  // (Only there: std::ceil is a libm call on baseline x86-64, once per triangle.)
  int64_t clipGrow = 0;
  if constexpr (kProvenance) {
    const double clipPx = std::max({w0.errSub, w1.errSub, w2.errSub}) / double(kSubpixelOne);
    clipGrow = clipPx < 65536.0 ? int64_t(std::ceil(clipPx)) : 65536;
  }
  const int64_t grow = kProvenance ? 1 + clipGrow : 0;
  const int64_t x0 = std::max<int64_t>(floorPixels(minx - kSubpixelHalf + kSubpixelOne - 1) - grow, r.x);
  const int64_t x1 = std::min<int64_t>(floorPixels(maxx - kSubpixelHalf) + grow, int64_t(r.x) + r.w - 1);
  const int64_t y0 = std::max<int64_t>(floorPixels(miny - kSubpixelHalf + kSubpixelOne - 1) - grow, r.y);
  const int64_t y1 = std::min<int64_t>(floorPixels(maxy - kSubpixelHalf) + grow, int64_t(r.y) + r.h - 1);
  if (x0 > x1 || y0 > y1) {
    sink.tris.pop_back();
    return;
  }
  t.minX = int32_t(x0), t.maxX = int32_t(x1), t.minY = int32_t(y0), t.maxY = int32_t(y1);

  for (int k = 0; k < kMaxFlatVaryings; ++k) t.flat[k] = provoking.flat[k];
  t.primitiveId = primitiveId;
  t.layer = layer;
  t.drawState = params.stateIndex;
  t.frontFacing = front;
  t.clipped = kClipped;
  t.depthSig = 0;  // provenance mode sets it after setup (cpu_backend.cpp)

  const size_t tilesBefore = sink.tiles.size();
  bool any = false;
  for (int32_t ty = t.minY >> kTileOrder; ty <= (t.maxY >> kTileOrder); ++ty) {
    for (int32_t tx = t.minX >> kTileOrder; tx <= (t.maxX >> kTileOrder); ++tx) {
      // Trivial reject: the largest value of each edge function over the tile's sample points.
      const int64_t sx0 = (int64_t(tx) << (kTileOrder + kSubpixelBits)) + kSubpixelHalf;
      const int64_t sy0 = (int64_t(ty) << (kTileOrder + kSubpixelBits)) + kSubpixelHalf;
      const int64_t span = int64_t(kTileSize - 1) << kSubpixelBits;
      bool reject = false;
      for (int i = 0; i < 3 && !reject; ++i) {
        const int64_t sx = t.a[i] > 0 ? sx0 + span : sx0;
        const int64_t sy = t.b[i] > 0 ? sy0 + span : sy0;
        // In provenance mode a near miss (within the tie margin, at most 2 px of edge function
        // here) must still reach the tile.
        const int64_t slack =
            kProvenance ? (2 + clipGrow) * kSubpixelOne * (std::abs(t.a[i]) + std::abs(t.b[i])) : 0;
        reject = t.a[i] * sx + t.b[i] * sy + t.c[i] - t.bias[i] + slack < 0;
      }
      if (reject) continue;
      sink.tiles.push_back(uint32_t(ty) * uint32_t(sink.tilesX) + uint32_t(tx));
      any = true;
    }
  }
  if (!any) {
    sink.tris.pop_back();
    sink.tiles.resize(tilesBefore);
    return;
  }
  sink.tileEnd.push_back(uint32_t(sink.tiles.size()));
  sink.boxPixels += uint64_t(x1 - x0 + 1) * uint64_t(y1 - y0 + 1);
  ++stats.triangles_binned;
  binned = true;
}

// A window coordinate in sub-pixels, rounded half to even (docs/spec-choices.md, snapping). Below 2^51
// (every coordinate of a primitive inside the guard band) the two-addition form of raster/round.h
// gives roundHalfEven's integer without its branches: the fraction of a snapped coordinate is
// arbitrary, so those branches were mispredicted about half the time, and they were over half of the
// setup of a small-triangle frame (city_block). Larger values keep the truncating form.
inline int64_t snap(double v) { return std::fabs(v) <= 2251799813685248.0 ? roundHalfEvenNear(v) : roundHalfEven(v); }

// Perspective division, viewport transform (GL 4.6 §13.8, in the order rr uses: divide first,
// then scale and offset) and snapping.
inline WindowVertex toWindow(const double pos[4], const Rect& vp) {
  const double invW = 1.0 / pos[3];
  const double xd = pos[0] * invW, yd = pos[1] * invW, zd = pos[2] * invW;
  const double halfW = 0.5 * vp.w, halfH = 0.5 * vp.h;
  const double xw = xd * halfW + (vp.x + halfW);
  const double yw = yd * halfH + (vp.y + halfH);
  // Depth range [0, 1]: zw = zd / 2 + 1/2, clamped (GL 4.6 §13.8.1; clipping already bounds it up
  // to rounding).
  double zw = zd * 0.5 + 0.5;
  zw = std::clamp(zw, 0.0, 1.0);
  WindowVertex w;
  w.x = snap(xw * double(kSubpixelOne));
  w.y = snap(yw * double(kSubpixelOne));
  w.invW = invW;
  w.z = float(zw);
  w.var = nullptr;
  w.varF = nullptr;
  w.original = true;
  w.errSub = 0.0;
  return w;
}

// Provenance: whether a vertex of the clipped polygon is one of the primitive's own (clipping copies
// those unchanged).
inline bool isOriginal(const ClipVertex& c, const VertexOut (&v)[3]) {
  for (const VertexOut& o : v)
    if (c.pos[0] == double(o.pos[0]) && c.pos[1] == double(o.pos[1]) && c.pos[2] == double(o.pos[2]) &&
        c.pos[3] == double(o.pos[3]))
      return true;
  return false;
}

// Provenance: the largest clip-space magnitude among the primitive's vertices, the scale of GL's
// float error in a vertex that clipping computes from them.
inline double clipMagnitude(const VertexOut (&v)[3]) {
  double m = 0.0;
  for (const VertexOut& o : v)
    for (int k = 0; k < 4; ++k) m = std::max(m, std::fabs(double(o.pos[k])));
  return m;
}

// Provenance: how far (sub-pixels, x plus y) GL may put a vertex that clipping made, when it clips
// in float (docs/crosscheck.md, CLIP_EDGE): each clip-space component within
// tolerance::kClipVertexRel * mag, then divided by w and scaled by the viewport, plus GL's own
// snapping of it (counted by the edge margin). Unbounded (infinity) when w may reach 0.
inline double clipVertexErrorSub(const double pos[4], double mag, const Rect& vp) {
  const double e = tolerance::kClipVertexRel * mag;
  const double w = pos[3];
  if (!(w - e > 0.0)) return std::numeric_limits<double>::infinity();
  const double wl = w - e;
  const double dx = (e + std::fabs(pos[0] / w) * e) / wl, dy = (e + std::fabs(pos[1] / w) * e) / wl;
  const double sub = (dx * 0.5 * vp.w + dy * 0.5 * vp.h) * double(kSubpixelOne);
  return std::isfinite(sub) ? sub : std::numeric_limits<double>::infinity();
}

}  // namespace

void windowVerticesReference(const VertexOut* v, size_t n, const Rect& vp, uint8_t clipMask, const VertexWindows& out) {
  for (size_t i = 0; i < n; ++i) {
    out.x[i] = out.y[i] = 0, out.invW[i] = 0.0, out.z[i] = 0.0f;
    uint32_t code = classifyVertex(v[i], clipMask);
    if (!(code & (kClipFixedPlaneBits | kClipNonFinite))) {
      if (v[i].pos[3] > 0.0f) {
        const double pos[4] = {v[i].pos[0], v[i].pos[1], v[i].pos[2], v[i].pos[3]};
        const WindowVertex w = toWindow(pos, vp);
        out.x[i] = w.x, out.y[i] = w.y, out.invW[i] = w.invW, out.z[i] = w.z;
      } else {
        // w == 0 passes the fixed planes only at the clip-space origin: no window position.
        code |= kVertexNoWindow;
      }
    }
    out.code[i] = code;
  }
}

void appendToScene(SetupSink& sink, Scene& scene, PipelineStats& stats) {
  stats.add(sink.stats);
  const size_t count = sink.tris.size();
  if (count == 0) return;
  assert(count <= size_t(UINT16_MAX) + 1);  // TileCmd::slot; cpu_backend.cpp bounds a chunk's output
  const uint32_t block = uint32_t(scene.triBlocks.size());
  scene.blocks.push_back({sink.tris[0].drawState, uint32_t(std::min<uint64_t>(sink.boxPixels / count, UINT32_MAX))});
  scene.triBlocks.push_back(std::exchange(sink.tris, {}));
  scene.triangles += count;
  uint32_t begin = 0;
  for (size_t i = 0; i < count; ++i) {
    for (uint32_t k = begin; k < sink.tileEnd[i]; ++k)
      scene.push(sink.tiles[k], {TileOp::Triangle, uint16_t(i), block}, sink.segment, stats);
    begin = sink.tileEnd[i];
  }
}

void setupTriangle(const VertexOut* const (&v)[3], const VertexWindows& win, const size_t (&s)[3],
                   uint32_t primitiveId, uint32_t layer, const SetupParams& params, SetupSink& sink) {
  PipelineStats& stats = sink.stats;
  ++stats.primitives_assembled;
  const uint32_t code[3] = {win.code[s[0]], win.code[s[1]], win.code[s[2]]};
  const ClipResult cr = classifyCodes(code[0], code[1], code[2]);
  if (cr == ClipResult::Outside) {
    ++stats.primitives_culled;
    return;
  }
  bool binned = false;
  if (cr == ClipResult::Inside) {
    // A vertex with w <= 0 has no window position (VertexWindow); GL leaves the primitive undefined
    // and the oracle drops it.
    if ((code[0] | code[1] | code[2]) & kVertexNoWindow) {
      ++stats.primitives_culled;
      return;
    }
    WindowVertex w[3];
    for (int i = 0; i < 3; ++i) {
      w[i].x = win.x[s[i]], w[i].y = win.y[s[i]], w[i].invW = win.invW[s[i]], w[i].z = win.z[s[i]];
      w[i].var = nullptr;
      w[i].varF = v[i]->var;
      w[i].original = true;
      w[i].errSub = 0.0;
    }
    if (params.provenance)
      binTriangle<true, false>(w[0], w[1], w[2], *v[2], primitiveId, layer, params, sink, binned);
    else
      binTriangle<false, false>(w[0], w[1], w[2], *v[2], primitiveId, layer, params, sink, binned);
  } else {
    ++stats.primitives_clipped;
    const VertexOut c[3] = {*v[0], *v[1], *v[2]};  // the clipping functions take the vertices by value
    ClipVertex poly[kMaxClipPolygon];
    const uint64_t clip0 = params.timeStages ? stageClock() : 0;
    const int n = clipTriangle(c, params.raster.clipMask, params.varyings, poly);
    if (params.timeStages) sink.clipTicks += stageClock() - clip0;
    WindowVertex w[kMaxClipPolygon];
    for (int i = 0; i < n; ++i)
      if (!(poly[i].pos[3] > 0.0)) {
        ++stats.primitives_culled;
        return;
      }
    const double mag = params.provenance ? clipMagnitude(c) : 0.0;
    for (int i = 0; i < n; ++i) {
      w[i] = toWindow(poly[i].pos, params.viewport);
      w[i].var = poly[i].var;
      if (params.provenance) {
        w[i].original = isOriginal(poly[i], c);
        w[i].errSub = w[i].original ? 0.0 : clipVertexErrorSub(poly[i].pos, mag, params.viewport);
      }
    }
    // Fan from the first vertex; every sub-triangle keeps the primitive's provoking vertex and id.
    for (int i = 1; i + 1 < n; ++i) {
      const std::array<bool, 3> internal = {i > 1, false, i + 2 < n};
      if (params.provenance)
        binTriangle<true, true>(w[0], w[i], w[i + 1], c[2], primitiveId, layer, params, sink, binned, internal);
      else
        binTriangle<false, true>(w[0], w[i], w[i + 1], c[2], primitiveId, layer, params, sink, binned, internal);
    }
  }
  if (!binned) ++stats.primitives_culled;
}

}  // namespace tessera::detail
