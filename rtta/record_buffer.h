// The record buffer of Trapp & Döllner 2010 (§3): the per-frame encoding of every record R_ID that
// the capture program (atlas_displace / atlas_capture: unit 0, an RGBA32F buffer texture) reads by
// object id, and that post-processing and compositing share.
// Layout, two RGBA32F texels per object id: texel 2 id = (a, b, c, d), the linear part of T; texel
// 2 id + 1 = (tx, ty, layer, 0). A record without a layer (culled) stores layer -1, which the
// programs treat as "drop the object" (they accept only 0 <= layer < 65536).
// Does not implement: B_world / B_viewport / B_atlas on the GPU side (compositing gets its sprite
// rectangles as vertices, built on the CPU from the same records).
#pragma once

#include <span>
#include <vector>

#include "rtta/record.h"

namespace tessera::rtta {

// 8 floats per record, in id order (records[i].id must be i).
std::vector<float> encodeRecordBuffer(std::span<const Record> records);

}  // namespace tessera::rtta
