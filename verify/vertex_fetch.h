// Vertex attribute fetch and index reads for the visibility oracle, written from the attribute
// rules (GL 4.6 §10.2, docs/spec-choices.md V7) rather than shared with the CPU backend, so that a
// fetch bug in one of them shows up as a disagreement instead of being copied.
//
// Rules: every location starts as (0, 0, 0, 1); an enabled attribute (components 1..4, location
// below kMaxAttribs) overwrites its first `components` lanes from
// buffer[index * stride + offset + 4k]; F32 lanes are the bytes' float, U32 lanes are the integer
// converted to float (exact below 2^24, which validation guarantees).
// Does not implement: buffer state tracking (visibility_scene.cpp keeps the bytes).
#pragma once

#include <cstdint>
#include <span>

#include "raster/program.h"
#include "raster/types.h"

namespace tessera::verify {

// Throws Error when a read would leave `vertexBytes` (a validated list never does).
void fetchVertex(std::span<const uint8_t> vertexBytes, const VertexLayout& layout, uint32_t index, VertexIn& out);

// Index `i` of an index buffer of the given type (little-endian). Throws Error when out of range.
uint32_t readIndex(std::span<const uint8_t> indexBytes, IndexType type, uint64_t i);

}  // namespace tessera::verify
