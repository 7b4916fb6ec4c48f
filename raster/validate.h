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
//   NaN / Inf in the position attribute (location 0) and no U32 attribute value >= 2^24.
// Buffer contents at a draw are the uploads recorded before it, applied in order over zeros.
// Does not implement: checks that need program internals (which units or outputs a program uses).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "raster/command_list.h"

namespace tessera {

struct Diagnostic {
  size_t command;  // index into CommandList::commands()
  std::string message;
};

// All problems, in command order. Empty for a valid list. Linear in the commands plus the vertices
// and indices the draws reference.
std::vector<Diagnostic> validate(const CommandList& list);

// Throws Error "<frameName>: N problem(s)" followed by the first 10 diagnostics, one per line, as
// "command N (Kind): message".
void validateOrThrow(const CommandList& list, std::string_view frameName);

}  // namespace tessera
