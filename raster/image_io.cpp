#include "raster/image_io.h"

#include <cstdio>
#include <cstring>

#include "base/atomic_file.h"
#include "base/sha256.h"
#include "raster/image_module.h"

namespace tessera {

std::vector<uint8_t> imagePixels(const TextureData& tex, uint32_t level, uint32_t layer) {
  const uint32_t w = levelWidth(tex.desc, level), h = levelHeight(tex.desc, level);
  const size_t row = size_t(w) * texelBytes(tex.desc.format);
  std::vector<uint8_t> out(row * h);
  for (uint32_t y = 0; y < h; ++y)  // GL rows are bottom-up; files are top-down
    std::memcpy(out.data() + size_t(h - 1 - y) * row, tex.texel(level, layer, 0, y), row);
  return out;
}

std::string imageSha256(const TextureData& tex, uint32_t level, uint32_t layer) {
  const auto px = imagePixels(tex, level, layer);
  return sha256Hex(px);
}

std::string imageExtension(Format f) { return isUnorm(f) ? ".png" : ".exr"; }

namespace {

void writeAtomically(const std::string& path, const imagemod::WriteSpec& spec, const void* pixels) {
  const imagemod::Api& api = imagemod::api();
  writeFileAtomically(path, [&](const std::string& tmp) {
    const std::string error = api.write(path, tmp, spec, pixels);  // format from the final name's extension
    if (!error.empty()) throw Error(path + ": " + error);
  });
}

}  // namespace

void writeImage(const TextureData& tex, uint32_t level, uint32_t layer, const std::string& path) {
  const uint32_t w = levelWidth(tex.desc, level), h = levelHeight(tex.desc, level);
  const auto px = imagePixels(tex, level, layer);
  imagemod::WriteSpec spec;
  spec.width = int(w), spec.height = int(h), spec.channels = channelCount(tex.desc.format);
  switch (tex.desc.format) {
    case Format::RGBA8:
    case Format::R8: spec.type = imagemod::Type::U8; break;
    case Format::R32UI: spec.type = imagemod::Type::U32; break;
    default: spec.type = imagemod::Type::Float; break;
  }
  if (tex.desc.format == Format::R32UI) spec.firstChannelName = "id";
  spec.alphaLast = tex.desc.format == Format::RGBA8;
  // OIIO's OpenEXR writer stamps the current time as "DateTime" unless the spec names one, and an
  // empty value means none. Without this the same frame gave different EXR bytes on every run, so a
  // file hash could not stand for the frame as the PNGs' hashes do.
  spec.emptyDateTime = true;
  writeAtomically(path, spec, px.data());
}

DecodedImage readImage(const std::string& path) {
  std::string error;
  const std::unique_ptr<imagemod::Reader> in = imagemod::api().open(path, error);  // alpha as stored
  if (!in) throw Error(path + ": cannot read image: " + error);
  const imagemod::Header& hd = in->header();
  DecodedImage img;
  img.width = hd.width;
  img.height = hd.height;
  img.channels = hd.channels;
  const imagemod::Type stored = hd.format;
  imagemod::Type type;
  if (stored == imagemod::Type::U8) {
    img.bitsPerChannel = 8;
    type = imagemod::Type::U8;
  } else if (stored == imagemod::Type::U32 || stored == imagemod::Type::I32) {
    img.bitsPerChannel = 32;
    type = imagemod::Type::U32;
  } else {
    img.bitsPerChannel = 32;
    img.isFloat = true;
    type = imagemod::Type::Float;
  }
  img.pixels.resize(size_t(img.width) * img.height * img.channels * (img.bitsPerChannel / 8));
  if (const std::string e = in->read(type, img.pixels.data()); !e.empty()) throw Error(path + ": cannot decode image: " + e);
  return img;
}

void writePngRGBA8(const std::string& path, int width, int height, const uint8_t* topDownRows) {
  writeImage8(path, width, height, 4, topDownRows);
}

void writeImage8(const std::string& path, int width, int height, int channels, const uint8_t* topDownRows,
                 const Image8Options& options) {
  imagemod::WriteSpec spec;
  spec.width = width, spec.height = height, spec.channels = channels;
  spec.type = imagemod::Type::U8;
  spec.alphaLast = channels == 4;  // store alpha as given, colour not premultiplied
  spec.jpegQuality = options.jpegQuality;
  spec.pngCompressionLevel = options.pngCompressionLevel;
  writeAtomically(path, spec, topDownRows);
}

}  // namespace tessera
