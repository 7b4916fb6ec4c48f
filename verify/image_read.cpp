#include "verify/image_read.h"

#include <cmath>
#include <cstring>
#include <limits>

#include "raster/image_module.h"

namespace tessera::verify {

namespace {

size_t typeBytes(ChannelType t) {
  switch (t) {
    case ChannelType::UInt8:
    case ChannelType::Int8:
      return 1;
    case ChannelType::UInt16:
    case ChannelType::Int16:
    case ChannelType::Half:
      return 2;
    case ChannelType::UInt32:
    case ChannelType::Int32:
    case ChannelType::Float:
      return 4;
    case ChannelType::Double:
      return 8;
  }
  return 0;
}

std::optional<ChannelType> fromModule(imagemod::Type t) {
  switch (t) {
    case imagemod::Type::U8: return ChannelType::UInt8;
    case imagemod::Type::I8: return ChannelType::Int8;
    case imagemod::Type::U16: return ChannelType::UInt16;
    case imagemod::Type::I16: return ChannelType::Int16;
    case imagemod::Type::U32: return ChannelType::UInt32;
    case imagemod::Type::I32: return ChannelType::Int32;
    case imagemod::Type::Half: return ChannelType::Half;
    case imagemod::Type::Float: return ChannelType::Float;
    case imagemod::Type::Double: return ChannelType::Double;
    default: return std::nullopt;
  }
}

// IEEE binary16 -> double, exact (every half is a double).
double halfToDouble(uint16_t h) {
  const int sign = h >> 15, exp = (h >> 10) & 0x1f, mant = h & 0x3ff;
  double v;
  if (exp == 0) {
    v = std::ldexp(double(mant), -24);
  } else if (exp == 31) {
    v = mant ? std::numeric_limits<double>::quiet_NaN() : std::numeric_limits<double>::infinity();
  } else {
    v = std::ldexp(double(mant | 0x400), exp - 25);
  }
  return sign ? -v : v;
}

template <typename T>
T load(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

}  // namespace

const char* channelTypeName(ChannelType t) {
  switch (t) {
    case ChannelType::UInt8:
      return "uint8";
    case ChannelType::Int8:
      return "int8";
    case ChannelType::UInt16:
      return "uint16";
    case ChannelType::Int16:
      return "int16";
    case ChannelType::UInt32:
      return "uint32";
    case ChannelType::Int32:
      return "int32";
    case ChannelType::Half:
      return "half";
    case ChannelType::Float:
      return "float";
    case ChannelType::Double:
      return "double";
  }
  return "?";
}

double channelPeak(ChannelType t) {
  switch (t) {
    case ChannelType::UInt8:
      return 255.0;
    case ChannelType::Int8:
      return 127.0;
    case ChannelType::UInt16:
      return 65535.0;
    case ChannelType::Int16:
      return 32767.0;
    case ChannelType::UInt32:
      return 4294967295.0;
    case ChannelType::Int32:
      return 2147483647.0;
    default:
      return 1.0;
  }
}

double DecodedImage::value(size_t p, int c) const {
  const uint8_t* q = bytes.data() + p * pixelBytes + offsets[size_t(c)];
  switch (types[size_t(c)]) {
    case ChannelType::UInt8:
      return *q;
    case ChannelType::Int8:
      return load<int8_t>(q);
    case ChannelType::UInt16:
      return load<uint16_t>(q);
    case ChannelType::Int16:
      return load<int16_t>(q);
    case ChannelType::UInt32:
      return load<uint32_t>(q);
    case ChannelType::Int32:
      return load<int32_t>(q);
    case ChannelType::Half:
      return halfToDouble(load<uint16_t>(q));
    case ChannelType::Float:
      return load<float>(q);
    case ChannelType::Double:
      return load<double>(q);
  }
  return 0.0;
}

ReadOutcome readImage(const std::string& path) {
  ReadOutcome out;
  // Compare what the file stores: the module reads colour as stored, never premultiplied by alpha.
  std::string error;
  const std::unique_ptr<imagemod::Reader> in = imagemod::api().open(path, error);
  if (!in) {
    out.error = "cannot read '" + path + "': " + error;
    return out;
  }
  const imagemod::Header& hd = in->header();
  if (hd.deepOrVolume) {
    out.unsupported = true;
    out.error = "'" + path + "' is a deep or volume image (only flat 2D images are compared)";
    return out;
  }
  DecodedImage img;
  img.width = hd.width, img.height = hd.height;
  img.originX = hd.x, img.originY = hd.y;
  for (int c = 0; c < hd.channels; ++c) {
    const auto t = fromModule(hd.channelTypes[size_t(c)]);
    if (!t) {
      out.unsupported = true;
      out.error = "'" + path + "' channel " + std::to_string(c) + " has the unsupported type " + hd.channelTypeNames[size_t(c)];
      return out;
    }
    img.names.push_back(c < int(hd.channelNames.size()) ? hd.channelNames[size_t(c)] : "ch" + std::to_string(c));
    img.types.push_back(*t);
    img.offsets.push_back(img.pixelBytes);
    img.pixelBytes += typeBytes(*t);
  }
  img.bytes.resize(img.pixels() * img.pixelBytes);
  // Type::Unknown = the file's own per-channel types, packed: no conversion, no rounding.
  if (const std::string e = in->read(imagemod::Type::Unknown, img.bytes.data()); !e.empty()) {
    out.error = "cannot read the pixels of '" + path + "': " + e;
    return out;
  }
  out.image = std::move(img);
  return out;
}

}  // namespace tessera::verify
