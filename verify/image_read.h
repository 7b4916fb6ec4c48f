// Reading images for the comparison: any file OpenImageIO can read, kept in its stored channel
// types so that integer channels compare exactly and thresholds can be stated in their units.
//
// Implements: subimage 0, MIP level 0 of a flat (non-deep, 2D) image, read with alpha left as
// stored (no premultiplication on read: "oiio:UnassociatedAlpha" = 1), channel types UINT8, INT8,
// UINT16, INT16, UINT32, INT32, HALF, FLOAT, DOUBLE (per channel when the file mixes them).
// Pixels are in file order: the top row first, x to the right, (0, 0) at the data window origin.
// Does not implement: colour management (values are compared as stored), other subimages or levels.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tessera::verify {

enum class ChannelType : uint8_t { UInt8, Int8, UInt16, Int16, UInt32, Int32, Half, Float, Double };

const char* channelTypeName(ChannelType t);
inline bool isIntegerChannel(ChannelType t) { return t <= ChannelType::Int32; }
// Largest value of the type (1 for float types): the peak of PSNR.
double channelPeak(ChannelType t);

struct DecodedImage {
  int32_t width = 0, height = 0;
  int32_t originX = 0, originY = 0;  // data window origin (EXR)
  std::vector<std::string> names;
  std::vector<ChannelType> types;
  std::vector<size_t> offsets;  // byte offset of each channel inside a pixel
  size_t pixelBytes = 0;
  std::vector<uint8_t> bytes;  // width * height * pixelBytes, native little-endian

  int channels() const { return int(types.size()); }
  size_t pixels() const { return size_t(width) * size_t(height); }
  // Channel c of pixel p (file order) as a double: exact for every supported type.
  double value(size_t p, int c) const;
};

struct ReadOutcome {
  std::optional<DecodedImage> image;
  bool unsupported = false;  // readable, but a kind of image the comparison refuses (deep, volume, type)
  std::string error;         // names the file
};

ReadOutcome readImage(const std::string& path);

}  // namespace tessera::verify
