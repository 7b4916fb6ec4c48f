// The size of a paging file, known from the build plan before anything is written.
//
// Implements: the one place that knows how blocks are encoded and laid out: the bytes of one atlas block
// (raw A × A × channels, or the S3TC mip chain of block_encoding.h), how
// original images are cut into row pieces in blocks of their own of at most about A² · 4 bytes (OriginalBlockLayout, which the
// builder's packer uses itself, so the two cannot drift), and the file's exact size: the 128-byte header,
// every block padded to 16 bytes, and the metadata (metadataBytes, paging_file.h). The estimate is exact,
// not a bound: tests compare it with the files the builder writes.
// Does not implement: the plan (build_plan.h), the limit or the choice of d_min (output_budget.h).
#pragma once

#include <cstdint>

#include "mta/build_plan.h"

namespace tessera::mta {

// Payload bytes of one stored atlas of an A x A tree with `channels` (3: RGB tree, 4: RGBA tree).
uint64_t atlasBlockBytes(uint32_t atlasSize, uint32_t channels, BlockEncoding encoding);
// The fill at which an Original block is closed: about one RGBA atlas (A² · 4 bytes).
uint64_t originalBlockTarget(uint32_t atlasSize);

// Cuts images, one after the other, into row ranges (pieces) of blocks of about `target` bytes. Every
// image starts a block of its own (format version 2), so that loading one image never reads another's
// texels (§4.6: a block is "an original texture of a leaf node", split only when it is large). A piece
// takes as many whole rows as fit the current block (at least one), and a block is closed when the image
// ends or its next row would not fit (so a row longer than `target` gets a block of its own). Hence every
// block holds exactly one piece.
class OriginalBlockLayout {
 public:
  explicit OriginalBlockLayout(uint64_t target) : target_(target) {}
  struct Piece {
    uint64_t closedBlockBytes = 0;  // > 0: the current block (that many bytes) is closed before this piece
    uint32_t rows = 0;              // rows in this piece
    uint64_t offset = 0;            // byte offset of the piece in its block (always 0 since version 2)
  };
  // The next piece of an image with `rowsLeft` (>= 1) rows of `rowBytes` (>= 1) bytes still to place;
  // `firstOfImage`: the image's first piece, which closes the block the previous image left open.
  Piece next(uint32_t rowsLeft, uint64_t rowBytes, bool firstOfImage);
  uint64_t fill() const { return fill_; }  // bytes in the open block (0: none open)

 private:
  uint64_t target_, fill_ = 0;
};

struct OutputEstimate {
  uint64_t nodes = 0, leaves = 0;
  uint64_t atlasBlocks = 0, atlasBytes = 0;        // payloads, each padded to 16 bytes
  uint64_t originalBlocks = 0, originalBytes = 0;  // likewise
  uint64_t pieces = 0;
  uint64_t metadataBytes = 0;
  uint64_t totalBytes = 0;  // header + atlasBytes + originalBytes + metadataBytes: the file's size
};

// The exact size of the file `plan` builds. Blocks start at 16-byte boundaries after the 128-byte header
// and the metadata follows the last one at a 16-byte boundary, so each block counts as its payload rounded
// up to 16, whatever the order of the blocks. Overflow is impossible for any plan that fits in memory
// (nodes · layers · 256 MiB per atlas at A = 8192 stays far below 2^64).
OutputEstimate estimateOutput(const BuildPlan& plan);

}  // namespace tessera::mta
