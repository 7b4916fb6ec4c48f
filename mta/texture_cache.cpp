#include "mta/texture_cache.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "base/error.h"
#include "raster/texture.h"

namespace tessera::mta {

uint64_t MipChain::bytes() const {
  uint64_t b = 0;
  for (const auto& l : levels) b += l.size();
  return b;
}

uint64_t MipChain::decodedBytes() const {
  if (compression == BcFormat::None) return bytes();
  uint64_t b = 0;
  for (uint32_t l = 0; l < levels.size(); ++l)
    b += uint64_t(std::max(1u, width >> l)) * std::max(1u, height >> l) * 4;
  return b;
}

TextureCache::TextureCache(const PagingFile& file, const Residency* residency, uint64_t fileCacheBytes)
    : file_(file), residency_(residency), fileCacheBytes_(fileCacheBytes) {}

void TextureCache::prune() {
  if (!residency_) return;
  for (auto it = entries_.begin(); it != entries_.end();) {
    bool stale = false;
    for (auto [b, gen] : it->second.blocks) stale |= !residency_->resident(b) || residency_->generation(b) != gen;
    if (stale) {
      bytes_ -= it->second.chain->bytes();
      decodedBytes_ -= it->second.chain->decodedBytes();
      it = entries_.erase(it);
    } else {
      ++it;
    }
  }
}

// The bytes of a block, valid until the next call: resident data, or (file mode) one of the last few
// blocks read.
std::span<const uint8_t> TextureCache::blockBytes(uint32_t block) {
  if (!residency_) {
    // Keep the last few read (each read verifies the block's SHA-256, which dominated `mta runs` when
    // format version 1 packed the images of one leaf into shared blocks).
    for (const auto& [b, bytes] : recentBlocks_)
      if (b == block) return bytes;
    if (recentBlocks_.size() == 4) recentBlocks_.erase(recentBlocks_.begin());
    recentBlocks_.emplace_back(block, file_.readBlock(block));
    return recentBlocks_.back().second;
  }
  const auto span = residency_->data(block);
  if (span.empty()) throw Error("texture cache: internal error: block " + std::to_string(block) + " is not in memory");
  return span;
}

const MipChain& TextureCache::store(uint64_t key, std::shared_ptr<MipChain> chain,
                                    std::vector<std::pair<uint32_t, uint64_t>> blocks) {
  if (!residency_ && bytes_ + chain->bytes() > fileCacheBytes_) {
    entries_.clear();  // comparison runs: a crude bound is enough, the file is the backing store
    bytes_ = decodedBytes_ = 0;
  }
  bytes_ += chain->bytes();
  decodedBytes_ += chain->decodedBytes();
  Entry& e = entries_[key];
  e.chain = std::move(chain);
  e.blocks = std::move(blocks);
  return *e.chain;
}

namespace {

std::vector<uint8_t> toRGBA(const uint8_t* src, size_t texels, uint32_t channels) {
  std::vector<uint8_t> out(texels * 4);
  for (size_t i = 0; i < texels; ++i) {
    out[i * 4 + 0] = src[i * channels + 0];
    out[i * 4 + 1] = src[i * channels + 1];
    out[i * 4 + 2] = src[i * channels + 2];
    out[i * 4 + 3] = channels == 4 ? src[i * channels + 3] : 255;
  }
  return out;
}

// An S3TC block (the whole encoded chain of a w x h image) cut into its levels.
std::shared_ptr<MipChain> compressedChain(uint32_t w, uint32_t h, uint32_t channels, std::span<const uint8_t> block) {
  const std::vector<uint64_t> off = s3tcLevelOffsets(w, h, channels);
  // The validator fixes the block's size; checked because a wrong one would be read past its end.
  if (block.size() != off.back())
    throw Error("texture cache: internal error: a block of " + std::to_string(block.size()) + " bytes is not the " +
                std::to_string(off.back()) + "-byte chain of a " + std::to_string(w) + "x" + std::to_string(h) + " image");
  auto chain = std::make_shared<MipChain>();
  chain->width = w, chain->height = h, chain->compression = storedBcFormat(channels);
  for (size_t l = 0; l + 1 < off.size(); ++l) chain->levels.emplace_back(block.begin() + off[l], block.begin() + off[l + 1]);
  return chain;
}

}  // namespace

const MipChain& TextureCache::atlas(uint8_t tree, uint32_t node, uint32_t layer) {
  const uint64_t key = (uint64_t(1) << 62) | (uint64_t(layer & 0xff) << 40) | (uint64_t(tree) << 32) | node;
  if (auto it = entries_.find(key); it != entries_.end()) return *it->second.chain;
  const MtaMeta& m = file_.meta();
  if (tree >= m.trees.size() || layer >= m.layerCount ||
      size_t(node) * m.layerCount + layer >= m.trees[tree].atlasBlocks.size())
    throw Error("texture cache: internal error: atlas of tree " + std::to_string(tree) + " node " +
                std::to_string(node) + " layer " + std::to_string(layer) + " out of range");
  const uint32_t block = m.trees[tree].atlasBlocks[size_t(node) * m.layerCount + layer];
  const std::span<const uint8_t> raw = blockBytes(block);
  const uint32_t a = m.params.atlasSize;
  if (m.encoding == BlockEncoding::S3tc)
    return store(key, compressedChain(a, a, m.trees[tree].channels(), raw),
                 {{block, residency_ ? residency_->generation(block) : 0}});
  // The validator fixes an atlas block's size; a wrong one here would be read past its end.
  if (raw.size() != size_t(a) * a * m.trees[tree].channels())
    throw Error("texture cache: internal error: block " + std::to_string(block) +
                " is not an atlas of the tree's size");
  auto chain = std::make_shared<MipChain>();
  chain->width = chain->height = a;
  chain->levels = buildMipChainRGBA8(a, a, toRGBA(raw.data(), size_t(a) * a, m.trees[tree].channels()));
  return store(key, std::move(chain), {{block, residency_ ? residency_->generation(block) : 0}});
}

const MipChain& TextureCache::image(uint32_t image) {
  const uint64_t key = (uint64_t(2) << 62) | image;
  if (auto it = entries_.find(key); it != entries_.end()) return *it->second.chain;
  const MtaMeta& m = file_.meta();
  if (image >= m.images.size())
    throw Error("texture cache: internal error: image " + std::to_string(image) + " out of range");
  const ImageRecord& r = m.images[image];
  if (m.encoding == BlockEncoding::S3tc) {
    // One piece, its block the chain (validated).
    const uint32_t b = m.pieces.at(r.firstPiece).block;
    return store(key, compressedChain(r.width, r.height, r.channels, blockBytes(b)),
                 {{b, residency_ ? residency_->generation(b) : 0}});
  }
  std::vector<uint8_t> texels(size_t(r.width) * r.height * r.channels);
  std::vector<std::pair<uint32_t, uint64_t>> blocks;
  const size_t rowBytes = size_t(r.width) * r.channels;
  for (uint32_t k = 0; k < r.pieceCount; ++k) {
    const PieceRecord& p = m.pieces.at(size_t(r.firstPiece) + k);
    const std::span<const uint8_t> bytes = blockBytes(p.block);
    // Guaranteed by the validator (pieces tile their image's rows and their block); checked because a
    // wrong record would copy out of bounds.
    if (uint64_t(p.row0) + p.rows > r.height || p.offset > bytes.size() ||
        size_t(p.rows) * rowBytes > bytes.size() - p.offset)
      throw Error("texture cache: internal error: piece " + std::to_string(r.firstPiece + k) +
                  " lies outside its image or block");
    std::memcpy(texels.data() + size_t(p.row0) * rowBytes, bytes.data() + p.offset, size_t(p.rows) * rowBytes);
    blocks.emplace_back(p.block, residency_ ? residency_->generation(p.block) : 0);
  }
  auto chain = std::make_shared<MipChain>();
  chain->width = r.width;
  chain->height = r.height;
  // Stored top row first with v = 0 there; uploaded as is, GL's t = 0 row is v = 0 (docs/mta-format.md).
  chain->levels = buildMipChainRGBA8(r.width, r.height, toRGBA(texels.data(), size_t(r.width) * r.height, r.channels));
  return store(key, std::move(chain), std::move(blocks));
}

}  // namespace tessera::mta
