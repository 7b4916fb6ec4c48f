// Recording one frame of render-to-texture-atlas and its two baselines as CommandLists (Trapp &
// Döllner 2010, §3 and Table 1). Same camera, same objects, same colours in every mode:
// - STD:  the scene drawn once to the screen with `textured` (one draw per run of meshes sharing a
//         texture and a base-colour factor, in the scene's texture order).
// - RTT:  one off-screen pass per object into its own viewport-sized layer of an n-layer array (the
//         paper does not spell RTT out; docs/rtta.md gives this reading): per object a render-target
//         change, clears, and its meshes drawn with `atlas_capture` under identity records (no
//         displacement), then the composite.
// - RTTA: Algorithm 1 (parameterize.h, packing.h, transform.h), the record buffer, one capture pass
//         into the layered atlas (colour RGBA8, window depth RG32F, D32F), viewport (0, 0, Tw, Th), four
//         clip planes on the undisplaced position, one bind and one draw per texture (`--texturing
//         bind`, program atlas_capture), then the composite.
// Composites (Fig. 3), all from the capture's colour and depth by `atlas_sprite`, two triangles per
// visible object covering its B_viewport (T⁻¹ of B_atlas: a whole-pixel shift), objects in id order:
// - depth (3A):       depth test LESS with the captured window depth as fragment depth: the plain
//                     rendering again, up to depth ties between objects (docs/rtta.md);
// - transparent (3B): no depth test, every object blended (SRC_ALPHA, ONE_MINUS_SRC_ALPHA) with alpha
//                     kTransparentAlpha, back to front: distance from the eye to the centre of B_world
//                     descending, ties by id;
// - ghosted (3C):     the important objects first, opaque with depth test and a highlight tint, then the
//                     others blended back to front with alpha kGhostAlpha and no depth test;
// - ghosted-ao (3D):  ghosted, but the important objects are drawn by `atlas_sprite_ao`: ambient
//                     occlusion and edge enhancement computed on each one's own atlas region (the
//                     border, at least programs::kAoRadius, keeps the kernel off its neighbours), with
//                     a bias and an edge step derived from the object's window-depth span.
// Resources are created and uploaded before the first draw of the frame. Filtering is trilinear.
// `--texturing tab` needs the scene's TAB output batches (batching::runAlgorithm1, then
// refreshTamIndices); its TAMs are written with opaque materials, as bind draws them.
// `atlasInput` replaces the capture by uploaded atlas images (for judging the post-process on another
// renderer's capture, docs/rtta.md "ghosted-ao").
// Does not implement: executing, choosing cameras.
#pragma once

#include <array>
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "raster/command_list.h"
#include "rtta/packing.h"
#include "rtta/parameterize.h"
#include "rtta/rtta_scene.h"

namespace tessera::rtta {

enum class Mode : uint8_t { Std = 0, Rtt = 1, Rtta = 2 };
enum class Composite : uint8_t { Depth = 0, Transparent = 1, Ghosted = 2, GhostedAo = 3 };
// How the RTTA capture gets its texels: bind (one bind and one draw per texture, atlas_capture) or tab
// (TAB's output batches: per batch its arrays and TAM bound, one draw per geometry batch,
// atlas_capture_tab; the meshes TAB does not batch are drawn as with bind afterwards).
enum class Texturing : uint8_t { Bind = 0, Tab = 1 };
const char* modeName(Mode m);
const char* texturingName(Texturing t);
const char* compositeName(Composite c);

inline constexpr float kTransparentAlpha = 0.5f;
inline constexpr float kGhostAlpha = 0.25f;
inline constexpr std::array<float, 4> kHighlightTint{1.0f, 0.75f, 0.5f, 1.0f};
// ghosted-ao: the occlusion bias and the edge step are these fractions of the important object's
// window-depth span (its B_world corners' z_w, clamped to [0, 1]); the factor for k occluding kernel
// pairs of 4 is 1 - k / 8 (exact in float); edges are drawn in kEdgeColor.
inline constexpr double kAoBiasFraction = 1.0 / 512.0;
inline constexpr double kAoEdgeFraction = 1.0 / 16.0;
inline constexpr std::array<float, 4> kEdgeColor{0.0f, 0.0f, 0.0f, 1.0f};
// The atlas colour clear: alpha 0 is the reserved "no object here" value that border texels keep.
inline constexpr std::array<float, 4> kAtlasClear{0.0f, 0.0f, 0.0f, 0.0f};
// The depth attachment's clear (RG32F): (far, not covered).
inline constexpr std::array<float, 4> kAtlasDepthClear{1.0f, 0.0f, 0.0f, 0.0f};

struct RttaView {
  glm::mat4 mvp{1.0f};
  glm::dvec3 eye{0.0};
  uint32_t width = 1024, height = 1024;
  std::array<float, 4> clear{0.62f, 0.74f, 0.88f, 1.0f};
};

// A captured atlas given as images instead of rendered: per layer, level 0, rows bottom first, in the
// capture's formats (colour RGBA8, window depth RG32F). Layer count and size must be the frame's.
struct AtlasImages {
  std::vector<std::vector<uint8_t>> color, depth;
};

struct RttaOptions {
  Mode mode = Mode::Rtta;
  Composite composite = Composite::Depth;
  Texturing texturing = Texturing::Bind;    // RTTA's capture only (RTT always binds)
  int32_t atlasWidth = 0, atlasHeight = 0;  // 0: the smallest power of two >= viewport + 2 border
  ParamOptions params;
  uint32_t allocatedLayers = 0;             // layers of the atlas texture (LayerAllocator); 0 = Td
  std::vector<uint32_t> important;          // ghosted: object ids; empty = the largest B_viewport
  bool captureOnly = false;                 // RTT / RTTA: end the frame on the capture target
  const AtlasImages* atlasInput = nullptr;  // RTTA: upload these instead of capturing (no capture pass)
};

struct RttaFrame {
  CommandList list;
  std::vector<Record> records;  // RTTA: packed; RTT and STD: parameterized only (for reports)
  AtlasSize atlas;              // RTTA: Tw x Th x Td; RTT: W x H x objects drawn
  uint32_t allocatedLayers = 0;
  size_t inexactTransforms = 0;
  uint64_t targetBytes = 0;     // bytes of every off-screen target (colour, depth-as-colour, depth)
  std::vector<uint32_t> important;
  ResourceId screen = kNone, screenDepth = kNone, captureColor = kNone, captureDepth = kNone;
};

// The default atlas side for a viewport side: the smallest power of two >= side + 2 border.
int32_t defaultAtlasSide(int32_t viewportSide, int32_t border);

RttaFrame recordRttaFrame(const RttaScene& scene, const RttaView& view, const RttaOptions& options);

}  // namespace tessera::rtta
