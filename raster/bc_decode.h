// The oracle's decoder of S3TC blocks: BC1 (GL_COMPRESSED_RGB_S3TC_DXT1_EXT) and BC3
// (GL_COMPRESSED_RGBA_S3TC_DXT5_EXT), as defined by the EXT_texture_compression_s3tc extension.
//
// Implements: the block layout of the extension and one documented rounding of the values it leaves free
// (docs/spec-choices.md C1-C4):
//   - Endpoints are RGB565, expanded to 8 bits by bit replication (r5 -> r5 << 3 | r5 >> 2,
//     g6 -> g6 << 2 | g6 >> 4), and every interpolant is computed from the expanded 8-bit values.
//   - BC1, color0 > color1 (four colours): code 2 = (2*c0 + c1)/3 and code 3 = (c0 + 2*c1)/3, rounded to
//     the nearest integer, floor((2*c0 + c1 + 1) / 3). A third is never a half, so there is no tie.
//   - BC1, color0 <= color1 (three colours): code 2 = (c0 + c1)/2 rounded half up, floor((c0 + c1 + 1) / 2);
//     code 3 = black. The RGB variant of DXT1 is decoded, whose black is opaque (alpha 255): the extension
//     makes it transparent only for GL_COMPRESSED_RGBA_S3TC_DXT1_EXT, which Tessera does not use.
//   - BC3 colour: always the four-colour rule, whatever the order of color0 and color1 (the extension:
//     DXT3/DXT5 colour blocks ignore the three-colour mode).
//   - BC3 alpha, alpha0 > alpha1 (eight values): code i in 2..7 = ((8 - i)*a0 + (i - 1)*a1)/7, rounded to
//     nearest, floor((x + 3) / 7). alpha0 <= alpha1 (six values): code i in 2..5 = ((6 - i)*a0 + (i - 1)*a1)/5,
//     floor((x + 2) / 5); code 6 = 0, code 7 = 255. Sevenths and fifths are never halves: no ties.
// Rounding to nearest keeps every decoded value within half a unit of the extension's exact value, so a
// driver that truncates or rounds the other way differs from the oracle by at most one unit per channel
// (the BC_INTERPOLANT class of docs/crosscheck.md).
//
// Layout: a level of w x h texels is ceil(w/4) x ceil(h/4) blocks, row-major, block row 0 holding texel rows
// 0..3 in memory order (the oracle stores rows bottom first, as GL uploads them). Inside a block texel
// (x, y) has code bits 2*(4*y + x) (colour) and 3*(4*y + x) (BC3 alpha), counted from the least significant
// bit of the little-endian code words. Texels of edge blocks past w or h are decoded and dropped.
// Does not implement: encoding (bc_encode.h), other S3TC variants (DXT1 RGBA, DXT3), BC4-BC7.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace tessera {

// The two block formats the project stores, and None for uncompressed texels (TextureDesc::compression).
// The values are on-disk tags (.tframe, .mta): append only.
enum class BcFormat : uint8_t { None = 0, BC1 = 1, BC3 = 2, Count };
const char* bcFormatName(BcFormat f);

constexpr uint32_t bcBlockBytes(BcFormat f) { return f == BcFormat::BC1 ? 8u : 16u; }
// Bytes of a w x h level: ceil(w/4) * ceil(h/4) blocks.
constexpr uint64_t bcLevelBytes(BcFormat f, uint32_t w, uint32_t h) {
  return uint64_t((w + 3) / 4) * ((h + 3) / 4) * bcBlockBytes(f);
}

// Decodes one block into 16 RGBA8 texels, row-major (texel (x, y) at out[4 * (4*y + x)]).
void decodeBc1Block(const uint8_t* block, uint8_t* out);
void decodeBc3Block(const uint8_t* block, uint8_t* out);

// Decodes a w x h level into tightly packed RGBA8 rows in the blocks' row order.
// Precondition: blocks.size() == bcLevelBytes(f, w, h) (Error otherwise), w and h >= 1.
std::vector<uint8_t> decodeBcLevel(BcFormat f, uint32_t w, uint32_t h, std::span<const uint8_t> blocks);
// The same into `out`, which must hold exactly w * h * 4 bytes (Error otherwise): a backend decodes
// straight into the texture's level, without a temporary level-sized buffer (under ASan every such
// buffer above the mmap threshold was a fresh mapping, zeroed, faulted in and unmapped per upload).
void decodeBcLevelInto(BcFormat f, uint32_t w, uint32_t h, std::span<const uint8_t> blocks, std::span<uint8_t> out);

// Which channels of each texel of that level are interpolants, whose rounding the extension leaves free
// (the cross-check widens exactly those by one unit, BC_INTERPOLANT): per texel a mask, bits 0..2 for RGB
// (colour codes 2 and 3 of the four-colour rule, code 2 of the three-colour rule), bit 3 for a BC3 alpha
// code 2..7 (2..5 in the six-value mode). Endpoints, black and the fixed alphas 0 and 255 are exact.
// Same precondition and layout as decodeBcLevel.
std::vector<uint8_t> bcInterpolantChannels(BcFormat f, uint32_t w, uint32_t h, std::span<const uint8_t> blocks);

}  // namespace tessera
