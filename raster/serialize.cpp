#include "raster/serialize.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <limits>
#include <system_error>
#include <type_traits>
#include <utility>

#include "base/atomic_file.h"
#include "base/sha256.h"

namespace tessera {
namespace {

// Byte offsets of the header fields (docs/tframe-format.md, "Header").
constexpr size_t kOffVersion = 8, kOffHeaderSize = 12, kOffCommandCount = 16, kOffBlobSize = 24, kOffNextId = 32,
                 kOffChecksum = 40;
// The smallest command is an opcode and a payload size with an empty payload.
constexpr uint64_t kMinCommandBytes = 2 + 4;
constexpr size_t kCommandKinds = std::variant_size_v<Command>;

// "attribs[].offset" with index 3 -> "attribs[3].offset"; names without "[]" are used as they are.
std::string fieldName(const char* name, int index) {
  std::string s(name);
  if (index >= 0) {
    if (auto at = s.find("[]"); at != std::string::npos) s.replace(at, 2, fmt::format("[{}]", index));
  }
  return s;
}

// Where an error happened: the header, one command (its kind once the opcode is known), or the
// command section as a whole.
struct Context {
  std::string_view source;
  int64_t command = -1;  // -1: header (or the section, see `section`)
  int kind = -1;         // Command::index() once known
  bool section = false;  // the command section as a whole (trailing bytes)
  std::string where() const {
    if (section) return "command section";
    if (command < 0) return "header";
    if (kind < 0) return fmt::format("command {}", command);
    return fmt::format("command {} ({})", command, commandName(size_t(kind)));
  }
  [[noreturn]] void fail(uint64_t byte, std::string_view message) const {
    throw Error(fmt::format("{}: {} at byte {}: {}", source, where(), byte, message));
  }
};

template <class C, class T>
concept Is = std::is_same_v<std::remove_const_t<C>, T>;

template <class E>
constexpr unsigned enumMax() {
  static_assert(std::is_same_v<std::underlying_type_t<E>, uint8_t>, "enums are stored as u8");
  return unsigned(E::Count) - 1;
}

// --- field lists ----------------------------------------------------------------------------
// One function per command kind lists its payload fields in declared order. Writer and Reader
// both walk these lists (Writer with const commands), so encoder and decoder cannot disagree.

template <class Ar, Is<CreateTexture> C>
void fields(Ar& ar, C& c) {
  ar.u32(c.id, "id");
  ar.enumeration(c.desc.kind, "desc.kind");
  ar.enumeration(c.desc.format, "desc.format");
  ar.u32(c.desc.width, "desc.width");
  ar.u32(c.desc.height, "desc.height");
  ar.u32(c.desc.layers, "desc.layers");
  ar.u32(c.desc.levels, "desc.levels");
  ar.u32(c.desc.buffer, "desc.buffer");
  if (ar.version >= 2) ar.enumeration(c.desc.compression, "desc.compression");
}
template <class Ar, Is<UploadTexture> C>
void fields(Ar& ar, C& c) {
  ar.u32(c.id, "id");
  ar.u32(c.level, "level");
  ar.u32(c.layer, "layer");
  ar.blobRange(c.data, "data");
}
template <class Ar, Is<CreateBuffer> C>
void fields(Ar& ar, C& c) {
  ar.u32(c.id, "id");
  ar.enumeration(c.kind, "kind");
  ar.u64(c.size, "size");
}
template <class Ar, Is<UploadBuffer> C>
void fields(Ar& ar, C& c) {
  ar.u32(c.id, "id");
  ar.u64(c.offset, "offset");
  ar.blobRange(c.data, "data");
}
template <class Ar, Is<CreateSampler> C>
void fields(Ar& ar, C& c) {
  ar.u32(c.id, "id");
  ar.enumeration(c.state.wrapS, "wrapS");
  ar.enumeration(c.state.wrapT, "wrapT");
  ar.enumeration(c.state.minFilter, "minFilter");
  ar.enumeration(c.state.magFilter, "magFilter");
  ar.f32(c.state.minLod, "minLod");
  ar.f32(c.state.maxLod, "maxLod");
  ar.f32(c.state.lodBias, "lodBias");
  for (int i = 0; i < 4; ++i) ar.f32(c.state.borderColor[i], "borderColor[]", i);
}
template <class Ar, Is<CreateProgram> C>
void fields(Ar& ar, C& c) {
  ar.u32(c.id, "id");
  ar.string(c.name, "name");
}
template <class Ar, Is<BindTexture> C>
void fields(Ar& ar, C& c) {
  ar.u32(c.unit, "unit");
  ar.u32(c.texture, "texture");
}
template <class Ar, Is<BindSampler> C>
void fields(Ar& ar, C& c) {
  ar.u32(c.unit, "unit");
  ar.u32(c.sampler, "sampler");
}
template <class Ar, Is<UseProgram> C>
void fields(Ar& ar, C& c) {
  ar.u32(c.program, "program");
}
template <class Ar, Is<SetUniforms> C>
void fields(Ar& ar, C& c) {
  ar.u32(c.slot, "slot");
  ar.u32(c.count, "count");
  ar.blobRange(c.data, "data");
}
template <class Ar, Is<BindVertexBuffer> C>
void fields(Ar& ar, C& c) {
  ar.u32(c.buffer, "buffer");
}
template <class Ar, Is<SetVertexLayout> C>
void fields(Ar& ar, C& c) {
  ar.u32(c.layout.stride, "stride");
  for (int i = 0; i < kMaxAttribs; ++i) {
    auto& a = c.layout.attribs[i];
    ar.u8(a.location, "attribs[].location", i);
    ar.u8(a.components, "attribs[].components", i);
    ar.enumeration(a.type, "attribs[].type", i);
    ar.u32(a.offset, "attribs[].offset", i);
  }
}
template <class Ar, Is<BindIndexBuffer> C>
void fields(Ar& ar, C& c) {
  ar.u32(c.buffer, "buffer");
  ar.enumeration(c.type, "type");
}
template <class Ar, class R>
void rectFields(Ar& ar, R& r) {
  ar.i32(r.x, "x");
  ar.i32(r.y, "y");
  ar.i32(r.w, "w");
  ar.i32(r.h, "h");
}
template <class Ar, Is<SetViewport> C>
void fields(Ar& ar, C& c) {
  rectFields(ar, c.rect);
}
template <class Ar, Is<SetScissor> C>
void fields(Ar& ar, C& c) {
  ar.boolean(c.state.enabled, "enabled");
  rectFields(ar, c.state.rect);
}
template <class Ar, Is<SetDepthState> C>
void fields(Ar& ar, C& c) {
  ar.boolean(c.state.test, "test");
  ar.boolean(c.state.write, "write");
  ar.enumeration(c.state.func, "func");
}
template <class Ar, Is<SetBlendState> C>
void fields(Ar& ar, C& c) {
  ar.boolean(c.state.enabled, "enabled");
  ar.enumeration(c.state.eqRgb, "eqRgb");
  ar.enumeration(c.state.eqAlpha, "eqAlpha");
  ar.enumeration(c.state.srcRgb, "srcRgb");
  ar.enumeration(c.state.dstRgb, "dstRgb");
  ar.enumeration(c.state.srcAlpha, "srcAlpha");
  ar.enumeration(c.state.dstAlpha, "dstAlpha");
  for (int i = 0; i < 4; ++i) ar.f32(c.state.constant[i], "constant[]", i);
}
template <class Ar, Is<SetRasterState> C>
void fields(Ar& ar, C& c) {
  ar.enumeration(c.state.cull, "cull");
  ar.boolean(c.state.frontCcw, "frontCcw");
  ar.u8(c.state.clipMask, "clipMask");
}
template <class Ar, Is<SetRenderTarget> C>
void fields(Ar& ar, C& c) {
  for (int i = 0; i < kMaxColorAttachments; ++i) ar.u32(c.target.color[i], "color[]", i);
  ar.u32(c.target.depth, "depth");
  ar.u32(c.target.level, "level");
  ar.u32(c.target.layer, "layer");
}
template <class Ar, Is<ClearColor> C>
void fields(Ar& ar, C& c) {
  ar.u32(c.attachment, "attachment");
  for (int i = 0; i < 4; ++i) ar.u32(c.bits[i], "bits[]", i);
}
template <class Ar, Is<ClearDepth> C>
void fields(Ar& ar, C& c) {
  ar.f32(c.depth, "depth");
}
template <class Ar, Is<Draw> C>
void fields(Ar& ar, C& c) {
  ar.enumeration(c.primitive, "primitive");
  ar.boolean(c.indexed, "indexed");
  ar.u32(c.first, "first");
  ar.u32(c.count, "count");
}
template <class Ar, Is<Marker> C>
void fields(Ar& ar, C& c) {
  ar.string(c.text, "text");
}

// The id a command creates, or kNone.
ResourceId createdId(const Command& c) {
  return std::visit(
      [](const auto& v) -> ResourceId {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, CreateTexture> || std::is_same_v<T, CreateBuffer> ||
                      std::is_same_v<T, CreateSampler> || std::is_same_v<T, CreateProgram>) {
          return v.id;
        } else {
          return kNone;
        }
      },
      c);
}

// --- encoding -------------------------------------------------------------------------------

class Writer {
 public:
  Writer(std::vector<uint8_t>& out, uint64_t blobSize, uint32_t v) : version(v), out_(out), blobSize_(blobSize) {}
  Context ctx{"encodeFrame"};
  uint32_t version;  // of the file being written: which fields exist

