// The encoder of S3TC blocks used to store textures compressed (the atlas tree's paging file).
//
// Implements: choosing BC1 or BC3 for an RGBA8 image (BC1 exactly when every texel's alpha is 255), and
// encoding a level with stb_dxt (the system's stb/stb_dxt.h, v1.11 or later: its tables are static, so no
// racy first-use initialisation) in its high-quality mode. The encoder is integer arithmetic plus float
// additions and multiplications in a fixed order (no libm but fabs, no dithering: stb_dxt 1.11 made
// STB_DXT_DITHER a no-op, and it is not asked for), and each block depends only on its own 16 texels; so the
// bytes are the same for any thread count, run or build type. Blocks are encoded in parallel over block rows.
// Padding: a level whose width or height is not a multiple of 4 (every level below 4x4 among them) fills the
// missing texels of its edge blocks by replicating the last column and row (clamped coordinates), so an edge
// block's endpoints are fitted to real texels only; the decoder drops those texels again (bc_decode.h).
// Does not implement: decoding (bc_decode.h), mip filtering (texture.h buildMipChainRGBA8 makes the levels).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "raster/bc_decode.h"

namespace tessera {

// BC1 when every alpha byte of the tightly packed RGBA8 texels is 255, BC3 otherwise.
BcFormat chooseBcFormat(std::span<const uint8_t> rgba);

// Encodes a w x h RGBA8 level (rows in memory order) into bcLevelBytes(f, w, h) bytes of blocks, laid out as
// bc_decode.h describes. Precondition: rgba.size() == 4 * w * h, w and h >= 1 (Error otherwise). BC1
// discards alpha: callers pick BC1 only for opaque images (chooseBcFormat).
std::vector<uint8_t> encodeBcLevel(BcFormat f, uint32_t w, uint32_t h, std::span<const uint8_t> rgba);

}  // namespace tessera
