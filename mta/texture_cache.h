// The texture cache of the atlas tree renderer: RGBA8 mip chains of the textures a frame binds, made
// from paging-file blocks.
//
// Implements: atlas(tree, node, layer) (the node's atlas of that layer, A x A) and image(i) (an original scene
// texture reassembled from its pieces). Raw files: converted to RGBA8 (3-channel texels get alpha 255) and
// reduced to a full mip chain with the documented box filter (raster/texture.h buildMipChainRGBA8). S3TC
// files: the block is already that chain, encoded (block_encoding.h); it is kept compressed, cut into its
// levels, and the frame uploads the blocks as they are (the oracle decodes them, GL takes them as they are).
// Two modes:
//   - memory-manager mode (residency given): blocks are read from the Residency's resident data; a
//     chain remembers the generation of every block it was made from, and prune() drops each chain one
//     of whose blocks was removed or reloaded since. The caller only asks for chains whose blocks are
//     resident (otherwise: Error, an internal error of the caller).
//   - file mode (residency == nullptr; the comparison runs of `mta runs`): blocks are read straight from
//     the paging file, each read verifying the block's SHA-256. The last 4 blocks read are kept (since
//     format version 2 a block holds one image, so this only saves the reads of a chain made again).
//     Chains are kept up to fileCacheBytes in all; when a new chain would exceed that, every chain is
//     dropped (a crude bound is enough: the file is the backing store).
// A returned reference stays valid until the next prune() or the next atlas()/image() call that drops
// chains (file mode); callers copy what they need into the frame's CommandList before that.
// The chains are a pure function of the paging file's bytes, so what a frame draws never depends on
// what the cache held.
// Does not implement: deciding what is resident (residency.h), recording frames (frame_recorder.h).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "mta/paging_file.h"
#include "mta/residency.h"

namespace tessera::mta {

struct MipChain {
  uint32_t width = 0, height = 0;
  BcFormat compression = BcFormat::None;     // None: RGBA8 levels; BC1 / BC3: each level's blocks
  std::vector<std::vector<uint8_t>> levels;  // rows bottom first as uploaded
  uint64_t bytes() const;                    // as held: compressed bytes for BC1 / BC3
  uint64_t decodedBytes() const;             // the RGBA8 chain the oracle decodes (= bytes() when None)
};

class TextureCache {
 public:
  // residency == nullptr: blocks are read from the file on demand (comparison runs), and the cache keeps
  // at most `fileCacheBytes` of chains.
  TextureCache(const PagingFile& file, const Residency* residency, uint64_t fileCacheBytes = uint64_t(2) << 30);
  // Drops chains whose blocks were removed or reloaded since they were made.
  void prune();
  const MipChain& atlas(uint8_t tree, uint32_t node, uint32_t layer = 0);
  const MipChain& image(uint32_t image);
  uint64_t bytes() const { return bytes_; }                 // the chains as held (compressed in S3TC files)
  uint64_t decodedBytes() const { return decodedBytes_; }   // the same chains as RGBA8

 private:
  struct Entry {
    std::shared_ptr<MipChain> chain;
    std::vector<std::pair<uint32_t, uint64_t>> blocks;  // (block, generation) it was made from
  };
  std::span<const uint8_t> blockBytes(uint32_t block);
  const MipChain& store(uint64_t key, std::shared_ptr<MipChain> chain,
                        std::vector<std::pair<uint32_t, uint64_t>> blocks);
  const PagingFile& file_;
  const Residency* residency_;
  uint64_t fileCacheBytes_, bytes_ = 0, decodedBytes_ = 0;
  std::map<uint64_t, Entry> entries_;
  std::vector<std::pair<uint32_t, std::vector<uint8_t>>> recentBlocks_;  // file mode only
};

}  // namespace tessera::mta
