// Texel storage and the deterministic mip-chain box filter (see texture.h).
//
// GL leaves the filter of glGenerateMipmap implementation-dependent (GL 4.6 §8.14.4: "a box filter
// is recommended"), so the oracle cannot match a driver bit for bit here. Instead the oracle computes
// every level itself with the exact area-weighted box filter below and the GL backend uploads the
// result, so both backends sample identical texels.
#include "raster/texture.h"

#include "raster/storage_pool.h"

#include <cstring>
#include <string>

namespace tessera {

TextureData::TextureData(const TextureDesc& d, StoragePool* pool) : desc(d) {
  // Buffer textures own no storage: their texels are the bytes of the bound buffer (GL 4.6 §8.9).
  if (desc.kind == TextureKind::Buffer) return;
  levels.resize(desc.levels);
  for (uint32_t l = 0; l < desc.levels; ++l) {
    const size_t n = size_t(levelBytes(desc, l) * desc.layers);
    if (pool) levels[l] = pool->take(n);
    else levels[l].assign(n, uint8_t{0});
    // A compressed texture starts as all-zero blocks, as GL's does (the GL backend uploads them): a BC1
    // zero block is color0 = color1 = 0, three-colour mode, code 0: opaque black (spec-choices C2). A
    // BC3 zero block decodes to (0, 0, 0, 0), the zeroed storage.
    if (desc.compression == BcFormat::BC1)
      for (size_t i = 3; i < n; i += 4) levels[l][i] = 255;
  }
}

namespace {

// The source taps of one destination index along one axis: `count` consecutive source texels
// starting at `first`, with integer weights that sum to the axis denominator.
struct AxisTaps {
  uint32_t first = 0;
  uint32_t count = 0;
  uint32_t w[3] = {0, 0, 0};
};

// Per-axis tap table for a source extent n -> destination extent max(1, n / 2).
// - n == 1: the axis is not reduced (the other axis is); the single texel is copied (weight 1/1).
// - n == 2m: destination texel i covers source texels 2i, 2i+1 exactly: weights (1, 1)/2.
// - n == 2m+1: destination texel i covers the source interval [i*n/m, (i+1)*n/m) of length n/m, i.e.
//   texels 2i, 2i+1, 2i+2 with coverage (m - i, m, i + 1)/m; normalising by the length n/m gives
//   (m - i, m, i + 1)/n. Example n = 5: (2, 2, 1)/5 and (1, 2, 2)/5.
// Returns the denominator.
uint32_t buildAxisTaps(uint32_t n, std::vector<AxisTaps>& taps) {
  const uint32_t dst = n > 1 ? n / 2 : 1;
  taps.assign(dst, AxisTaps{});
  if (n == 1) {
    taps[0] = AxisTaps{0, 1, {1, 0, 0}};
    return 1;
  }
  if (n % 2 == 0) {
    for (uint32_t i = 0; i < dst; ++i) taps[i] = AxisTaps{2 * i, 2, {1, 1, 0}};
    return 2;
  }
  const uint32_t m = (n - 1) / 2;  // == dst
  for (uint32_t i = 0; i < dst; ++i) taps[i] = AxisTaps{2 * i, 3, {m - i, m, i + 1}};
  return n;
}

// q = round_half_even(num / den) for num >= 0, den > 0, exactly.
inline uint64_t divRoundHalfEven(uint64_t num, uint64_t den) {
  const uint64_t q = num / den, r = num % den;
  if (2 * r > den || (2 * r == den && (q & 1) != 0)) return q + 1;
  return q;
}

inline float loadF32(const uint8_t* p) {
  float v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// One destination level of one layer from its source level. `src`/`dst` point at the layer.
void reduceLevel(Format fmt, const uint8_t* src, uint32_t sw, uint8_t* dst, uint32_t dw, uint32_t dh,
                 const std::vector<AxisTaps>& tx, uint32_t denX, const std::vector<AxisTaps>& ty, uint32_t denY) {
  const uint32_t bpt = texelBytes(fmt);
  const int channels = channelCount(fmt);
  const uint64_t srcRow = uint64_t(sw) * bpt;

  if (isInteger(fmt)) {
    // Integer textures are never filtered (GL 4.6 §8.17 makes LINEAR filters incomplete for them),
    // so a "reduction" that averages values would be meaningless: take texel (2i, 2j), which is
    // always inside the source (2i <= n - 2 for n >= 2, and i = 0 for n = 1).
    for (uint32_t j = 0; j < dh; ++j) {
      for (uint32_t i = 0; i < dw; ++i) {
        std::memcpy(dst + (uint64_t(j) * dw + i) * bpt, src + uint64_t(2 * j) * srcRow + uint64_t(2 * i) * bpt, bpt);
      }
    }
    return;
  }

  const uint64_t den = uint64_t(denX) * denY;  // <= 16383^2 < 2^28
  for (uint32_t j = 0; j < dh; ++j) {
    const AxisTaps& ay = ty[j];
    for (uint32_t i = 0; i < dw; ++i) {
      const AxisTaps& ax = tx[i];
      uint8_t* out = dst + (uint64_t(j) * dw + i) * bpt;
      if (isUnorm(fmt)) {
        // Exact integer sum (<= 255 * 2^28 < 2^36), one rounding from the exact rational.
        uint64_t acc[4] = {0, 0, 0, 0};
        for (uint32_t y = 0; y < ay.count; ++y) {
          const uint8_t* row = src + uint64_t(ay.first + y) * srcRow;
          for (uint32_t x = 0; x < ax.count; ++x) {
            const uint64_t w = uint64_t(ay.w[y]) * ax.w[x];
            const uint8_t* p = row + uint64_t(ax.first + x) * bpt;
            for (int c = 0; c < channels; ++c) acc[c] += w * p[c];
          }
        }
        for (int c = 0; c < channels; ++c) out[c] = uint8_t(divRoundHalfEven(acc[c], den));
      } else {
        // Float formats: every product (integer weight < 2^28) x (float) is exact in double; the
        // sum in a fixed order and the final division are double operations, rounded to float once.
        double acc[4] = {0, 0, 0, 0};
        for (uint32_t y = 0; y < ay.count; ++y) {
          const uint8_t* row = src + uint64_t(ay.first + y) * srcRow;
          for (uint32_t x = 0; x < ax.count; ++x) {
            const double w = double(uint64_t(ay.w[y]) * ax.w[x]);
            const uint8_t* p = row + uint64_t(ax.first + x) * bpt;
            for (int c = 0; c < channels; ++c) acc[c] += w * double(loadF32(p + 4 * c));
          }
        }
        for (int c = 0; c < channels; ++c) {
          const float v = float(acc[c] / double(den));
          std::memcpy(out + 4 * c, &v, sizeof v);
        }
      }
    }
  }
}

}  // namespace

void generateMipChain(TextureData& tex) {
  if (tex.desc.kind == TextureKind::Buffer) return;
  const TextureDesc& d = tex.desc;
  const uint32_t levelCount = uint32_t(tex.levels.size());
  std::vector<AxisTaps> tx, ty;  // reused across levels; no allocation inside the texel loops
  for (uint32_t l = 1; l < levelCount; ++l) {
    // Each level is reduced from the previous one (the GL convention for mip chains).
    const uint32_t sw = levelWidth(d, l - 1), sh = levelHeight(d, l - 1);
    const uint32_t dw = levelWidth(d, l), dh = levelHeight(d, l);
    const uint32_t denX = buildAxisTaps(sw, tx);
    const uint32_t denY = buildAxisTaps(sh, ty);
    const uint64_t srcLayer = levelBytes(d, l - 1), dstLayer = levelBytes(d, l);
    for (uint32_t layer = 0; layer < d.layers; ++layer) {
      const uint8_t* src = tex.levels[l - 1].data() + layer * srcLayer;
      uint8_t* dst = tex.levels[l].data() + layer * dstLayer;
      reduceLevel(d.format, src, sw, dst, dw, dh, tx, denX, ty, denY);
    }
  }
}

std::vector<std::vector<uint8_t>> buildMipChainRGBA8(uint32_t width, uint32_t height, std::span<const uint8_t> level0) {
  if (width == 0 || height == 0) throw Error("buildMipChainRGBA8: empty image");
  TextureDesc d;
  d.kind = TextureKind::Tex2D;
  d.format = Format::RGBA8;
  d.width = width;
  d.height = height;
  d.layers = 1;
  d.levels = fullMipCount(width, height);
  if (level0.size() != levelBytes(d, 0)) {
    throw Error("buildMipChainRGBA8: level 0 has " + std::to_string(level0.size()) + " bytes, expected " +
                std::to_string(levelBytes(d, 0)));
  }
  TextureData tex(d);
  std::memcpy(tex.levels[0].data(), level0.data(), level0.size());
  generateMipChain(tex);
  return std::move(tex.levels);
}

}  // namespace tessera
