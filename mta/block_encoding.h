// How the texels of an atlas tree's blocks are stored (docs/mta-format.md, "Blocks"): raw (level 0 only,
// `channels` bytes per texel; the runtime makes the mip chain) or S3TC (thesis §4.7): the whole mip chain,
// every level made by the box filter (raster/texture.h buildMipChainRGBA8) from the raw level 0 and then
// encoded in 4x4 blocks by raster/bc_encode.h: BC1 for 3-channel images and atlases (the RGB tree, whose
// texels are all opaque), BC3 for 4-channel ones. Levels follow each other from level 0 down to 1x1, each
// ceil(w/4) x ceil(h/4) blocks; levels below 4x4 are padded by edge replication (bc_encode.h).
//
// An S3TC image is one piece in one Original block (the chain cannot be cut into row ranges of level 0).
// BC1 or BC3 is chosen by the stored channel count, not by the texels, so that the size estimate, which
// knows channel counts but no texels, stays exact (output_size.h).
// Implements: the format choice, the exact byte count of a stored chain (the size estimate relies on it) and
// the encoding itself. Does not implement: decoding (the oracle decodes uploads, raster/bc_decode.h).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "raster/bc_decode.h"

namespace tessera::mta {

// The on-disk tag in the header of a version-3 paging file (docs/mta-format.md): append only.
enum class BlockEncoding : uint32_t { Raw = 0, S3tc = 1 };
const char* blockEncodingName(BlockEncoding e);

// BC1 for 3 channels, BC3 for 4.
BcFormat storedBcFormat(uint32_t channels);
// Bytes of the S3TC chain of a w x h image with `channels` channels: the sum of its levels' block bytes.
uint64_t s3tcChainBytes(uint32_t w, uint32_t h, uint32_t channels);
// Offsets of each level inside such a chain (levels + 1 entries; the last is s3tcChainBytes).
std::vector<uint64_t> s3tcLevelOffsets(uint32_t w, uint32_t h, uint32_t channels);
// Encodes level 0 (w x h texels of `channels` bytes, rows in stored order) into its S3TC chain. The bytes
// depend only on the texels (bc_encode.h), whatever the thread count.
std::vector<uint8_t> encodeS3tcChain(uint32_t w, uint32_t h, uint32_t channels, std::span<const uint8_t> texels);
// Level 0 of such a chain decoded back to w x h texels of `channels` bytes (PagingFile::readImage / readAtlas).
// Precondition: chain.size() >= s3tcChainBytes(w, h, channels) (Error otherwise).
std::vector<uint8_t> decodeS3tcLevel0(uint32_t w, uint32_t h, uint32_t channels, std::span<const uint8_t> chain);

}  // namespace tessera::mta
