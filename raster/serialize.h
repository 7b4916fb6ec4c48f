// The .tframe file: a CommandList as bytes (docs/tframe-format.md is the normative description).
//
// Implements: a versioned, little-endian, checksummed encoding of every command and the blob, a
// decoder that trusts nothing (every size, enum, range and string is checked before use, so a
// truncated or hostile file yields an Error naming the file, byte offset, command and field, and
// never a crash, a hang or an allocation larger than the file), and atomic file writes.
// Does not implement: semantic validation of the frame (validate.h) — a decoded list may still
// refer to unknown resources; it is only guaranteed to be well-formed.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "raster/command_list.h"

namespace tessera {

constexpr char kFrameMagic[8] = {'T', 'S', 'F', 'R', 'A', 'M', 'E', '\0'};
// Version 2 adds desc.compression to CreateTexture (S3TC textures). A list without a compressed texture
// is still written as version 1, byte for byte as before (so existing files, repros and byte snapshots
// stay valid); a list with one is written as version 2. The decoder reads both.
constexpr uint32_t kFrameVersion = 2;
constexpr uint32_t kFrameOldestVersion = 1;
constexpr uint32_t kFrameHeaderSize = 72;        // magic 8 + version 4 + header size 4 + 3 x u64 + sha 32
constexpr uint32_t kFrameMaxStringBytes = 4096;  // program names and marker texts

// Throws Error if the list cannot be represented (a string longer than kFrameMaxStringBytes, an
// out-of-range enum, a blob range outside the blob). The file's next id is 1 + the highest created
// id, whatever list.nextId() says (they differ only for lists cut short or built with appendRaw).
std::vector<uint8_t> encodeFrame(const CommandList& list);
// `sourceName` prefixes every error message (usually the file name).
CommandList decodeFrame(std::span<const uint8_t> bytes, std::string_view sourceName);

// Writes `path + ".tmp-<pid>"`, fsyncs it and renames it over `path`, so `path` is either the old
// file or the complete new one. On failure the temporary file is removed and an Error naming the
// path is thrown.
void writeFrame(const CommandList& list, const std::string& path);
CommandList readFrame(const std::string& path);

}  // namespace tessera
