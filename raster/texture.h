// Texel storage of the CPU backend and the deterministic mip-chain filter.
//
// Implements: storage of 2D / 2D-array textures (every level, every layer) and of buffers, texel
// addressing, and generateMipChain(): the documented box filter that produces every level below 0.
// Does not implement: sampling (sample.h) or GL upload (the GL backend uploads what this produced).
//
// Layout: level L of a texture is one contiguous byte vector holding layer 0, then layer 1, ...;
// each layer is rows of levelWidth(L) texels, bottom row first (GL order), tightly packed.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "raster/command_list.h"

namespace tessera {

struct Provenance;
class StoragePool;

struct BufferData {
  BufferKind kind = BufferKind::Vertex;
  std::vector<uint8_t> bytes;
};

struct TextureData {
  TextureDesc desc;
  std::vector<std::vector<uint8_t>> levels;  // empty for Buffer kind
  const BufferData* buffer = nullptr;        // Buffer kind only, set at bind time
  // Per-texel interval images, present only when the texture was rendered in provenance mode
  // (provenance.h). shared_ptr: Provenance is incomplete here and holds TextureData itself.
  std::shared_ptr<Provenance> prov;

  // Allocates zeroed storage for every level (2D / array kinds), taken from `pool` when one is given
  // (the storage is zeroed either way).
  explicit TextureData(const TextureDesc& d, StoragePool* pool = nullptr);
  uint8_t* texel(uint32_t level, uint32_t layer, uint32_t x, uint32_t y) {
    const uint32_t w = levelWidth(desc, level), h = levelHeight(desc, level);
    return levels[level].data() + ((uint64_t(layer) * h + y) * w + x) * texelBytes(desc.format);
  }
  const uint8_t* texel(uint32_t level, uint32_t layer, uint32_t x, uint32_t y) const {
    return const_cast<TextureData*>(this)->texel(level, layer, x, y);
  }
};

// Computes levels 1 .. levels-1 of every layer of `tex` from level 0 with the box filter of
// docs/spec-choices.md ("Mip chain"): each destination texel is the area-weighted average of the
// source texels it covers. Even source extents use weights (1, 1)/2; an odd extent n = 2m + 1
// uses the exact three-tap polyphase weights (m - i, m, i + 1)/n for destination texel i. The two
// axes are separable and combined as integer weights; unorm8 results are rounded half to even once
// from the exact rational, float results are computed in double and rounded to float once, R32UI
// takes the source texel (2i, 2j) (integer textures are never filtered).
void generateMipChain(TextureData& tex);

// Convenience for scene builders: returns every level of an RGBA8 image (bottom row first),
// level 0 first, computed with generateMipChain().
std::vector<std::vector<uint8_t>> buildMipChainRGBA8(uint32_t width, uint32_t height,
                                                     std::span<const uint8_t> level0);

}  // namespace tessera
