// The order in which a frame's planned draws are recorded: grouped by the texture they bind.
//
// planFrame (traversal.h) emits draws leaf by leaf in the traversal's depth-first order, so a leaf drawn
// with its original textures binds them again although a leaf before it bound the same ones: railway.glb
// (28 textures) bound up to 228 textures a frame. groupDrawsByTexture reorders the plan so that every
// draw of one texture follows the first draw that binds it:
// - a draw's texture key is the node atlas it binds (tree, node; on a file with a layer 1 the node's
//   layer-1 atlas comes with it), the pair of scene textures of an original draw (layer 0's and layer
//   1's, which the recorder binds on units 0 and 1: keying by layer 0 alone would merge draws that need
//   different light maps), or the white texture (the dummy run's, and separately the grey-tinted
//   untextured triangles');
// - keys keep the order in which the traversal first drew them, and inside a key the draws keep the
//   traversal's order (a stable sort by the rank of first appearance), so the result is a function of
//   the plan alone;
// - a draw whose triangle range continues the previous draw of its key is merged into it (leaves are
//   contiguous in runtime_geometry.h's layout, so the last run of a leaf and the first run of the next
//   leaf often share a texture). A merged original draw keeps the first leaf in PlannedDraw::node.
// Then the recorder (which binds only when the unit's binding changes) binds each texture once: at most
// one bind per node drawn with its atlas plus one per distinct original texture, plus the white texture
// (with a layer 1, unit 1 likewise binds once per distinct atlas, pair or white).
//
// Why the image stays correct: frames are opaque, with the depth test on (LESS, writes on) and neither
// blending nor alpha test (frame_recorder.h). A pixel's final depth is then the least depth of all its
// fragments whatever the order, and its colour is that of the first fragment drawn at that depth. The
// same triangles are drawn with the same state, so reordering can only change a pixel where two
// fragments tie at the least depth (coplanar overlapping triangles), and the depth buffer never changes.
//
// Does not implement: choosing the draws (traversal.h), recording them (frame_recorder.h).
#pragma once

#include "mta/traversal.h"

namespace tessera::mta {

// Reorders and merges plan.draws as above; the counters of the plan (nodes, leaves, triangles) are
// unchanged, and every triangle drawn before is drawn exactly once after. Idempotent.
void groupDrawsByTexture(FramePlan& plan);

// The number of distinct texture keys among plan.draws (as above): once grouped, the frame binds at most
// this many textures on unit 0, and at most this many on unit 1.
uint32_t textureKeyCount(const FramePlan& plan);

}  // namespace tessera::mta
