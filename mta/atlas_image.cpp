#include "mta/atlas_image.h"

#include <algorithm>
#include <cmath>

#include "raster/texture.h"

namespace tessera::mta {

uint64_t MipImage::bytes() const {
  uint64_t b = 0;
  for (const auto& l : levels) b += l.size();
  return b;
}

MipImage makeMipImage(const RgbaImage& img) {
  MipImage m;
  m.width = img.width;
  m.height = img.height;
  m.levels = buildMipChainRGBA8(img.width, img.height, img.rgba);
  return m;
}

namespace {

int64_t wrapIndex(int64_t i, int64_t n, model::Wrap w) {
  switch (w) {
    case model::Wrap::ClampToEdge:
      return std::clamp<int64_t>(i, 0, n - 1);
    case model::Wrap::MirroredRepeat: {
      int64_t m = i % (2 * n);
      if (m < 0) m += 2 * n;
      return m < n ? m : 2 * n - 1 - m;
    }
    case model::Wrap::Repeat:
    default: {
      int64_t m = i % n;
      return m < 0 ? m + n : m;
    }
  }
}

// Texel coordinate and 8-bit weight of the second tap (spec choice T7's rule).
void taps(double u, uint32_t size, int64_t& i0, uint32_t& a8) {
  double x = u * double(size) - 0.5;
  x = std::clamp(x, -4503599627370496.0, 4503599627370496.0);  // ±2^52, also maps NaN-free inputs safely
  const double f = std::floor(x);
  i0 = int64_t(f);
  a8 = uint32_t(std::nearbyint((x - f) * 256.0));  // default rounding mode: half to even
}

uint32_t rneShift(uint64_t sum, int shift) {
  const uint64_t q = sum >> shift, r = sum & ((uint64_t(1) << shift) - 1), half = uint64_t(1) << (shift - 1);
  return uint32_t(q + ((r > half || (r == half && (q & 1))) ? 1 : 0));
}

}  // namespace

void fillArea(uint8_t* atlas, uint32_t A, uint32_t channels, uint32_t x0, uint32_t y0, uint32_t w, uint32_t h,
              const AffineMap& m, const MipImage& img, model::Wrap wrapS, model::Wrap wrapT) {
  // Footprint in level-0 texels per atlas texel (max over the two atlas axes), fixed for the area.
  const double fx = std::sqrt(m.ux * m.ux * img.width * img.width + m.vx * m.vx * img.height * img.height);
  const double fy = std::sqrt(m.uy * m.uy * img.width * img.width + m.vy * m.vy * img.height * img.height);
  const double rho = std::max(fx, fy);
  uint32_t level = 0;
  while (level + 1 < img.levels.size() && double(uint64_t(2) << level) <= rho) ++level;
  const uint32_t lw = std::max(1u, img.width >> level), lh = std::max(1u, img.height >> level);
  const uint8_t* src = img.levels[level].data();
  for (uint32_t y = y0; y < y0 + h; ++y)
    for (uint32_t x = x0; x < x0 + w; ++x) {
      const double cx = x + 0.5, cy = y + 0.5;
      const double u = m.u0 + m.ux * cx + m.uy * cy, v = m.v0 + m.vx * cx + m.vy * cy;
      int64_t i0, j0;
      uint32_t ax, ay;
      taps(u, lw, i0, ax);
      taps(v, lh, j0, ay);
      const int64_t i[2] = {wrapIndex(i0, lw, wrapS), wrapIndex(i0 + 1, lw, wrapS)};
      const int64_t j[2] = {wrapIndex(j0, lh, wrapT), wrapIndex(j0 + 1, lh, wrapT)};
      const uint32_t wx[2] = {256 - ax, ax}, wy[2] = {256 - ay, ay};
      uint8_t* dst = atlas + (size_t(y) * A + x) * channels;
      for (uint32_t c = 0; c < channels; ++c) {
        uint64_t sum = 0;
        for (int b = 0; b < 2; ++b)
          for (int a = 0; a < 2; ++a) sum += uint64_t(wx[a] * wy[b]) * src[(size_t(j[b]) * lw + size_t(i[a])) * 4 + c];
        dst[c] = uint8_t(rneShift(sum, 16));
      }
    }
}

std::vector<uint8_t> blankAtlas(uint32_t A, uint32_t channels, uint32_t layer) {
  return std::vector<uint8_t>(size_t(A) * A * channels, layer == 0 ? 0 : 255);
}

void downsampleIntoQuadrant(const uint8_t* child, uint8_t* parent, uint32_t A, uint32_t channels, int q) {
  const uint32_t half = A / 2, ox = (q & 1) * half, oy = (q >> 1) * half;
  for (uint32_t y = 0; y < half; ++y)
    for (uint32_t x = 0; x < half; ++x) {
      const uint8_t* a = child + (size_t(2 * y) * A + 2 * x) * channels;
      const uint8_t* b = a + size_t(A) * channels;
      uint8_t* d = parent + (size_t(oy + y) * A + ox + x) * channels;
      for (uint32_t c = 0; c < channels; ++c)
        d[c] = uint8_t(rneShift(uint64_t(a[c]) + a[channels + c] + b[c] + b[channels + c], 2));
    }
}

}  // namespace tessera::mta
