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

// The 3.3 path edits textures through bind points: it binds them on this unit, which no program
// samples (units 0 .. kMaxTextureUnits-1 are the command list's; GL 3.3 guarantees 48 combined
// units), and leaves it active between commands.
inline constexpr int kScratchUnit = kMaxTextureUnits;

// Once per context, with the context current. `dsa`: the 4.5 path; the 3.3 path skips the state
// that GL 3.3 does not have (fixed-index primitive restart, sample shading, clip control), whose
// 3.3 behaviour is the pinned one already.
void pinContextState(bool dsa);
// At the start of a frame: the state counters.h calls GL's initial state (viewport and scissor rect
// 0x0, no scissor / depth / blend / culling / clip distances, CCW front faces), every unit of
// 0 .. kMaxTextureUnits-1 without texture and sampler, no program, framebuffer 0.
void resetFrameState(bool dsa);
// Unbinds every texture target and sampler of units 0 .. kMaxTextureUnits-1 (glBindTextures /
// glBindSamplers with DSA, one target at a time on the 3.3 path).
void unbindAllUnits(bool dsa);
// Binds texture `name` of `target` on `unit`; name 0 unbinds every target of the unit.
void bindTextureOnUnit(bool dsa, int unit, GLenum target, GLuint name);

void applyViewport(const Rect& r);
void applyScissor(const ScissorState& s);
void applyDepth(const DepthState& d);
void applyBlend(const BlendState& b);
void applyRaster(const RasterState& r);

}  // namespace tessera::gl