  void raw(uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) out_.push_back(uint8_t(v >> (8 * i)));
  }
  void u8(const uint8_t& v, const char*, int = -1) { raw(v, 1); }
  void boolean(const bool& v, const char*, int = -1) { raw(v ? 1 : 0, 1); }
  void u32(const uint32_t& v, const char*, int = -1) { raw(v, 4); }
  void i32(const int32_t& v, const char*, int = -1) { raw(uint32_t(v), 4); }
  void u64(const uint64_t& v, const char*, int = -1) { raw(v, 8); }
  void f32(const float& v, const char*, int = -1) {
    uint32_t bits;
    std::memcpy(&bits, &v, 4);  // bit pattern, so NaN payloads and -0 survive the round trip
    raw(bits, 4);
  }
  template <class E>
  void enumeration(const E& v, const char* name, int index = -1) {
    // An out-of-range enum (made by a cast) would encode into a file the decoder rejects.
    if (unsigned(v) > enumMax<E>()) {
      ctx.fail(out_.size(),
               fmt::format("field {} = {} is out of range (0..{})", fieldName(name, index), unsigned(v), enumMax<E>()));
    }
    raw(uint8_t(v), 1);
  }
  void string(const std::string& s, const char* name, int index = -1) {
    if (s.size() > kFrameMaxStringBytes) {
      ctx.fail(out_.size(), fmt::format("field {} has {} bytes, more than the limit {}", fieldName(name, index),
                                        s.size(), kFrameMaxStringBytes));
    }
    raw(s.size(), 4);
    out_.insert(out_.end(), s.begin(), s.end());
  }
  void blobRange(const BlobRange& r, const char* name, int index = -1) {
    if (r.offset > blobSize_ || r.size > blobSize_ - r.offset) {
      ctx.fail(out_.size(), fmt::format("field {} = [{}, +{}) lies outside the blob ({} bytes)", fieldName(name, index),
                                        r.offset, r.size, blobSize_));
    }
    raw(r.offset, 8);
    raw(r.size, 8);
  }

