#include "raster/image_io.h"

#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstring>

#include "base/atomic_file.h"
#include "base/sha256.h"

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

void writeAtomically(const std::string& path, const OIIO::ImageSpec& spec, const void* pixels) {
  writeFileAtomically(path, [&](const std::string& tmp) {
    auto out = OIIO::ImageOutput::create(path);  // format from the final name's extension
    if (!out) throw Error(path + ": cannot create an image writer: " + OIIO::geterror());
    if (!out->open(tmp, spec)) throw Error(path + ": cannot open for writing: " + out->geterror());
    if (!out->write_image(spec.format, pixels) || !out->close()) throw Error(path + ": write failed: " + out->geterror());
  });
}

}  // namespace

void writeImage(const TextureData& tex, uint32_t level, uint32_t layer, const std::string& path) {
  const uint32_t w = levelWidth(tex.desc, level), h = levelHeight(tex.desc, level);
  const auto px = imagePixels(tex, level, layer);
  OIIO::TypeDesc type;
  switch (tex.desc.format) {
    case Format::RGBA8:
    case Format::R8: type = OIIO::TypeDesc::UINT8; break;
    case Format::R32UI: type = OIIO::TypeDesc::UINT32; break;
    default: type = OIIO::TypeDesc::FLOAT; break;
  }
  OIIO::ImageSpec spec(int(w), int(h), channelCount(tex.desc.format), type);
  if (tex.desc.format == Format::R32UI) spec.channelnames = {"id"};
  if (tex.desc.format == Format::RGBA8) {
    spec.alpha_channel = 3;
    // Our pixels are what the target holds; without this OIIO would "un-premultiply" them on the way
    // into PNG and the file would no longer match image_sha256.
    spec.attribute("oiio:UnassociatedAlpha", 1);
  }
  // OIIO's OpenEXR writer stamps the current time as "DateTime" unless the spec names one, and an
  // empty value means none. Without this the same frame gave different EXR bytes on every run, so a
  // file hash could not stand for the frame as the PNGs' hashes do.
  spec.attribute("DateTime", "");
  writeAtomically(path, spec, px.data());
}

DecodedImage readImage(const std::string& path) {
  // Read PNG alpha as stored: without this OIIO premultiplies colour by alpha on input.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) throw Error(path + ": cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  DecodedImage img;
  img.width = spec.width;
  img.height = spec.height;
  img.channels = spec.nchannels;
  OIIO::TypeDesc type = spec.format;
  if (type == OIIO::TypeDesc::UINT8) {
    img.bitsPerChannel = 8;
  } else if (type == OIIO::TypeDesc::UINT32 || type == OIIO::TypeDesc::INT32) {
    img.bitsPerChannel = 32;
    type = OIIO::TypeDesc::UINT32;
  } else {
    img.bitsPerChannel = 32;
    img.isFloat = true;
    type = OIIO::TypeDesc::FLOAT;
  }
  img.pixels.resize(size_t(img.width) * img.height * img.channels * (img.bitsPerChannel / 8));
  if (!in->read_image(0, 0, 0, img.channels, type, img.pixels.data()))
    throw Error(path + ": cannot decode image: " + in->geterror());
  return img;
}

void writePngRGBA8(const std::string& path, int width, int height, const uint8_t* topDownRows) {
  writeImage8(path, width, height, 4, topDownRows);
}

void writeImage8(const std::string& path, int width, int height, int channels, const uint8_t* topDownRows,
                 const Image8Options& options) {
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
  if (channels == 4) {
    spec.alpha_channel = 3;
    spec.attribute("oiio:UnassociatedAlpha", 1);  // store alpha as given, colour not premultiplied
  }
  if (options.jpegQuality > 0) spec.attribute("Compression", "jpeg:" + std::to_string(options.jpegQuality));
  if (options.pngCompressionLevel >= 0) spec.attribute("png:compressionLevel", options.pngCompressionLevel);
  writeAtomically(path, spec, topDownRows);
}

}  // namespace tessera
