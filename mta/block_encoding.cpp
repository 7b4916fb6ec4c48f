#include "mta/block_encoding.h"

#include <string>

#include "base/error.h"
#include "raster/bc_encode.h"
#include "raster/command_list.h"
#include "raster/texture.h"

namespace tessera::mta {

const char* blockEncodingName(BlockEncoding e) {
  return e == BlockEncoding::Raw ? "raw" : e == BlockEncoding::S3tc ? "s3tc" : "?";
}

BcFormat storedBcFormat(uint32_t channels) { return channels == 3 ? BcFormat::BC1 : BcFormat::BC3; }

std::vector<uint64_t> s3tcLevelOffsets(uint32_t w, uint32_t h, uint32_t channels) {
  TextureDesc d;
  d.width = w, d.height = h, d.levels = fullMipCount(w, h);
  std::vector<uint64_t> off{0};
  for (uint32_t l = 0; l < d.levels; ++l)
    off.push_back(off.back() + bcLevelBytes(storedBcFormat(channels), levelWidth(d, l), levelHeight(d, l)));
  return off;
}

uint64_t s3tcChainBytes(uint32_t w, uint32_t h, uint32_t channels) { return s3tcLevelOffsets(w, h, channels).back(); }

std::vector<uint8_t> encodeS3tcChain(uint32_t w, uint32_t h, uint32_t channels, std::span<const uint8_t> texels) {
  if (texels.size() != size_t(w) * h * channels)
    throw Error("encodeS3tcChain: " + std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(channels) +
                " texels need " + std::to_string(size_t(w) * h * channels) + " bytes, got " + std::to_string(texels.size()));
  std::vector<uint8_t> rgba(size_t(w) * h * 4);
  for (size_t i = 0; i < size_t(w) * h; ++i) {
    for (uint32_t c = 0; c < 3; ++c) rgba[4 * i + c] = texels[i * channels + c];
    rgba[4 * i + 3] = channels == 4 ? texels[i * 4 + 3] : 255;
  }
  // The same chain the raw path's runtime builds (texture_cache.cpp), so raw and S3TC trees differ only by
  // the encoding.
  const std::vector<std::vector<uint8_t>> chain = buildMipChainRGBA8(w, h, rgba);
  const BcFormat f = storedBcFormat(channels);
  TextureDesc d;
  d.width = w, d.height = h, d.levels = uint32_t(chain.size());
  std::vector<uint8_t> out;
  out.reserve(size_t(s3tcChainBytes(w, h, channels)));
  for (uint32_t l = 0; l < d.levels; ++l) {
    const std::vector<uint8_t> blocks = encodeBcLevel(f, levelWidth(d, l), levelHeight(d, l), chain[l]);
    out.insert(out.end(), blocks.begin(), blocks.end());
  }
  return out;
}

}  // namespace tessera::mta

namespace tessera::mta {

std::vector<uint8_t> decodeS3tcLevel0(uint32_t w, uint32_t h, uint32_t channels, std::span<const uint8_t> chain) {
  const BcFormat f = storedBcFormat(channels);
  const uint64_t n = bcLevelBytes(f, w, h);
  if (chain.size() < s3tcChainBytes(w, h, channels))
    throw Error("decodeS3tcLevel0: a " + std::to_string(w) + "x" + std::to_string(h) + " chain needs " +
                std::to_string(s3tcChainBytes(w, h, channels)) + " bytes, got " + std::to_string(chain.size()));
  const std::vector<uint8_t> rgba = decodeBcLevel(f, w, h, chain.first(size_t(n)));
  std::vector<uint8_t> out(size_t(w) * h * channels);
  for (size_t i = 0; i < size_t(w) * h; ++i)
    for (uint32_t c = 0; c < channels; ++c) out[i * channels + c] = rgba[4 * i + c];
  return out;
}

}  // namespace tessera::mta