 private:
  std::vector<uint8_t>& out_;
  uint64_t blobSize_;
};

void putLe(std::vector<uint8_t>& out, size_t at, uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out[at + i] = uint8_t(v >> (8 * i));
}

// --- decoding -------------------------------------------------------------------------------

class Reader {
 public:
  Reader(std::span<const uint8_t> bytes, std::string_view source) : bytes_(bytes), end_(bytes.size()) {
    ctx.source = source;
  }
  Context ctx;
  uint64_t blobSize = 0;
  uint32_t version = kFrameVersion;  // of the file being read, from its header

  size_t pos() const { return pos_; }
  void seek(size_t p) { pos_ = p; }
  void limit(size_t end) { end_ = end; }
  size_t remaining() const { return end_ - pos_; }
  const char* region = "file";  // what end_ is the end of, for truncation messages

  // Little-endian unsigned of `bytes` bytes; names the field when it would run past the limit.
  uint64_t raw(int bytes, const char* name, int index) {
    if (remaining() < size_t(bytes)) {
      ctx.fail(pos_, fmt::format("field {} is truncated: needs {} bytes, {} left in the {}", fieldName(name, index),
                                 bytes, remaining(), region));
    }
    uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= uint64_t(bytes_[pos_ + i]) << (8 * i);
    pos_ += size_t(bytes);
    return v;
  }
  void u8(uint8_t& v, const char* name, int index = -1) { v = uint8_t(raw(1, name, index)); }
  void boolean(bool& v, const char* name, int index = -1) {
    const size_t at = pos_;
    const uint64_t b = raw(1, name, index);
    // Only 0 and 1, so that re-encoding reproduces the file byte for byte.
    if (b > 1) ctx.fail(at, fmt::format("field {} = {} is not a bool (0 or 1)", fieldName(name, index), b));
    v = b == 1;
  }
  void u32(uint32_t& v, const char* name, int index = -1) { v = uint32_t(raw(4, name, index)); }
  void i32(int32_t& v, const char* name, int index = -1) {
    const uint32_t u = uint32_t(raw(4, name, index));
    std::memcpy(&v, &u, 4);  // two's complement reinterpretation without implementation-defined casts
  }
  void u64(uint64_t& v, const char* name, int index = -1) { v = raw(8, name, index); }
  void f32(float& v, const char* name, int index = -1) {
    const uint32_t u = uint32_t(raw(4, name, index));
    std::memcpy(&v, &u, 4);
  }
  template <class E>
  void enumeration(E& v, const char* name, int index = -1) {
    const size_t at = pos_;
    const uint64_t b = raw(1, name, index);
    if (b > enumMax<E>()) {
      ctx.fail(at, fmt::format("field {} = {} is out of range (0..{})", fieldName(name, index), b, enumMax<E>()));
    }
    v = E(b);
  }
  void string(std::string& s, const char* name, int index = -1) {
    const size_t at = pos_;
    const uint64_t n = raw(4, name, index);
    // Both bounds before any allocation: the limit, and the bytes actually present.
    if (n > kFrameMaxStringBytes) {
      ctx.fail(at, fmt::format("field {} has length {}, more than the limit {}", fieldName(name, index), n,
                               kFrameMaxStringBytes));
    }
    if (n > remaining()) {
      ctx.fail(at, fmt::format("field {} has length {} but only {} bytes are left in the payload",
                               fieldName(name, index), n, remaining()));
    }
    s.assign(reinterpret_cast<const char*>(bytes_.data() + pos_), size_t(n));
    pos_ += size_t(n);
  }
  void blobRange(BlobRange& r, const char* name, int index = -1) {
    const size_t at = pos_;
    r.offset = raw(8, name, index);
    r.size = raw(8, name, index);
    if (r.offset > blobSize || r.size > blobSize - r.offset) {
      ctx.fail(at, fmt::format("field {} = [{}, +{}) lies outside the blob ({} bytes)", fieldName(name, index),
                               r.offset, r.size, blobSize));
    }
  }

