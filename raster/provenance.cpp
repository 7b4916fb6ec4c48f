#include "raster/provenance.h"

#include "raster/texture.h"

namespace tessera {

uint16_t texelIntervalClass(const TextureDesc& d) {
  return d.compression != BcFormat::None ? uint16_t(kBcInterpolant) : uint16_t(kInputInterval);
}

std::string_view ambiguityClassName(int bit) {
  static constexpr std::string_view kNames[kClassCount] = {
      "EDGE_TIE",         "CLIP_EDGE", "LOD_NEAR_SWITCH",  "SUBTEXEL_NEAR_HALF", "LAYER_TIE",     "DEPTH_NEAR_EQUAL",
      "OOB_FETCH",        "HELPER_DERIV", "FILTER_PRECISION", "BLEND_PRECISION", "OUTPUT_ROUNDING",
      "INPUT_INTERVAL",   "ALPHA_TEST", "BC_INTERPOLANT"};
  return bit >= 0 && bit < kClassCount ? kNames[bit] : std::string_view("?");
}

Provenance::Provenance(const TextureData& tex)
    : lo(std::make_unique<TextureData>(tex.desc)), hi(std::make_unique<TextureData>(tex.desc)) {
  lo->levels = tex.levels;
  hi->levels = tex.levels;
  for (uint32_t l = 0; l < tex.levels.size(); ++l) {
    const size_t n = size_t(levelWidth(tex.desc, l)) * levelHeight(tex.desc, l) * tex.desc.layers;
    classes.emplace_back(n, uint16_t(0));
    flags.emplace_back(n, uint8_t(0));
    candidates.emplace_back(n);
    depth.emplace_back(n);
  }
}

size_t Provenance::index(const TextureData& tex, uint32_t level, uint32_t layer, uint32_t x, uint32_t y) const {
  const uint32_t w = levelWidth(tex.desc, level), h = levelHeight(tex.desc, level);
  return (size_t(layer) * h + y) * w + x;
}

uint16_t& Provenance::cls(const TextureData& tex, uint32_t level, uint32_t layer, uint32_t x, uint32_t y) {
  return classes[level][index(tex, level, layer, x, y)];
}

ShadeProvenance& shadeProvenance() {
  thread_local ShadeProvenance p;
  return p;
}

}  // namespace tessera
