// Visibility for any frame: rewrites a frame whose presented target was not drawn with the
// "object_id" program into one that is, with the same geometry and the same state, so that
// castVisibility() can check it (docs/visibility.md, "Frames not drawn with object_id").
//
// Implements: for every draw to the presented target, the position attribute (location 0) of every
// vertex it reads is fetched (vertex_fetch.h, indices resolved) into a new vertex buffer together
// with the object id = the draw's index in the frame (every Draw command counts, from 0, as the
// cross-check's bisection counts them); the draw then runs "object_id" with the original program's
// MVP (uniform slots 0-3) as a non-indexed draw of the same vertices in the same order, so
// gl_PrimitiveID and the provoking vertex are unchanged. User clip planes go along: a vertex_color
// draw's planes (slots 8-15) become object_id's (the same expression); other programs write no clip
// distances, so object_id gets zero planes. The presented target becomes two R32UI
// attachments (object id, primitive id) and a D32F depth attachment, cleared to 0xffffffff and 1.0
// when it is first bound. Viewport, scissor, culling, winding and clip mask stay. Depth: a draw whose
// depth state is not "test on, writes on, LESS or LEQUAL" gets LESS with writes on (the nearest
// surface wins, the earlier one on a tie), since that is what visibility checks; blending is off
// (integer targets). Draws to other targets and every other command are kept, with resource ids
// renumbered (the new resources are created first).
// Does not implement: programs whose geometry stage moves vertices (atlas_displace) or layered
// presented targets: both are refused with an Error naming the command.
#pragma once

#include "base/resource_limits.h"
#include "raster/command_list.h"

namespace tessera::verify {

// True when some draw to the presented target uses a program other than "object_id".
bool needsObjectIdRewrite(const CommandList& list);

// The rewritten frame, or a copy of `list` when needsObjectIdRewrite() is false. Validates `list`
// first (validateOrThrow against `limits`, naming `frameName`).
CommandList rewriteToObjectIds(const CommandList& list, std::string_view frameName = "visibility",
                               const ResourceLimits& limits = {});

}  // namespace tessera::verify
