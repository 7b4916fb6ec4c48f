// Test helpers shared by the texture tests (test_mipchain.cpp, test_sample.cpp): the description of a 2D
// or 2D-array texture, and float texels written straight into a level. Nothing here samples or filters.
#pragma once

#include <cstdint>
#include <cstring>
#include <initializer_list>

#include "raster/texture.h"

namespace tessera::testing {

// A 2D texture, or a 2D array when `layers` > 1.
inline TextureDesc desc2D(Format f, uint32_t w, uint32_t h, uint32_t levels = 1, uint32_t layers = 1) {
  TextureDesc d;
  d.kind = layers > 1 ? TextureKind::Tex2DArray : TextureKind::Tex2D;
  d.format = f;
  d.width = w;
  d.height = h;
  d.levels = levels;
  d.layers = layers;
  return d;
}

// Writes the float channels `v` of texel (x, y) of `level` and `layer` (an R32F / RG32F / RGBA32F texture).
inline void setF32(TextureData& t, uint32_t level, uint32_t layer, uint32_t x, uint32_t y,
                   std::initializer_list<float> v) {
  std::memcpy(t.texel(level, layer, x, y), v.begin(), v.size() * sizeof(float));
}

}  // namespace tessera::testing