 private:
  std::span<const uint8_t> bytes_;
  size_t pos_ = 0, end_;
};

using DecodeFn = Command (*)(Reader&);
template <size_t I>
Command decodeKind(Reader& r) {
  std::variant_alternative_t<I, Command> c{};
  fields(r, c);
  return Command(std::in_place_index<I>, std::move(c));
}
template <size_t... I>
constexpr std::array<DecodeFn, sizeof...(I)> makeDecoders(std::index_sequence<I...>) {
  return {&decodeKind<I>...};
}
constexpr auto kDecoders = makeDecoders(std::make_index_sequence<kCommandKinds>());

// --- files ----------------------------------------------------------------------------------

[[noreturn]] void failErrno(const std::string& path, std::string_view what, int err) {
  // error_code::message, unlike strerror, is safe to call from several threads.
  throw Error(fmt::format("{}: {}: {}", path, what, std::error_code(err, std::generic_category()).message()));
}


}  // namespace

std::vector<uint8_t> encodeFrame(const CommandList& list) {
  const std::vector<uint8_t>& blob = list.blob();
  std::vector<uint8_t> out(kFrameHeaderSize, 0);
  out.reserve(kFrameHeaderSize + list.commands().size() * 32 + blob.size());
  // The oldest version that can hold the list (serialize.h): 2 only when a texture is compressed.
  uint32_t version = 1;
  for (const Command& c : list.commands())
    if (const auto* t = std::get_if<CreateTexture>(&c); t && t->desc.compression != BcFormat::None) version = 2;
  Writer w(out, blob.size(), version);

  ResourceId maxCreated = kNone;
  const auto& cmds = list.commands();
  for (size_t i = 0; i < cmds.size(); ++i) {
    w.ctx.command = int64_t(i);
    w.ctx.kind = int(cmds[i].index());
    w.raw(cmds[i].index(), 2);
    const size_t sizeAt = out.size();
    w.raw(0, 4);  // payload size, patched below
    std::visit([&](const auto& c) { fields(w, c); }, cmds[i]);
    putLe(out, sizeAt, out.size() - sizeAt - 4, 4);
    maxCreated = std::max(maxCreated, createdId(cmds[i]));
  }
  // The file's next id is derived from the commands rather than copied from list.nextId(): a list cut
  // short (CommandList::truncate, bisection) keeps a larger nextId() that means nothing in a file, and
  // a derived value lets the decoder check the (unchecksummed) header field exactly.
  const uint64_t nextId = uint64_t(maxCreated) + 1;
  if (nextId > std::numeric_limits<uint32_t>::max()) {
    throw Error(fmt::format("encodeFrame: created id {} leaves no next id", maxCreated));
  }
  out.insert(out.end(), blob.begin(), blob.end());

  std::memcpy(out.data(), kFrameMagic, 8);
  putLe(out, kOffVersion, version, 4);
  putLe(out, kOffHeaderSize, kFrameHeaderSize, 4);
  putLe(out, kOffCommandCount, cmds.size(), 8);
  putLe(out, kOffBlobSize, blob.size(), 8);
  putLe(out, kOffNextId, nextId, 8);
  const auto digest = sha256(std::span(out).subspan(kFrameHeaderSize));
  std::memcpy(out.data() + kOffChecksum, digest.data(), digest.size());
  return out;
}

