// The image module: every image file the project reads or writes goes through OpenImageIO, and OIIO is
// loaded only when a process first needs it (dlopen of tessera's own libtessera_image_module.so).
//
// Why: Debian's libOpenImageIO pulls in about 260 shared libraries (OpenCV, FFmpeg, GDAL, GStreamer,
// ...). Linked normally, every process paid for loading and relocating them at start: about 0.5 s of
// CPU, before main(). Each GoogleTest case runs in its own process and the suite starts a process per
// step, so that was about half of the Release test run's CPU time. Now a process that touches no image
// file (most tests, every refused command line) starts in milliseconds, and one that does pays once.
//
// Implements: the interface below (no OIIO type crosses it), and api(), which loads the module on the
// first call (thread-safe) from TESSERA_IMAGE_MODULE if set, else from the path the build wrote into
// the binary, else from beside the executable. The module itself is raster/image_module_oiio.cpp.
// Does not: choose formats or pixel rules (raster/image_io.cpp, verify/image_read.cpp and
// model/model.cpp do, as before), or unload the module (readers it made must stay valid).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace tessera::imagemod {

// A channel's type, as stored in a file or as requested from a reader. Unknown in a read request means
// "each channel in its own stored type, packed" (no conversion).
enum class Type : uint8_t { Unknown, U8, I8, U16, I16, U32, I32, Half, Float, Double, Other };

struct Header {
  int width = 0, height = 0, channels = 0;
  int x = 0, y = 0;          // data window origin
  int alphaChannel = -1;     // -1: none named
  bool deepOrVolume = false;
  Type format = Type::Other;            // OIIO's spec.format: the image's data type
  std::vector<Type> channelTypes;       // per channel
  std::vector<std::string> channelTypeNames;  // OIIO's spelling, for messages about Other
  std::vector<std::string> channelNames;      // as the file names them (may be fewer than channels)
  std::string formatName;  // "png", "openexr", "jpeg", ...
};

// An open image (subimage 0, mip level 0). Colour is read as stored: never premultiplied by alpha.
class Reader {
 public:
  virtual ~Reader() = default;
  virtual const Header& header() const = 0;
  // Reads every channel as `type` into out (width * height * channels values, top row first). Returns
  // "" or the reader's error.
  virtual std::string read(Type type, void* out) = 0;
};

struct WriteSpec {
  int width = 0, height = 0, channels = 0;
  Type type = Type::U8;           // U8, U32 or Float
  std::string firstChannelName;   // "" keeps the format's default names
  bool alphaLast = false;         // channel channels-1 is unassociated alpha (stored as given)
  int jpegQuality = 0;            // > 0: JPEG compression inside the file (TIFF, EXR)
  int pngCompressionLevel = -1;   // >= 0: zlib level of a PNG
  // Names an empty "DateTime": OIIO's OpenEXR writer otherwise stamps the current time, and the same
  // frame would give other bytes on every run. (Set where it always was: raster's writeImage.)
  bool emptyDateTime = false;
};

struct Api {
  uint32_t abi = 0;  // kAbi of the module; api() refuses a module built from other sources
  // Opens a file; format from its contents and name. nullptr with `error` set when it cannot.
  std::unique_ptr<Reader> (*open)(const std::string& path, std::string& error) = nullptr;
  // Opens `size` bytes at `data` (kept alive by the caller while the reader lives) as format `ext`
  // ("png", "jpg", ...). nullptr with `error` empty when that format's reader cannot read from memory
  // (the caller then goes through a temporary file); nullptr with `error` set when it fails.
  std::unique_ptr<Reader> (*openMemory)(const uint8_t* data, size_t size, const std::string& ext,
                                        std::string& error) = nullptr;
  // Writes top-down rows to `file` in the format of `formatPath`'s extension (they differ when the
  // caller writes a temporary and renames it). Returns "" or the writer's error.
  std::string (*write)(const std::string& formatPath, const std::string& file, const WriteSpec& spec,
                       const void* pixels) = nullptr;
};

// Bump when Api, Header, Reader or WriteSpec change.
constexpr uint32_t kAbi = 1;

// The module's interface, loaded on first use. Throws Error naming the module path and dlerror()
// when it cannot be loaded.
const Api& api();

}  // namespace tessera::imagemod
