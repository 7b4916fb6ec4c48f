// S3TC encoding through stb_dxt (bc_encode.h). This is the one translation unit that compiles stb_dxt's
// implementation; its functions are static (STB_DXT_STATIC), so nothing else can link against them.
#include "raster/bc_encode.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstring>  // stb_dxt.h calls memcpy without including <string.h>
#include <string>

#include "base/error.h"

// A third-party header: its unused BC4/BC5 entry points and C idioms are not ours to warn about.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wconversion"
#define STB_DXT_STATIC
#define STB_DXT_IMPLEMENTATION
#include <stb/stb_dxt.h>
#pragma GCC diagnostic pop

namespace tessera {

BcFormat chooseBcFormat(std::span<const uint8_t> rgba) {
  for (size_t i = 3; i < rgba.size(); i += 4)
    if (rgba[i] != 255) return BcFormat::BC3;
  return BcFormat::BC1;
}

std::vector<uint8_t> encodeBcLevel(BcFormat f, uint32_t w, uint32_t h, std::span<const uint8_t> rgba) {
  if (f != BcFormat::BC1 && f != BcFormat::BC3)
    throw Error("encodeBcLevel: block format " + std::to_string(int(f)) + " is neither BC1 (1) nor BC3 (2)");
  if (w == 0 || h == 0 || rgba.size() != size_t(w) * h * 4)
    throw Error("encodeBcLevel: a " + std::to_string(w) + "x" + std::to_string(h) + " RGBA8 level needs " +
                std::to_string(size_t(w) * h * 4) + " bytes, got " + std::to_string(rgba.size()));
  const uint32_t bw = (w + 3) / 4, bh = (h + 3) / 4, bytes = bcBlockBytes(f);
  std::vector<uint8_t> out(size_t(bcLevelBytes(f, w, h)));
  // Rows of blocks are independent (each block reads only its own clamped 4x4 texels), so the split over
  // threads cannot change a byte.
  tbb::parallel_for(uint32_t(0), bh, [&](uint32_t by) {
    uint8_t texels[64];
    for (uint32_t bx = 0; bx < bw; ++bx) {
      for (uint32_t y = 0; y < 4; ++y)
        for (uint32_t x = 0; x < 4; ++x) {
          const uint32_t sx = std::min(4 * bx + x, w - 1), sy = std::min(4 * by + y, h - 1);
          std::copy_n(rgba.data() + (size_t(sy) * w + sx) * 4, 4, texels + 4 * (4 * y + x));
        }
      stb_compress_dxt_block(out.data() + (size_t(by) * bw + bx) * bytes, texels, f == BcFormat::BC3 ? 1 : 0,
                             STB_DXT_HIGHQUAL);
    }
  });
  return out;
}

}  // namespace tessera
