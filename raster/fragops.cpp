#include "raster/fragops.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "raster/setup.h"

namespace tessera::detail {

namespace {

inline double clamp01(double v) { return v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0; }  // NaN -> 0

// Blend factor for channel k (0-2 colour, 3 alpha), GL 4.6 Table 17.2.
inline double factor(BlendFactor f, int k, const double s[4], const double d[4], const double c[4]) {
  switch (f) {
    case BlendFactor::Zero: return 0.0;
    case BlendFactor::One: return 1.0;
    case BlendFactor::SrcColor: return s[k];
    case BlendFactor::OneMinusSrcColor: return 1.0 - s[k];
    case BlendFactor::DstColor: return d[k];
    case BlendFactor::OneMinusDstColor: return 1.0 - d[k];
    case BlendFactor::SrcAlpha: return s[3];
    case BlendFactor::OneMinusSrcAlpha: return 1.0 - s[3];
    case BlendFactor::DstAlpha: return d[3];
    case BlendFactor::OneMinusDstAlpha: return 1.0 - d[3];
    case BlendFactor::ConstantColor: return c[k];
    case BlendFactor::OneMinusConstantColor: return 1.0 - c[k];
    case BlendFactor::ConstantAlpha: return c[3];
    case BlendFactor::OneMinusConstantAlpha: return 1.0 - c[3];
    case BlendFactor::SrcAlphaSaturate: return k == 3 ? 1.0 : std::min(s[3], 1.0 - d[3]);
    default: return 0.0;
  }
}

inline double equation(BlendEq e, double s, double fs, double d, double fd) {
  switch (e) {
    case BlendEq::Add: return s * fs + d * fd;
    case BlendEq::Subtract: return s * fs - d * fd;
    case BlendEq::ReverseSubtract: return d * fd - s * fs;
    case BlendEq::Min: return std::min(s, d);  // factors ignored (§17.3.6.2)
    case BlendEq::Max: return std::max(s, d);
    default: return 0.0;
  }
}

}  // namespace

void blend(const BlendState& b, bool unorm, const float src[4], const double dst[4], double out[4]) {
  double s[4], d[4], c[4];
  for (int k = 0; k < 4; ++k) {
    s[k] = unorm ? clamp01(src[k]) : double(src[k]);
    d[k] = unorm ? clamp01(dst[k]) : dst[k];
    c[k] = unorm ? clamp01(b.constant[k]) : double(b.constant[k]);
  }
  for (int k = 0; k < 4; ++k) {
    const bool alpha = k == 3;
    const BlendFactor fsrc = alpha ? b.srcAlpha : b.srcRgb, fdst = alpha ? b.dstAlpha : b.dstRgb;
    double fs = factor(fsrc, k, s, d, c), fd = factor(fdst, k, s, d, c);
    if (unorm) fs = clamp01(fs), fd = clamp01(fd);
    double r = equation(alpha ? b.eqAlpha : b.eqRgb, s[k], fs, d[k], fd);
    out[k] = unorm ? clamp01(r) : r;
  }
}

void writeFragment(Format f, uint8_t* texel, const uint32_t bits[4], const BlendState& b) {
  float src[4];
  std::memcpy(src, bits, sizeof src);
  switch (f) {
    case Format::RGBA8:
    case Format::R8: {
      const int n = f == Format::RGBA8 ? 4 : 1;
      if (!b.enabled) {
        for (int k = 0; k < n; ++k) texel[k] = toUnorm8(src[k]);
        return;
      }
      // Missing destination channels read as (0, 0, 0, 1) (GL 4.6 §17.3.6, Table 15.1 for R8).
      double dst[4] = {0, 0, 0, 1}, out[4];
      for (int k = 0; k < n; ++k) dst[k] = kUnorm8ToDouble.v[texel[k]];
      blend(b, true, src, dst, out);
      for (int k = 0; k < n; ++k) texel[k] = toUnorm8(out[k]);
      return;
    }
    case Format::RG32F:
    case Format::RGBA32F: {
      const int n = f == Format::RGBA32F ? 4 : 2;
      if (!b.enabled) {
        std::memcpy(texel, src, sizeof(float) * size_t(n));
        return;
      }
      double dst[4] = {0, 0, 0, 1}, out[4];
      float cur[4];
      std::memcpy(cur, texel, sizeof(float) * size_t(n));
      for (int k = 0; k < n; ++k) dst[k] = cur[k];
      blend(b, false, src, dst, out);
      for (int k = 0; k < n; ++k) cur[k] = float(out[k]);
      std::memcpy(texel, cur, sizeof(float) * size_t(n));
      return;
    }
    case Format::R32UI:
      std::memcpy(texel, bits, 4);  // integer targets are never blended (GL 4.6 §17.3.6)
      return;
    default:
      return;
  }
}

}  // namespace tessera::detail
