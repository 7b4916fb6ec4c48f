// Fixed-function GL state of a replay: the state pinned once per context to the oracle's choices,
// the oracle's initial state at the start of every frame, and one function per state command.
//
// Pinned (docs/gl-backend.md, "Pinning"; docs/spec-choices.md): dithering off (F7), no sRGB
// conversion, no primitive restart (an index 0xffff / 0xffffffff is an ordinary vertex), no depth
// clamp, no polygon offset, no logic op, no stencil, fill mode, the last-vertex provoking
// convention (V6), clip control lower-left with depth -1..1 and depth range [0, 1] (V5), all colour
// channels written, pixel (un)pack alignment 1 (tightly packed rows).
// Internal to gl/.
#pragma once

#include "gl/gl_api.h"
#include "raster/command_list.h"

namespace tessera::gl {

// Once per context, with the context current.
void pinContextState();
// At the start of a frame: the state counters.h calls GL's initial state (viewport and scissor rect
// 0x0, no scissor / depth / blend / culling / clip distances, CCW front faces), every unit of
// 0 .. kMaxTextureUnits-1 without texture and sampler, no program, framebuffer 0.
void resetFrameState();

void applyViewport(const Rect& r);
void applyScissor(const ScissorState& s);
void applyDepth(const DepthState& d);
void applyBlend(const BlendState& b);
void applyRaster(const RasterState& r);

}  // namespace tessera::gl
