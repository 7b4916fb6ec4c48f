// libtessera_image_module.so: the only code that includes OpenImageIO (raster/image_module.h says
// why it is loaded on demand). Self-contained on purpose: it links OIIO and the C++ runtime only, so
// the static libraries of the project need not be compiled position-independent for it.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "raster/image_module.h"

namespace tessera::imagemod {
namespace {

Type fromOiio(OIIO::TypeDesc t) {
  switch (t.basetype) {
    case OIIO::TypeDesc::UINT8: return Type::U8;
    case OIIO::TypeDesc::INT8: return Type::I8;
    case OIIO::TypeDesc::UINT16: return Type::U16;
    case OIIO::TypeDesc::INT16: return Type::I16;
    case OIIO::TypeDesc::UINT32: return Type::U32;
    case OIIO::TypeDesc::INT32: return Type::I32;
    case OIIO::TypeDesc::HALF: return Type::Half;
    case OIIO::TypeDesc::FLOAT: return Type::Float;
    case OIIO::TypeDesc::DOUBLE: return Type::Double;
    default: return Type::Other;
  }
}

OIIO::TypeDesc toOiio(Type t) {
  switch (t) {
    case Type::U8: return OIIO::TypeDesc::UINT8;
    case Type::I8: return OIIO::TypeDesc::INT8;
    case Type::U16: return OIIO::TypeDesc::UINT16;
    case Type::I16: return OIIO::TypeDesc::INT16;
    case Type::U32: return OIIO::TypeDesc::UINT32;
    case Type::I32: return OIIO::TypeDesc::INT32;
    case Type::Half: return OIIO::TypeDesc::HALF;
    case Type::Float: return OIIO::TypeDesc::FLOAT;
    case Type::Double: return OIIO::TypeDesc::DOUBLE;
    default: return OIIO::TypeDesc::UNKNOWN;  // read: each channel's own type
  }
}

// Colour as stored: without this hint OIIO premultiplies PNG colour by alpha on input.
OIIO::ImageSpec readConfig() {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  return config;
}

class OiioReader final : public Reader {
 public:
  OiioReader(std::unique_ptr<OIIO::ImageInput> in, std::unique_ptr<OIIO::Filesystem::IOMemReader> proxy)
      : proxy_(std::move(proxy)), in_(std::move(in)) {
    const OIIO::ImageSpec& s = in_->spec();
    h_.width = s.width, h_.height = s.height, h_.channels = s.nchannels;
    h_.x = s.x, h_.y = s.y;
    h_.alphaChannel = s.alpha_channel;
    h_.deepOrVolume = s.deep || s.depth > 1;
    h_.format = fromOiio(s.format);
    for (int c = 0; c < s.nchannels; ++c) {
      h_.channelTypes.push_back(fromOiio(s.channelformat(c)));
      h_.channelTypeNames.push_back(s.channelformat(c).c_str());
      if (c < int(s.channelnames.size())) h_.channelNames.push_back(s.channelnames[size_t(c)]);
    }
    h_.formatName = in_->format_name();
  }
  ~OiioReader() override { in_->close(); }
  const Header& header() const override { return h_; }
  std::string read(Type type, void* out) override {
    // OpenImageIO 2.4 reads through a temporary buffer of about 64 MiB per image whenever a type is
    // requested, even the file's own; TypeDesc::UNKNOWN (the native type) reads straight into `out`.
    // Asking for UNKNOWN when the requested type is the native one of every channel gives the same
    // bytes without that buffer (under ASan each one was a 64 MiB memset and its page faults).
    const OIIO::ImageSpec& s = in_->spec();
    const bool native = s.channelformats.empty() && s.format == toOiio(type);
    if (in_->read_image(0, 0, 0, h_.channels, native ? OIIO::TypeDesc(OIIO::TypeDesc::UNKNOWN) : toOiio(type), out))
      return {};
    const std::string e = in_->geterror();
    return e.empty() ? std::string("decoding failed") : e;
  }

 private:
  Header h_;
  std::unique_ptr<OIIO::Filesystem::IOMemReader> proxy_;  // outlives in_ (declared first)
  std::unique_ptr<OIIO::ImageInput> in_;
};

std::unique_ptr<Reader> openFile(const std::string& path, std::string& error) {
  const OIIO::ImageSpec config = readConfig();
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) {
    error = OIIO::geterror();
    if (error.empty()) error = "no reader for this file";
    return nullptr;
  }
  return std::make_unique<OiioReader>(std::move(in), nullptr);
}

std::unique_ptr<Reader> openMemory(const uint8_t* data, size_t size, const std::string& ext, std::string& error) {
  error.clear();
  auto probe = OIIO::ImageInput::create("x." + ext);
  if (!probe || !probe->supports("ioproxy")) return nullptr;  // the caller uses a temporary file
  auto proxy = std::make_unique<OIIO::Filesystem::IOMemReader>(data, size);
  const OIIO::ImageSpec config = readConfig();
  auto in = OIIO::ImageInput::open("memory." + ext, &config, proxy.get());
  if (!in) {
    error = OIIO::geterror();
    if (error.empty()) error = "cannot decode the bytes as " + ext;
    return nullptr;
  }
  return std::make_unique<OiioReader>(std::move(in), std::move(proxy));
}

std::string write(const std::string& formatPath, const std::string& file, const WriteSpec& w, const void* pixels) {
  OIIO::ImageSpec spec(w.width, w.height, w.channels, toOiio(w.type));
  if (!w.firstChannelName.empty() && w.channels == 1) spec.channelnames = {w.firstChannelName};
  if (w.alphaLast) {
    spec.alpha_channel = w.channels - 1;
    // Pixels are what the target holds; without this OIIO would "un-premultiply" them on the way into
    // PNG and the file would no longer match the frame's image_sha256.
    spec.attribute("oiio:UnassociatedAlpha", 1);
  }
  if (w.jpegQuality > 0) spec.attribute("Compression", "jpeg:" + std::to_string(w.jpegQuality));
  if (w.pngCompressionLevel >= 0) spec.attribute("png:compressionLevel", w.pngCompressionLevel);
  if (w.emptyDateTime) spec.attribute("DateTime", "");
  auto out = OIIO::ImageOutput::create(formatPath);  // format from the final name's extension
  if (!out) return "cannot create an image writer: " + OIIO::geterror();
  if (!out->open(file, spec)) return "cannot open for writing: " + out->geterror();
  if (!out->write_image(spec.format, pixels) || !out->close()) return "write failed: " + out->geterror();
  return {};
}

const Api kApi{kAbi, &openFile, &openMemory, &write};

}  // namespace
}  // namespace tessera::imagemod

extern "C" __attribute__((visibility("default"))) const tessera::imagemod::Api* tessera_image_module_api() {
  return &tessera::imagemod::kApi;
}
