// The paging file of a texture atlas tree (docs/mta-format.md): one file holding the node tables,
// the geometry, every node atlas and every original texture, in blocks with SHA-256 checksums.
//
// Implements: a streaming writer (blocks are appended as they are produced to path.tmp-<pid>, the
// metadata and the header last, then renamed) and a reader that validates the header, the metadata
// checksum and every field and cross-reference before returning (paging_file_validation.h; the rules are
// listed in docs/mta-format.md, "Validation"), and verifies each block's checksum when it is read. The
// runtime streams blocks through PagingFile::readBlock.
// Does not implement: building (build.h), rendering or caching policy.
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "base/atomic_file.h"
#include "base/resource_limits.h"
#include "mta/block_encoding.h"
#include "mta/params.h"
#include "mta/scene.h"
#include "mta/tree.h"

namespace tessera::mta {

// 2: every original image starts blocks of its own (version 1 packed several images into one block, so
// loading one image read its neighbours' texels too).
// 3: the header records the block encoding (raw texels or S3TC mip chains, mta/block_encoding.h). Version 1
// and 2 files are refused with a message that says to rebuild them.
constexpr uint32_t kFormatVersion = 3;
constexpr uint32_t kHeaderSize = 128;
// Limits of the format (docs/mta-format.md, "Validation").
constexpr uint32_t kMaxLayers = 16;
// A set of layers, bit l for layer l (kMaxLayers <= 32).
using LayerMask = uint32_t;
static_assert(kMaxLayers <= 32);
constexpr uint32_t kMaxNodeLevel = 60;     // the builder stops splitting there (tree_build.cpp)
constexpr uint32_t kMaxImageSize = 65536;  // width and height of a stored image, as mta::Scene allows
// Triangles over all trees: draws address vertices with 32-bit indices (3 per triangle).
constexpr uint64_t kMaxTriangles = UINT32_MAX / 3;

enum class BlockKind : uint8_t { Atlas = 1, Original = 2 };
const char* blockKindName(BlockKind k);

struct BlockInfo {
  uint64_t offset = 0, size = 0;
  BlockKind kind = BlockKind::Atlas;
  uint8_t tree = 0, layer = 0;  // Atlas: tree and layer
  uint32_t node = 0;            // Atlas: node; Original: the image in the block
  std::array<uint8_t, 32> sha256{};
};

// One image is stored once, top row first, `channels` (3 or 4) bytes per texel, as row ranges (pieces)
// in Original blocks of at most about atlas size that hold nothing else (one piece per block). In an S3TC
// file an image is one piece (all rows) whose block is its encoded mip chain (block_encoding.h).
struct ImageRecord {
  uint32_t width = 0, height = 0, channels = 0;
  uint32_t firstPiece = 0, pieceCount = 0;
  std::string name;
};
struct PieceRecord {
  uint32_t image = 0, block = 0, row0 = 0, rows = 0;
  uint64_t offset = 0;  // byte offset of row row0 inside the block
};

struct BuildStats {
  uint64_t trianglesIn = 0, trianglesOut = 0, criticalAtRequested = 0, criticalAfterRaise = 0, trianglesAdded = 0;
  uint32_t maxSplitDepth = 0;
  double dMinRequested = 0.0, dMinUsed = 0.0, sceneDiagonal = 0.0;
};

// Everything but the block payloads.
struct MtaMeta {
  BuildParams params;  // memoryLimit, threads and progress are not stored
  uint32_t layerCount = 1;
  BlockEncoding encoding = BlockEncoding::Raw;  // stored in the header (version 3)
  BuildStats stats;
  std::vector<SceneTexture> textures;
  std::vector<ImageRecord> images;
  std::vector<PieceRecord> pieces;
  std::vector<BlockInfo> blocks;
  std::vector<Tree> trees;  // 0..2: the RGB tree and / or the RGBA tree (Tree::alpha)
};

class PagingFileWriter {
 public:
  // Writes through an AtomicFile (base/atomic_file.h): path.tmp-<pid> until finish() renames it, removed
  // on destruction, on SIGINT / SIGTERM, or by the next writer of `path` if this process is killed.
  explicit PagingFileWriter(std::string path);  // throws Error on failure
  ~PagingFileWriter();
  PagingFileWriter(const PagingFileWriter&) = delete;
  PagingFileWriter& operator=(const PagingFileWriter&) = delete;
  // Appends a block (16-byte aligned) and returns its index.
  uint32_t addBlock(BlockKind kind, uint8_t tree, uint8_t layer, uint32_t node, std::span<const uint8_t> bytes);
  uint64_t bytesWritten() const { return end_; }
  // meta.blocks is replaced by the blocks added. Writes metadata and header, then renames.
  void finish(MtaMeta& meta);

 private:
  std::string path_;
  AtomicFile file_;
  uint64_t end_ = kHeaderSize;
  std::vector<BlockInfo> blocks_;
};

// The metadata bytes of `meta`, as PagingFileWriter::finish stores them (docs/mta-format.md, "Metadata").
// Public for tools and tests that rewrite a file's metadata; nothing is checked.
std::vector<uint8_t> encodeMetadata(const MtaMeta& meta);
// encodeMetadata(meta).size() if meta held `pieces` pieces and `blocks` blocks, computed from the counts
// without encoding (the size estimate of a build, output_size.h, calls it before any block exists).
uint64_t metadataBytes(const MtaMeta& meta, uint64_t pieces, uint64_t blocks);

class PagingFile {
 public:
  // Reads and validates the header and the metadata: checksums, sizes, and every field a consumer relies
  // on (paging_file_validation.h), within `limits` (mtaLeafBlockRefs). Throws Error naming the file, the
  // field and the reason: "<file>: <record>[<index>].<field>: <reason>".
  explicit PagingFile(std::string path, const ResourceLimits& limits = {});
  ~PagingFile();
  PagingFile(const PagingFile&) = delete;
  PagingFile& operator=(const PagingFile&) = delete;
  const MtaMeta& meta() const { return meta_; }
  uint64_t fileSize() const { return fileSize_; }
  // The payload of block i, checksum verified (Error on mismatch or I/O failure). Thread-safe (pread).
  std::vector<uint8_t> readBlock(uint32_t index) const;
  // Image i reassembled from its pieces (top row first, channels bytes per texel); in an S3TC file its
  // level 0 decoded (raster/bc_decode.h).
  std::vector<uint8_t> readImage(uint32_t image) const;
  // The atlas texels of (tree, node, layer): A x A x channels (S3TC: level 0 decoded).
  std::vector<uint8_t> readAtlas(uint32_t tree, uint32_t node, uint32_t layer = 0) const;

 private:
  void load(const ResourceLimits& limits);  // the header and the metadata, validated
  std::string path_;
  int fd_ = -1;
  uint64_t fileSize_ = 0;
  MtaMeta meta_;
};

}  // namespace tessera::mta
