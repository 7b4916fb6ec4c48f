// The .tab file of a batched scene (docs/tab-format.md): one file holding a TabScene (tab_scene.h):
// parameters, textures with their full mip chains, texture arrays, output batches with their TAMs and
// geometry batches, meshes and vertices, in seven checksummed sections after a checksummed header.
//
// Implements: writeTabFile (validates the scene, then streams the sections through an AtomicFile and
// writes the header last, so a half-written file never carries the final name and the same scene always
// gives the same bytes), encodeTabFile (the same bytes in memory, unchecked, for tests and tools that
// build hostile files), and readTabFile, which treats the file as hostile: header, section table and
// checksums first, every count and size against the bytes present before anything is allocated, then
// every field and cross-reference (validateTabScene, tab_file_validation.cpp). Every refusal is an Error
// "<file>: <field>: <reason>".
// Does not implement: building a scene (batcher.h) or drawing it (tab_record.h); random access to one
// texture (the reader returns the whole scene).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/resource_limits.h"
#include "batching/tab_scene.h"

namespace tessera::batching {

constexpr uint32_t kTabFormatVersion = 1;
// The sections, in file order; the section table lists each exactly once, in this order.
enum class TabSection : uint32_t {
  Meta = 1,
  Textures = 2,
  Texels = 3,
  Arrays = 4,
  Batches = 5,
  Meshes = 6,
  Vertices = 7
};
constexpr uint32_t kTabSectionCount = 7;
// magic 8, version 4, header size 4, section count 4, reserved 4, file size 8; 7 x (kind 4, reserved 4,
// offset 8, size 8, SHA-256 32); SHA-256 of everything before it.
constexpr uint32_t kTabHeaderSize = 32 + kTabSectionCount * 56 + 32;  // 456

// Validates `scene` (validateTabScene, naming `path` in errors), then writes it atomically: Error naming
// `path` when the scene is invalid or the file cannot be written; then nothing is left under `path` or
// beside it.
void writeTabFile(const TabScene& scene, const std::string& path);

// The bytes writeTabFile writes for `scene`, without validating it (for tests and fuzz seeds).
std::vector<uint8_t> encodeTabFile(const TabScene& scene);

// Reads and validates a .tab file. The total texel bytes are held to limits.modelTextureBytes and the
// vertices to limits.modelVertices (docs/limits.md). Throws Error "<path>: <field>: <reason>".
TabScene readTabFile(const std::string& path, const ResourceLimits& limits = {});

// Every rule of docs/tab-format.md, "What the reader checks", that concerns the decoded scene: ranges of
// the parameters, enum values, finite floats, mip chains, and every cross-reference between textures,
// arrays, batches, TAM entries, geometry batches, meshes and vertices. Throws Error "<path>: <field>:
// <reason>" for the first violation. Used by readTabFile and writeTabFile; public for the batcher's tests.
void validateTabScene(const TabScene& scene, const std::string& path);

}  // namespace tessera::batching
