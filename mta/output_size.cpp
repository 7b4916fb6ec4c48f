#include "mta/output_size.h"

#include <algorithm>

namespace tessera::mta {

namespace {

uint64_t padded(uint64_t bytes) { return (bytes + 15) & ~uint64_t(15); }

}  // namespace

uint64_t atlasBlockBytes(uint32_t atlasSize, uint32_t channels, BlockEncoding encoding) {
  if (encoding == BlockEncoding::S3tc) return s3tcChainBytes(atlasSize, atlasSize, channels);
  return uint64_t(atlasSize) * atlasSize * channels;
}

uint64_t originalBlockTarget(uint32_t atlasSize) { return uint64_t(atlasSize) * atlasSize * 4; }

OriginalBlockLayout::Piece OriginalBlockLayout::next(uint32_t rowsLeft, uint64_t rowBytes, bool firstOfImage) {
  Piece p;
  if ((firstOfImage || fill_ + rowBytes > target_) && fill_ != 0) p.closedBlockBytes = fill_, fill_ = 0;
  // fill_ <= target_ here unless the block is empty (one over-long row), so the subtraction cannot wrap.
  p.rows =
      uint32_t(std::min<uint64_t>(rowsLeft, std::max<uint64_t>(1, (target_ - std::min(fill_, target_)) / rowBytes)));
  p.offset = fill_;
  fill_ += uint64_t(p.rows) * rowBytes;
  return p;
}

OutputEstimate estimateOutput(const BuildPlan& plan) {
  const MtaMeta& m = plan.meta;
  OutputEstimate e;
  e.nodes = plan.nodes, e.leaves = plan.leaves;
  for (const Tree& t : m.trees) {
    e.atlasBlocks += uint64_t(t.nodes.size()) * m.layerCount;
    e.atlasBytes += uint64_t(t.nodes.size()) * m.layerCount * padded(atlasBlockBytes(m.params.atlasSize, t.channels(), m.encoding));
  }
  // Originals are stored in the order of first use: trees in order, leaves in node order, each leaf's
  // images in its (sorted) list; batches of leaves do not change that order (build.cpp).
  OriginalBlockLayout layout(originalBlockTarget(m.params.atlasSize));
  std::vector<uint8_t> stored(m.images.size(), 0);
  auto close = [&](uint64_t bytes) { ++e.originalBlocks, e.originalBytes += padded(bytes); };
  for (const Tree& t : m.trees)
    for (const Node& n : t.nodes) {
      if (!n.leaf()) continue;
      for (uint32_t j = 0; j < n.imageCount; ++j) {
        const uint32_t img = t.leafImages[n.imageFirst + j];
        if (stored[img]) continue;
        stored[img] = 1;
        const ImageRecord& r = m.images[img];
        if (m.encoding == BlockEncoding::S3tc) {  // one piece, one block: the image's chain
          ++e.pieces;
          close(s3tcChainBytes(r.width, r.height, r.channels));
          continue;
        }
        const uint64_t rowBytes = uint64_t(r.width) * r.channels;
        for (uint32_t row = 0; row < r.height;) {
          const OriginalBlockLayout::Piece p = layout.next(r.height - row, rowBytes, row == 0);
          if (p.closedBlockBytes) close(p.closedBlockBytes);
          ++e.pieces;
          row += p.rows;
        }
      }
    }
  if (layout.fill()) close(layout.fill());
  e.metadataBytes = metadataBytes(m, e.pieces, e.atlasBlocks + e.originalBlocks);
  e.totalBytes = kHeaderSize + e.atlasBytes + e.originalBytes + e.metadataBytes;
  return e;
}

}  // namespace tessera::mta
