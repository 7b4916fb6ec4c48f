// Recording an atlas tree frame as a CommandList, so that every texture bind, state change and draw is
// counted exactly (raster/counters.h) and the oracle renders it.
//
// Implements: the frame's resources (one RGBA8 colour target and a D32F depth target, the runtime
// vertex array, one texture with a full mip chain per texture bound this frame, the samplers, all before
// the first draw) and its commands in plan order (TreeRenderer groups the plan by texture first,
// draw_order.h): an atlas draw binds the node's atlas, sets the texture matrix diag(2^level) (§4.5.4,
// REPEAT addressing) and draws root-atlas texcoords; an original draw binds the scene texture with its
// wrap modes and the identity matrix and draws the original texcoords; the dummy run uses a 1x1 white
// texture, untextured triangles the same with a grey tint (slot 7). A file with a layer 1 (§5.1.3) is
// drawn with program "textured_layers" instead, layer 1 on unit 1 (spec choice F13): an atlas draw binds
// the node's layer-1 atlas with the same texture matrix and coordinates (the layers share the atlas
// parameterization, runtime_geometry.h), an original draw the triangles' layer-1 texture with its wrap
// modes and texcoords, and every other draw (no layer-1 texture, white, untextured) the 1x1 white
// texture, whose factor is exactly 1, so those pixels equal "textured"'s. Slot 12 = (1, 1): strength 1
// and the R-only mode, because layer 1 is glTF's occlusionTexture (sceneFromModel), whose G and B may
// hold other data (ORM packing). The strength is 1 because the paging file does not store glTF's
// occlusion strength (one per material, where the tree keeps textures per triangle); every occlusion
// map this project makes (`tessera city --light-map`) has strength 1. Filtering is trilinear everywhere
// (LINEAR_MIPMAP_LINEAR), mip chains come from the documented box filter (raster/texture.h). Alpha is not
// tested or blended: the thesis's comparison runs did the same (§4.7.2) so that texture content cannot
// change the frame cost.
// The id variant draws the same triangles with "object_id" into two R32UI targets: attachment 0 holds
// the global triangle index (runtime_geometry.h), 0xffffffff where nothing was drawn.
// Does not implement: choosing draws (traversal.h), the mip chains of the textures it uploads
// (texture_cache.h), executing (raster/cpu_backend.h).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "mta/paging_file.h"
#include "mta/runtime_geometry.h"
#include "mta/texture_cache.h"
#include "mta/traversal.h"
#include "raster/command_list.h"

namespace tessera::mta {

// The layers recordFrame samples: layer 0 (the atlases' layout layer and the originals' base colour) and
// layer 1 where the file has it. The memory manager and the traversals request the blocks of these layers
// only (TreeRenderer; buildBlockIndex ignores the bit of a layer the file lacks, so a one-layer file is
// paged as before). Layers >= 2 are not drawn ("textured_layers" combines two) and so not requested.
constexpr LayerMask kRecordedLayers = 0b11;
// Whether recordFrame draws layer 1 for this file.
inline bool recordsLayer1(const MtaMeta& meta) { return meta.layerCount > 1 && (kRecordedLayers & 2) != 0; }

struct RecordParams {
  uint32_t width = 1024, height = 768;
  std::array<float, 4> clear{0.62f, 0.74f, 0.88f, 1.0f};  // sky
  bool idFrame = false;
};

// Every texture the frame bound, for the texel analysis: what unit 0 held at each planned draw.
struct BoundTexture {
  uint32_t width = 0, height = 0, levels = 0;
  double scale = 1.0;  // texture matrix scale (2^level for atlases)
};

struct RecordedFrame {
  CommandList list;
  std::vector<BoundTexture> drawTexture;  // per PlannedDraw
};

RecordedFrame recordFrame(const MtaMeta& meta, const RuntimeGeometry& geometry, const FramePlan& plan, const ViewParams& view,
                          TextureCache& textures, const RecordParams& params);
// The same, recorded into `out` (cleared first), whose storage is reused: TreeRenderer records every
// frame into one RecordedFrame, so a frame's uploads cost one copy and no allocation once the blob
// has grown to the largest frame's size.
void recordFrame(const MtaMeta& meta, const RuntimeGeometry& geometry, const FramePlan& plan, const ViewParams& view,
                 TextureCache& textures, const RecordParams& params, RecordedFrame& out);

}  // namespace tessera::mta