CommandList decodeFrame(std::span<const uint8_t> bytes, std::string_view sourceName) {
  Reader r(bytes, sourceName);
  const uint64_t fileSize = bytes.size();

  // Header. Each field read checks the bytes are there, so a short file names the missing field.
  if (fileSize < 8 || std::memcmp(bytes.data(), kFrameMagic, 8) != 0) {
    r.ctx.fail(0, fileSize < 8 ? fmt::format("file has {} bytes, too short for the magic \"TSFRAME\\0\"", fileSize)
                               : std::string("field magic is not \"TSFRAME\\0\" (not a .tframe file)"));
  }
  r.seek(8);
  uint32_t version = 0, headerSize = 0;
  uint64_t count = 0, blobSize = 0, nextId = 0;
  r.u32(version, "version");
  if (version < kFrameOldestVersion || version > kFrameVersion) {
    r.ctx.fail(kOffVersion, fmt::format("field version = {} is not supported (expected {} to {})", version,
                                        kFrameOldestVersion, kFrameVersion));
  }
  r.version = version;
  r.u32(headerSize, "headerSize");
  if (headerSize != kFrameHeaderSize) {
    r.ctx.fail(kOffHeaderSize, fmt::format("field headerSize = {} is wrong (version {} headers have {} bytes)",
                                           headerSize, version, kFrameHeaderSize));
  }
  r.u64(count, "commandCount");
  r.u64(blobSize, "blobSize");
  r.u64(nextId, "nextId");
  if (r.remaining() < 32) {
    r.ctx.fail(kOffChecksum,
               fmt::format("field checksum is truncated: needs 32 bytes, {} left in the file", r.remaining()));
  }
  const uint64_t bodySize = fileSize - kFrameHeaderSize;
  if (blobSize > bodySize) {
    r.ctx.fail(kOffBlobSize, fmt::format("field blobSize = {} exceeds the {} bytes after the header (file truncated?)",
                                         blobSize, bodySize));
  }
  const uint64_t sectionSize = bodySize - blobSize;
  if (count > sectionSize / kMinCommandBytes) {
    r.ctx.fail(kOffCommandCount, fmt::format("field commandCount = {} cannot fit in the {} command bytes "
                                             "(a command takes at least {})",
                                             count, sectionSize, kMinCommandBytes));
  }
  if (nextId == 0 || nextId > std::numeric_limits<uint32_t>::max()) {
    r.ctx.fail(kOffNextId,
               fmt::format("field nextId = {} is out of range (1..{})", nextId, std::numeric_limits<uint32_t>::max()));
  }
  const auto body = bytes.subspan(kFrameHeaderSize);
  const auto digest = sha256(body);
  const auto stored = bytes.subspan(kOffChecksum, 32);
  if (std::memcmp(digest.data(), stored.data(), 32) != 0) {
    r.ctx.fail(kOffChecksum, fmt::format("field checksum {} does not match the content's SHA-256 {} "
                                         "(file corrupted or truncated)",
                                         toHex(stored), toHex(digest)));
  }

  // Commands: each confined to its declared payload, which is confined to the command section.
  CommandList list;
  r.blobSize = blobSize;
  const size_t sectionEnd = size_t(kFrameHeaderSize + sectionSize);
  r.seek(kFrameHeaderSize);
  ResourceId maxCreated = kNone;
  for (uint64_t i = 0; i < count; ++i) {
    r.ctx.command = int64_t(i);
    r.ctx.kind = -1;  // unknown until the opcode is read
    r.limit(sectionEnd);
    r.region = "command section";
    if (r.remaining() == 0) {
      r.ctx.fail(r.pos(),
                 fmt::format("the command section ends after {} of the {} commands the header announces", i, count));
    }
    const size_t opcodeAt = r.pos();
    const auto opcode = uint16_t(r.raw(2, "opcode", -1));
    if (opcode >= kCommandKinds) {
      r.ctx.fail(opcodeAt, fmt::format("field opcode = {} is out of range (0..{})", opcode, kCommandKinds - 1));
    }
    r.ctx.kind = opcode;  // from here on errors name the command kind
    const size_t sizeAt = r.pos();
    uint32_t payloadSize = 0;
    r.u32(payloadSize, "payloadSize");
    if (payloadSize > r.remaining()) {
      r.ctx.fail(sizeAt, fmt::format("field payloadSize = {} exceeds the {} bytes left in the command section",
                                     payloadSize, r.remaining()));
    }
    const size_t payloadStart = r.pos(), payloadEnd = payloadStart + payloadSize;
    r.limit(payloadEnd);
    r.region = "payload";
    Command c = kDecoders[opcode](r);
    if (r.pos() != payloadEnd) {
      r.ctx.fail(payloadStart, fmt::format("payloadSize = {} but the fields of {} use {} bytes", payloadSize,
                                           commandName(opcode), r.pos() - payloadStart));
    }
    maxCreated = std::max(maxCreated, createdId(c));
    list.appendRaw(std::move(c));
  }
  r.limit(sectionEnd);
  if (r.remaining() != 0) {
    r.ctx.section = true;
    r.ctx.fail(r.pos(),
               fmt::format("{} bytes follow the last of the {} commands the header announces", r.remaining(), count));
  }
  if (nextId != uint64_t(maxCreated) + 1) {
    r.ctx = Context{r.ctx.source};
    r.ctx.fail(kOffNextId,
               fmt::format("field nextId = {} does not follow the highest created id {}", nextId, maxCreated));
  }
  list.appendBlob(bytes.subspan(sectionEnd, size_t(blobSize)));
  list.setNextId(uint32_t(nextId));
  return list;
}

void writeFrame(const CommandList& list, const std::string& path) {
  writeFileAtomically(path, encodeFrame(list));
}

CommandList readFrame(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) failErrno(path, "cannot open", errno);
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) failErrno(path, "cannot stat", errno);
  if (!S_ISREG(st.st_mode)) throw Error(fmt::format("{}: not a regular file", path));
  std::vector<uint8_t> bytes(size_t(st.st_size));
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) failErrno(path, "cannot read", errno);
    if (n == 0) break;  // the file shrank while reading: decode what is there (it will fail cleanly)
    done += size_t(n);
  }
  bytes.resize(done);
  return decodeFrame(bytes, path);
}

}  // namespace tessera
