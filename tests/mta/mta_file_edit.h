// Hostile paging files for the mta tests: a valid file with one metadata field changed and both checksums
// recomputed, so that the edit reaches the validator instead of stopping at a checksum mismatch.
#pragma once

#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "base/sha256.h"
#include "mta/paging_file.h"

namespace tessera::mta::testing {

inline std::vector<uint8_t> readBytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(f), {});
}

inline void writeBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

inline uint64_t metadataOffset(const std::vector<uint8_t>& file) {
  uint64_t off = 0;
  std::memcpy(&off, file.data() + 24, 8);
  return off;
}

// Makes the header agree with the bytes (docs/mta-format.md, "Header"): file size, metadata size, the
// metadata's SHA-256 and the header's own SHA-256.
inline void fixHeader(std::vector<uint8_t>& file) {
  const uint64_t size = file.size(), off = metadataOffset(file), metaSize = size - off;
  std::memcpy(file.data() + 16, &size, 8);
  std::memcpy(file.data() + 32, &metaSize, 8);
  const auto ms = sha256(std::span<const uint8_t>(file).subspan(size_t(off)));
  std::memcpy(file.data() + 40, ms.data(), 32);
  const auto hs = sha256(std::span<const uint8_t>(file.data(), 96));
  std::memcpy(file.data() + 96, hs.data(), 32);
}

// Writes `out`: the valid paging file `in` with its decoded metadata changed by `edit`, re-encoded
// (encodeMetadata), and the header fixed. The block payloads are kept byte for byte.
inline void rewriteMetadata(const std::string& in, const std::string& out, const std::function<void(MtaMeta&)>& edit) {
  MtaMeta meta = PagingFile(in).meta();
  edit(meta);
  std::vector<uint8_t> file = readBytes(in);
  file.resize(size_t(metadataOffset(file)));
  const std::vector<uint8_t> body = encodeMetadata(meta);
  file.insert(file.end(), body.begin(), body.end());
  fixHeader(file);
  writeBytes(out, file);
}

// The same with the metadata's bytes edited directly (for what MtaMeta cannot hold: a layer count that
// does not match the arrays, a block's padding byte).
inline void rewriteMetadataBytes(const std::string& in, const std::string& out,
                                 const std::function<void(std::vector<uint8_t>& metadata)>& edit) {
  std::vector<uint8_t> file = readBytes(in);
  const size_t off = size_t(metadataOffset(file));
  std::vector<uint8_t> body(file.begin() + std::ptrdiff_t(off), file.end());
  edit(body);
  file.resize(off);
  file.insert(file.end(), body.begin(), body.end());
  fixHeader(file);
  writeBytes(out, file);
}

// Byte offset, inside the metadata, of the first block directory record (docs/mta-format.md, "Metadata").
inline size_t blockDirectoryOffset(const MtaMeta& m) {
  size_t p = 4 * 4 + 6 * 8;  // parameters
  p += 5 * 8 + 4 + 3 * 8;    // stats
  p += 4 + 6 * m.textures.size();
  p += 4;
  for (const ImageRecord& r : m.images) p += 5 * 4 + 4 + r.name.size();
  p += 8 + 24 * m.pieces.size();
  return p + 8;
}

}  // namespace tessera::mta::testing
