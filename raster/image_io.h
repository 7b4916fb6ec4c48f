// Image files and pixel hashes of render targets.
//
// Implements: writing one level/layer of a texture as PNG (RGBA8, R8) or OpenEXR (RG32F, RGBA32F,
// R32UI as 32-bit uint channels, D32F) through OpenImageIO, atomically (temp file + rename), top
// row first as image files expect; and image_sha256: SHA-256 of exactly those decoded pixels (rows
// top to bottom, channels interleaved, native little-endian for 32-bit channels), so anyone can
// recompute it from the file.
// Does not implement: reading images (the scene loaders do that).
#pragma once

#include <string>
#include <vector>

#include "raster/texture.h"

namespace tessera {

// The pixels of (level, layer) as stored in an image file: top row first.
std::vector<uint8_t> imagePixels(const TextureData& tex, uint32_t level, uint32_t layer);
std::string imageSha256(const TextureData& tex, uint32_t level, uint32_t layer);
// ".png" or ".exr", chosen by format.
std::string imageExtension(Format f);
// Writes the image; throws Error naming the path on failure; never leaves a partial file.
void writeImage(const TextureData& tex, uint32_t level, uint32_t layer, const std::string& path);
// A decoded image file: pixels top row first, channels interleaved, as imagePixels() lays them out.
struct DecodedImage {
  int width = 0, height = 0, channels = 0;
  int bitsPerChannel = 0;  // 8, or 32 for float / uint
  bool isFloat = false;
  std::vector<uint8_t> pixels;
};
// Reads a PNG / EXR written by writeImage (or any OIIO-readable file); throws Error naming the path.
DecodedImage readImage(const std::string& path);

// Writes tightly packed RGBA8 rows (top row first) as PNG, atomically.
void writePngRGBA8(const std::string& path, int width, int height, const uint8_t* topDownRows);

// Writes tightly packed 8-bit rows (top row first, 1-4 channels, alpha unassociated) in the format
// that the extension of `path` names (.png, .jpg, ...), atomically (base/atomic_file.h).
struct Image8Options {
  int jpegQuality = 0;           // > 0: JPEG "Compression" quality
  int pngCompressionLevel = -1;  // >= 0: zlib level for PNG
};
void writeImage8(const std::string& path, int width, int height, int channels, const uint8_t* topDownRows,
                 const Image8Options& options = {});

}  // namespace tessera
