// Semantic validation of a CommandList: simulates resource creation and bound state through the
// list and reports everything a backend would have to reject or could only execute with undefined
// or implementation-dependent results.
//
// Checks, in command order (each diagnostic names the command index):
// - resource ids: unknown, wrong kind, 0 where a resource is needed, duplicate or out-of-order
//   creation (ids are one dense space shared by all kinds, handed out in creation order);
// - texture descriptions (sizes, layers, levels, Buffer-kind rules), texture / buffer uploads
//   (size, level, layer, range), blob ranges;
// - texture units, uniform slots, sampler filters and LOD values, vertex layouts;
// - viewports, scissors, render targets (renderable formats, equal sizes, level / layer), clears;
// - draws: program, vertex buffer, layout, target and index buffer present; indices inside the
//   index buffer; every attribute fetch of every referenced vertex inside the vertex buffer; no
//   NaN / Inf in the position attribute (location 0) and no U32 attribute value >= 2^24;
// - the frame's memory: every level and layer of every texture (render targets are textures too) and
//   the declared size of every buffer, summed with overflow-checked arithmetic, against
//   ResourceLimits::frameBytes (base/resource_limits.h, docs/limits.md). A backend allocates exactly
//   these, so a list that passes cannot make one allocate more than the budget (plus its own working
//   memory: tile bins, and in provenance mode two more copies of each texture).
// Buffer contents at a draw are the uploads recorded before it, applied in order over zeros.
// Does not implement: checks that need program internals (which units or outputs a program uses).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "base/resource_limits.h"
#include "raster/command_list.h"

namespace tessera {

struct Diagnostic {
  size_t command;  // index into CommandList::commands()
  std::string message;
};

// All problems, in command order. Empty for a valid list. Linear in the commands plus the vertices
// and indices the draws reference. Allocates nothing in proportion to the sizes the list declares.
// A frame over limits.frameBytes gets one diagnostic, on the command whose resource first takes the
// running total over the budget: "frame: needs <total of the whole frame>, over the limit of <budget>
// by <excess> (raise it with --memory-budget)" (overLimitMessage). A texture whose description is
// invalid is not counted (it has no meaningful size and is reported already); a buffer counts with its
// declared size even when that is over the per-buffer limit.
std::vector<Diagnostic> validate(const CommandList& list, const ResourceLimits& limits = {});

// Throws Error "<frameName>: N problem(s)" followed by the first 10 diagnostics, one per line, as
// "command N (Kind): message".
void validateOrThrow(const CommandList& list, std::string_view frameName, const ResourceLimits& limits = {});

}  // namespace tessera
