// An RGBA8 image in memory, and the one row order every such image in the project uses.
//
// Implements: RgbaImage (width x height texels, 4 bytes each, tightly packed, row 0 first) and a texel
// setter.
// Does not implement: other formats, mip chains (raster/texture.h), image files (model::loadTexture
// decodes, raster/image_io.h writes rendered frames).
//
// Row order: row 0 is the row that texture coordinate t = 0 addresses, which is also the row that GL's
// glTexSubImage takes first (GL calls it the bottom row). Every texture upload passes `rgba` as it is;
// no code flips the rows of an RgbaImage.
// - A decoded image file keeps the file's order, so row 0 is the file's top row. That needs no
//   conversion because model/ stores texcoords with v = 0 at that row (glTF's convention; the OBJ and
//   Assimp loaders flip v, never pixels), and GL's t is v (docs/model-import.md).
// - An image drawn by code (tools/scenes) counts y from row 0 = t = 0 up, as GL's window does.
// The one place where rows are reversed is writing a rendered frame to a file (raster/image_io.h:
// GL's bottom row first in memory, the top row first in the file); that is not an RgbaImage.
//
// Why base/: model/ (decoding, model::Image adds what the file said), mta/ (the atlas build's input)
// and tools/scenes (procedural textures) share it, and none of them should depend on another for a
// plain pixel container; raster/ keeps texels as TextureData levels and spans and needs no image type.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

namespace tessera {

struct RgbaImage {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4 bytes, row 0 first (see above)

  // Texel (x, y), y counted from row 0. Precondition: x < width, y < height, rgba is full size.
  void set(uint32_t x, uint32_t y, std::array<uint8_t, 4> c) {
    std::memcpy(&rgba[(size_t(y) * width + x) * 4], c.data(), 4);
  }
};

}  // namespace tessera
