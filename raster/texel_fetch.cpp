// texelFetch on level 0 of a 2D / 2D-array texture for a quad (sample.h, fetchQuad2DArray): the exact
// integer-coordinate read of GL 4.6 §8.9 / §11.1.3.2 (texelFetch), with the oracle's defined value for
// coordinates outside the texture (the twins test against textureSize and return vec4(0)).
// Provenance: a texture rendered in this frame is read through its lower / upper interval images in
// the bound runs, and the pixels where those differ from its value are classed by texelIntervalClass()
// (INPUT_INTERVAL, or BC_INTERPOLANT for an S3TC texture).
#include <cstring>

#include "raster/provenance.h"
#include "raster/sample.h"

namespace tessera {
namespace {

void decode(Format fmt, const uint8_t* p, float out[4]) {
  for (int c = 0; c < 4; ++c) out[c] = c == 3 ? 1.0f : 0.0f;  // Table 15.1 expansion
  const int channels = channelCount(fmt);
  for (int c = 0; c < channels; ++c) {
    if (isUnorm(fmt)) {
      out[c] = float(double(p[c]) / 255.0);  // the value fetchBuffer and the filtered path give
    } else if (isFloat(fmt)) {
      std::memcpy(&out[c], p + 4 * c, 4);
    } else {
      uint32_t v;
      std::memcpy(&v, p + 4 * c, 4);
      out[c] = float(v);
    }
  }
}

}  // namespace

void fetchQuad2DArray(const TexUnit& u, const int64_t x[4], const int64_t y[4], const int64_t layer[4],
                      float out[4][4]) {
  ShadeProvenance& sp = shadeProvenance();
  for (int p = 0; p < 4; ++p) {
    if (u.tex == nullptr) {  // no texture: incomplete (GL 4.6 §11.1.3.5)
      out[p][0] = out[p][1] = out[p][2] = 0.0f, out[p][3] = 1.0f;
      continue;
    }
    const TextureData& tex = *u.tex;
    const TextureDesc& d = tex.desc;
    if (d.kind == TextureKind::Buffer || tex.levels.empty() || x[p] < 0 || y[p] < 0 || layer[p] < 0 ||
        x[p] >= int64_t(d.width) || y[p] >= int64_t(d.height) || layer[p] >= int64_t(d.layers)) {
      for (int c = 0; c < 4; ++c) out[p][c] = 0.0f;
      continue;
    }
    const auto xi = uint32_t(x[p]), yi = uint32_t(y[p]), li = uint32_t(layer[p]);
    decode(d.format, tex.texel(0, li, xi, yi), out[p]);
    if (!tex.prov || !sp.active || sp.bound == SampleBound::Value) continue;
    const TextureData& bound = sp.bound == SampleBound::Lo ? *tex.prov->lo : *tex.prov->hi;
    float b[4];
    decode(d.format, bound.texel(0, li, xi, yi), b);
    if (std::memcmp(b, out[p], sizeof b) != 0)
      sp.classes[size_t(p)] |= texelIntervalClass(d);
    std::memcpy(out[p], b, sizeof b);
  }
}

}  // namespace tessera
