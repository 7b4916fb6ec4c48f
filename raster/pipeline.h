// Internal data of the CPU backend, shared by its stages (not a public header):
//   setup (clip.cpp, setup.cpp): vertices -> clipped, snapped triangles binned into 64x64 tiles;
//   scene (this file): the bins, the per-draw state snapshots and the triangle arena;
//   rast (rast.cpp, fragops.cpp): runs each tile's commands in submission order.
// The two halves talk only through Scene, as llvmpipe's setup and rast do (lp_scene.h).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "raster/command_list.h"
#include "raster/lod_probe.h"
#include "raster/program.h"
#include "raster/texture.h"

namespace tessera::detail {

// Everything a triangle of one draw needs at rasterization time, captured when the draw is issued
// so later state changes do not affect it.
struct DrawState {
  const Program* program = nullptr;
  std::array<Vec4, kMaxUniformSlots> uniforms{};
  ShadeContext ctx;  // ctx.uniforms points into `uniforms`
  DepthState depth;
  BlendState blend;
  int varyings = 0;
  int colorOutputs = 1;
  Rect clampRect;  // viewport ∩ scissor ∩ target of the draw (provenance mode widens bboxes within it)
  uint64_t drawSerial = 0;  // provenance: the draw's number in the list (edge tags correlate one draw only)
  // Provenance: the part of the depth-writer signature shared by the draw's triangles, and the depth
  // epoch it was issued in (raster/depth_signature.h).
  uint64_t depthSigBase = 0;
  uint32_t depthEpoch = 0;
};

// A triangle after clipping, snapping and setup. Coordinates are in sub-pixels (8 fractional bits)
// of GL window space (origin bottom-left, y up), already ordered counter-clockwise.
struct TriSetup {
  // TriSetup{} and `TriSetup t;` are as for an aggregate (zeroed, uninitialised). Setup builds each
  // one in place with NoInit: value-initialising its 472 bytes was a `rep stos` per triangle (4 % of
  // a setup-bound frame), and binTriangle writes every member that is read (the varyings up to the
  // draw's count, the provenance-only members in provenance mode; depthSig 0 until provenance mode
  // sets it).
  struct NoInit {};
  TriSetup() = default;
  explicit TriSetup(NoInit) {}
  // Edge function i is opposite vertex i: E_i(p) = a[i] * px + b[i] * py + c[i]; E_i > 0 inside.
  int64_t a[3], b[3], c[3];
  // 0 for inclusive edges (left or bottom, GL window space), 1 otherwise: a sample on the edge is
  // covered iff E_i - bias[i] >= 0 (docs/spec-choices.md "Fill rule").
  int64_t bias[3];
  int64_t area2;                    // 2 * signed area, > 0
  int32_t minX, minY, maxX, maxY;   // inclusive pixel bounds, clamped to viewport/scissor/target
  double invW[3];                   // 1 / w_clip per vertex
  float z[3];                       // window depth per vertex
  float var[3][kMaxVaryings];
  uint32_t flat[kMaxFlatVaryings];
  uint32_t primitiveId;
  uint32_t layer;
  uint32_t drawState;               // index into Scene::states
  bool frontFacing;
  bool clipped;                     // made by clipping: its edges may sit elsewhere in GL (CLIP_EDGE)
  // Provenance only (setup leaves them unset otherwise): the snapped window position of each vertex
  // (sub-pixels, counter-clockwise order) to recognise an edge that two triangles share (EdgeTag in
  // provenance.h); per edge (opposite vertex i) its kind and the extra distance (sub-pixels) by which
  // GL may place it elsewhere because clipping computed an endpoint (docs/crosscheck.md, CLIP_EDGE).
  int64_t vx[3], vy[3];
  uint8_t edgeKind[3];  // EdgeKind
  double clipMarginSub[3];
  // Provenance only: the depth-writer signature of the primitive (raster/depth_signature.h): equal
  // signatures give bit-identical fragment depths in GL at any one pixel (Appendix A); 0 = none.
  uint64_t depthSig;
};

// What made an edge of a triangle (provenance mode).
enum EdgeKind : uint8_t {
  kEdgeOriginal = 0,  // both endpoints are vertices of the primitive
  kEdgeInternal = 1,  // a diagonal of the fan that triangulates a clipped polygon (no boundary)
  kEdgeClipped = 2,   // at least one endpoint was made by clipping
};

enum class TileOp : uint8_t { Triangle, ClearColor, ClearDepth };
struct TileCmd {
  TileOp op;
  uint16_t slot;   // Triangle: the triangle's place in its block (Scene::triBlocks)
  uint32_t index;  // Triangle: the block, Scene::triBlocks; clears: Scene::clears
};

struct ClearCmd {
  uint32_t attachment;            // colour attachment (ClearColor only)
  std::array<uint32_t, 4> bits;   // float bits or uint values; ClearDepth: bits[0] = float bits
  Rect rect;                      // scissor-limited area
};

// One bound render target, resolved to storage.
struct TargetView {
  std::array<TextureData*, kMaxColorAttachments> color{};
  TextureData* depth = nullptr;
  uint32_t level = 0;
  uint32_t layer = 0;        // fixed layer or kLayered
  uint32_t layerCount = 1;   // layers available (min over attachments)
  int32_t width = 0, height = 0;
};

// Counters of what the pipeline did (deterministic: integer sums, independent of threads).
struct PipelineStats {
  uint64_t primitives_assembled = 0;     // triangles formed from draws
  uint64_t primitives_dropped_by_program = 0;  // geometry stage returned false or bad layer
  uint64_t primitives_culled = 0;        // trivially outside a clip plane, zero-area, face-culled, no pixels
  uint64_t primitives_clipped = 0;       // crossed a clip plane and went through polygon clipping
  uint64_t triangles_binned = 0;         // triangles that reached the tile bins (after clipping)
  uint64_t quads_shaded = 0;             // 2x2 quads that ran the fragment program
  uint64_t fragments_shaded = 0;         // covered pixels that ran the fragment program
  uint64_t helper_invocations = 0;       // uncovered quad pixels shaded for derivatives
  uint64_t fragments_depth_failed = 0;
  uint64_t fragments_discarded = 0;
  uint64_t pixels_written = 0;
  uint64_t tiles_rasterized = 0;         // bins with work, per upload segment (Scene::segment)
  void add(const PipelineStats& o);
  bool operator==(const PipelineStats&) const = default;
};

struct Scene {
  TargetView target;
  bool provenance = false;  // track per-pixel intervals (provenance.h); bins use 1-px-wider bboxes
  double edgeMarginSub = 0.0;  // provenance: tolerance::edgeMarginSub of the judged implementation
  double vertexSnapPx = 0.0;   // provenance: tolerance::vertexSnapPx of the judged implementation
  std::vector<std::unique_ptr<DrawState>> states;
  // The set-up triangles, in blocks: one block is one setup sink's output (setup.h), moved in whole
  // rather than copied, since a TriSetup is 472 bytes and a setup-bound frame has millions.
  // reset() returns the blocks to `spareBlocks` with their capacity, so steady frames allocate nothing.
  std::vector<std::vector<TriSetup>> triBlocks;
  std::vector<std::vector<TriSetup>> spareBlocks;
  // Per block of triBlocks (one setup chunk of one draw): what the rasterizer asks of a bin's triangles
  // without reading their TriSetups (a miss to memory each, in a setup-bound frame).
  struct BlockInfo {
    uint32_t drawState;      // every triangle of a block has the draw's state
    uint32_t meanBoxPixels;  // the mean pixel count of its triangles' bounding boxes
  };
  std::vector<BlockInfo> blocks;
  std::vector<ClearCmd> clears;
  int32_t tilesX = 0, tilesY = 0;
  std::vector<std::vector<TileCmd>> bins;
  // PipelineStats::tiles_rasterized counts the bins with work afresh after every texture or buffer
  // upload, as if each upload ended the scene. Uploads used to flush; now only one that unexecuted work
  // reads does (cpu_backend.cpp), and the counter keeps its meaning for any flush policy.
  uint64_t segment = 1;              // advanced by every upload
  std::vector<uint64_t> binSegment;  // per bin: the segment of its last command (0: none since reset)
  bool timeStages = false;  // RenderOptions::stageTimes: stages add their ticks to RastScratch::ticks
  // LOD probe (lod_probe.h): the maps of the target's colour attachment 0, one per layer, or nullptr.
  std::vector<LodMap>* lod = nullptr;

  size_t triangles = 0;  // in triBlocks (appendToScene)

  void begin(const TargetView& t);
  bool empty() const { return triBlocks.empty() && clears.empty(); }
  // Empties the scene for the next one. `keepSegments`: the scene continues the same upload segments
  // (a flush for memory, cpu_backend.cpp), so tiles_rasterized does not count its bins again.
  void reset(bool keepSegments = false);
  const TriSetup& tri(const TileCmd& c) const { return triBlocks[c.index][c.slot]; }
  // Appends c to bin `b`, issued in upload segment `seg`, and counts a bin new to that segment.
  void push(size_t b, const TileCmd& c, uint64_t seg, PipelineStats& stats) {
    bins[b].push_back(c);
    if (binSegment[b] != seg) {
      binSegment[b] = seg;
      ++stats.tiles_rasterized;
    }
  }
  // An empty block for a setup sink to fill: a spare one (with capacity) when there is one.
  // Draws hand them to their sinks before setup (cpu_backend.cpp).
  std::vector<TriSetup> takeSpareBlock();
};


}  // namespace tessera::detail
