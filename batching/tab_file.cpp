#include "batching/tab_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <bit>
#include <cerrno>
#include <cstring>
#include <optional>
#include <span>
#include <type_traits>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/sha256.h"
#include "raster/command_list.h"
#include "raster/limits.h"

namespace tessera::batching {

namespace {

// Fixed-width little-endian fields are written as the bytes of the host's values: every host the project
// runs on is little-endian, and this keeps that assumption in one checked place.
static_assert(std::endian::native == std::endian::little);
static_assert(std::is_trivially_copyable_v<Vertex> && sizeof(Vertex) == 6 * sizeof(float));

constexpr char kMagic[8] = {'T', 'E', 'S', 'S', 'T', 'A', 'B', '\x1a'};
constexpr uint32_t kTableOffset = 32, kEntrySize = 56, kHeaderShaOffset = kTableOffset + kTabSectionCount * kEntrySize;
static_assert(kHeaderShaOffset + 32 == kTabHeaderSize);

const char* sectionName(uint32_t kind) {
  static const char* names[] = {"?", "meta", "textures", "texels", "arrays", "batches", "meshes", "vertices"};
  return kind >= 1 && kind <= kTabSectionCount ? names[kind] : "?";
}

std::string at(const std::string& record, uint64_t i) { return record + "[" + std::to_string(i) + "]"; }

// --- writing ----------------------------------------------------------------------------------------

struct Out {
  std::vector<uint8_t> b;
  template <class T>
  void put(T v) {
    static_assert(std::is_arithmetic_v<T>);
    const size_t o = b.size();
    b.resize(o + sizeof(T));
    std::memcpy(b.data() + o, &v, sizeof(T));
  }
  void str(const std::string& s) {
    put<uint32_t>(uint32_t(s.size()));
    b.insert(b.end(), s.begin(), s.end());
  }
  void u32s(const std::vector<uint32_t>& v) {
    put<uint32_t>(uint32_t(v.size()));
    for (uint32_t x : v) put(x);
  }
  void f32s(std::span<const float> v) {
    for (float x : v) put(x);
  }
};

// Where the bytes go: an AtomicFile or a vector. The header is written last, over the space left for it.
struct Sink {
  virtual ~Sink() = default;
  virtual void append(std::span<const uint8_t> bytes) = 0;
  virtual void header(std::span<const uint8_t> bytes) = 0;
};

struct VectorSink : Sink {
  std::vector<uint8_t> b = std::vector<uint8_t>(kTabHeaderSize, 0);
  void append(std::span<const uint8_t> bytes) override { b.insert(b.end(), bytes.begin(), bytes.end()); }
  void header(std::span<const uint8_t> bytes) override { std::memcpy(b.data(), bytes.data(), bytes.size()); }
};

struct FileSink : Sink {
  AtomicFile& f;
  explicit FileSink(AtomicFile& file) : f(file) { f.writeAt(0, std::vector<uint8_t>(kTabHeaderSize, 0)); }
  void append(std::span<const uint8_t> bytes) override { f.write(bytes); }
  void header(std::span<const uint8_t> bytes) override { f.writeAt(0, bytes); }
};

struct TableEntry {
  uint64_t offset = 0, size = 0;
  std::array<uint8_t, 32> sha{};
};

class Encoder {
 public:
  explicit Encoder(Sink& sink) : sink_(sink) {}

  void section(uint32_t kind, std::span<const uint8_t> bytes) {
    begin();
    add(bytes);
    end(kind);
  }
  void begin() { start_ = pos_; }
  void add(std::span<const uint8_t> bytes) {
    sink_.append(bytes);
    sha_.update(bytes);
    pos_ += bytes.size();
  }
  void end(uint32_t kind) { table_[kind - 1] = {start_, pos_ - start_, sha_.finish()}; }

  void finish() {
    Out h;
    for (char c : kMagic) h.put(uint8_t(c));
    h.put<uint32_t>(kTabFormatVersion), h.put<uint32_t>(kTabHeaderSize), h.put<uint32_t>(kTabSectionCount);
    h.put<uint32_t>(0), h.put<uint64_t>(pos_);
    for (uint32_t k = 0; k < kTabSectionCount; ++k) {
      h.put<uint32_t>(k + 1), h.put<uint32_t>(0), h.put<uint64_t>(table_[k].offset), h.put<uint64_t>(table_[k].size);
      h.b.insert(h.b.end(), table_[k].sha.begin(), table_[k].sha.end());
    }
    const auto sha = sha256(h.b);
    h.b.insert(h.b.end(), sha.begin(), sha.end());
    sink_.header(h.b);
  }

 private:
  Sink& sink_;
  Sha256 sha_;
  uint64_t pos_ = kTabHeaderSize, start_ = 0;
  std::array<TableEntry, kTabSectionCount> table_{};
};

// Counts are u32 in the file; the writer refuses what would not fit rather than wrapping.
void fits32(uint64_t n, const char* what) {
  if (n > UINT32_MAX)
    throw Error(std::string("tab file: ") + what + ": " + std::to_string(n) + " does not fit 32 bits");
}

void encode(const TabScene& s, Sink& sink) {
  Encoder e(sink);
  {
    Out o;
    o.put(s.params.bMax), o.put(s.params.dMax), o.put(s.params.aMax);
    o.str(s.source);
    o.f32s(s.bounds);
    e.section(uint32_t(TabSection::Meta), o.b);
  }
  {
    fits32(s.textures.size(), "textures");
    Out o;
    o.put<uint32_t>(uint32_t(s.textures.size()));
    for (const TabTexture& t : s.textures) {
      o.str(t.name);
      o.put(t.width), o.put(t.height);
      o.put(uint8_t(t.format)), o.put(uint8_t(t.wrapS)), o.put(uint8_t(t.wrapT));
      o.put<uint8_t>(uint8_t(t.levels.size()));
    }
    e.section(uint32_t(TabSection::Textures), o.b);
  }
  e.begin();
  for (const TabTexture& t : s.textures)
    for (const auto& level : t.levels) e.add(level);
  e.end(uint32_t(TabSection::Texels));
  {
    fits32(s.arrays.size(), "arrays");
    Out o;
    o.put<uint32_t>(uint32_t(s.arrays.size()));
    for (const TextureArray& a : s.arrays) {
      o.put(a.key.width), o.put(a.key.height);
      o.put(uint8_t(a.key.format)), o.put(uint8_t(a.key.wrapS)), o.put(uint8_t(a.key.wrapT));
      o.u32s(a.layers);
    }
    e.section(uint32_t(TabSection::Arrays), o.b);
  }
  {
    fits32(s.batches.size(), "batches");
    Out o;
    o.put<uint32_t>(uint32_t(s.batches.size()));
    for (const OutputBatch& b : s.batches) {
      o.u32s(b.arrays);
      o.put<uint32_t>(uint32_t(b.tam.size()));
      for (const TamEntry& t : b.tam) {
        o.put(t.array), o.put(t.layer);
        o.f32s(t.factor);
        o.put(t.alphaCutoff), o.put<uint8_t>(t.opaque ? 1 : 0);
      }
      o.put<uint32_t>(uint32_t(b.geometry.size()));
      for (const GeometryBatch& g : b.geometry)
        o.put(g.firstVertex), o.put(g.vertexCount), o.put(g.firstMesh), o.put(g.meshCount);
    }
    e.section(uint32_t(TabSection::Batches), o.b);
  }
  {
    fits32(s.meshes.size(), "meshes");
    Out o;
    o.put<uint32_t>(uint32_t(s.meshes.size()));
    for (const TabMesh& m : s.meshes) {
      o.str(m.name);
      o.put(uint8_t(m.kind));
      o.put(m.modelMesh), o.put(m.firstVertex), o.put(m.vertexCount);
      o.u32s(m.textures);
      o.f32s(m.factor);
      o.put(uint8_t(m.alphaMode)), o.put(m.alphaCutoff);
      o.put(m.outputBatch), o.put(m.tamIndex);
    }
    e.section(uint32_t(TabSection::Meshes), o.b);
  }
  fits32(s.vertices.size(), "vertices");
  e.begin();
  Out count;
  count.put<uint32_t>(uint32_t(s.vertices.size()));
  e.add(count.b);
  e.add(std::span(reinterpret_cast<const uint8_t*>(s.vertices.data()), s.vertices.size() * sizeof(Vertex)));
  e.end(uint32_t(TabSection::Vertices));
  e.finish();
}

// --- reading ----------------------------------------------------------------------------------------

// A section's bytes, decoded with every read bounded by what is left.
struct In {
  const std::vector<uint8_t>& b;
  const std::string& path;
  const char* section;
  size_t pos = 0;
  [[noreturn]] void fail(const std::string& field, const std::string& why) const {
    throw Error(path + ": " + field + ": " + why + " (" + section + " section, byte " + std::to_string(pos) + ")");
  }
  size_t left() const { return b.size() - pos; }
  template <class T>
  T get(const std::string& field) {
    if (left() < sizeof(T)) fail(field, "truncated");
    T v;
    std::memcpy(&v, b.data() + pos, sizeof(T));
    pos += sizeof(T);
    return v;
  }
  // A count of records of at least `minBytes` each: refused before anything is allocated if the records
  // cannot all be in the bytes that are left.
  uint32_t count(const std::string& field, size_t minBytes) {
    const uint32_t n = get<uint32_t>(field);
    if (uint64_t(n) * minBytes > left())
      fail(field, "count " + std::to_string(n) + " needs at least " + std::to_string(uint64_t(n) * minBytes) +
                      " bytes, but only " + std::to_string(left()) + " are left");
    return n;
  }
  std::string str(const std::string& field) {
    const uint32_t n = count(field, 1);
    std::string s(reinterpret_cast<const char*>(b.data() + pos), n);
    pos += n;
    return s;
  }
  std::vector<uint32_t> u32s(const std::string& field) {
    const uint32_t n = count(field, 4);
    std::vector<uint32_t> v(n);
    if (n) std::memcpy(v.data(), b.data() + pos, size_t(n) * 4);
    pos += size_t(n) * 4;
    return v;
  }
  template <size_t N>
  void f32s(std::array<float, N>& v, const std::string& field) {
    for (float& x : v) x = get<float>(field);
  }
  template <class E>
  E enumValue(const std::string& field, uint8_t max) {
    const uint8_t v = get<uint8_t>(field);
    if (v > max) fail(field, std::to_string(v) + " is not a value in [0, " + std::to_string(max) + "]");
    return E(v);
  }
  void done() const {
    if (pos != b.size()) fail("end", std::to_string(left()) + " trailing bytes");
  }
};

class Reader {
 public:
  Reader(std::string path, const ResourceLimits& limits) : path_(std::move(path)), limits_(limits) {
    fd_ = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) throw Error(path_ + ": cannot open: " + std::strerror(errno));
  }
  ~Reader() { ::close(fd_); }
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  TabScene read() {
    header();
    TabScene s;
    meta(s);
    textures(s);
    texels(s);
    arrays(s);
    batches(s);
    meshes(s);
    vertices(s);
    validateTabScene(s, path_);
    return s;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const { throw Error(path_ + ": " + why); }

  void readAt(uint64_t offset, uint8_t* dst, uint64_t n, const char* what) const {
    while (n > 0) {
      const ssize_t r = ::pread(fd_, dst, size_t(std::min<uint64_t>(n, 1u << 30)), off_t(offset));
      if (r < 0 && errno == EINTR) continue;
      if (r <= 0)
        fail(std::string("cannot read the ") + what +
             (r < 0 ? std::string(": ") + std::strerror(errno) : ": file shrank"));
      dst += r, offset += uint64_t(r), n -= uint64_t(r);
    }
  }

  void header() {
    struct stat st {};
    if (::fstat(fd_, &st) != 0) fail(std::string("cannot stat: ") + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) fail("not a regular file, not a .tab file");
    size_ = uint64_t(st.st_size);
    if (size_ < kTabHeaderSize)
      fail("truncated: " + std::to_string(size_) + " bytes, shorter than the " + std::to_string(kTabHeaderSize) +
           "-byte header");
    std::array<uint8_t, kTabHeaderSize> h;
    readAt(0, h.data(), kTabHeaderSize, "header");
    if (std::memcmp(h.data(), kMagic, 8) != 0) fail("not a Tessera .tab file (bad magic)");
    auto u32 = [&](size_t o) {
      uint32_t v;
      std::memcpy(&v, h.data() + o, 4);
      return v;
    };
    auto u64 = [&](size_t o) {
      uint64_t v;
      std::memcpy(&v, h.data() + o, 8);
      return v;
    };
    if (u32(8) != kTabFormatVersion)
      fail("header.version: " + std::to_string(u32(8)) + " (this reader knows version " +
           std::to_string(kTabFormatVersion) + ")");
    const auto sha = sha256(std::span<const uint8_t>(h.data(), kHeaderShaOffset));
    if (std::memcmp(sha.data(), h.data() + kHeaderShaOffset, 32) != 0)
      fail("header checksum mismatch (corrupted header)");
    if (u32(12) != kTabHeaderSize)
      fail("header.header_size: " + std::to_string(u32(12)) + ", expected " + std::to_string(kTabHeaderSize));
    if (u32(16) != kTabSectionCount)
      fail("header.section_count: " + std::to_string(u32(16)) + ", expected " + std::to_string(kTabSectionCount));
    if (u32(20) != 0) fail("header.reserved: " + std::to_string(u32(20)) + " (must be 0)");
    const uint64_t fileSize = u64(24);
    if (fileSize != size_)
      fail("file is " + std::to_string(size_) + " bytes but the header says " + std::to_string(fileSize) +
           (size_ < fileSize ? " (truncated)" : " (trailing bytes)"));
    uint64_t end = kTabHeaderSize;
    for (uint32_t k = 0; k < kTabSectionCount; ++k) {
      const size_t o = kTableOffset + size_t(k) * kEntrySize;
      const std::string f = at("header.sections", k);
      if (u32(o) != k + 1)
        fail(f + ".kind: " + std::to_string(u32(o)) + ", expected " + std::to_string(k + 1) + " (" +
             sectionName(k + 1) + ")");
      if (u32(o + 4) != 0) fail(f + ".reserved: " + std::to_string(u32(o + 4)) + " (must be 0)");
      TableEntry& t = table_[k];
      t.offset = u64(o + 8), t.size = u64(o + 16);
      std::memcpy(t.sha.data(), h.data() + o + 24, 32);
      // The sections follow each other without gaps from the end of the header to the end of the file.
      if (t.offset != end)
        fail(f + ".offset: " + std::to_string(t.offset) + ", expected " + std::to_string(end) +
             " (where the previous section ends)");
      if (t.size > size_ - end)
        fail(f + ".size: " + std::to_string(t.size) + " bytes from offset " + std::to_string(t.offset) +
             " run past the end of the " + std::to_string(size_) + "-byte file");
      end += t.size;
    }
    if (end != size_) fail("sections end at byte " + std::to_string(end) + " of " + std::to_string(size_));
  }

  // A whole section, checksum verified. Its size was checked against the file's.
  std::vector<uint8_t> section(TabSection kind) const {
    const TableEntry& t = table_[uint32_t(kind) - 1];
    std::vector<uint8_t> b(t.size);
    readAt(t.offset, b.data(), t.size, sectionName(uint32_t(kind)));
    if (sha256(b) != t.sha) fail(std::string(sectionName(uint32_t(kind))) + " section: checksum mismatch (corrupted)");
    return b;
  }

  void meta(TabScene& s) {
    const std::vector<uint8_t> b = section(TabSection::Meta);
    In in{b, path_, "meta"};
    s.params.bMax = in.get<uint32_t>("params.b_max");
    s.params.dMax = in.get<uint32_t>("params.d_max");
    s.params.aMax = in.get<uint32_t>("params.a_max");
    s.source = in.str("source");
    in.f32s(s.bounds, "bounds");
    in.done();
  }

  void textures(TabScene& s) {
    const std::vector<uint8_t> b = section(TabSection::Textures);
    In in{b, path_, "textures"};
    const uint32_t n = in.count("textures", 16);
    s.textures.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
      TabTexture& t = s.textures[i];
      const std::string f = at("textures", i);
      t.name = in.str(f + ".name");
      t.width = in.get<uint32_t>(f + ".width"), t.height = in.get<uint32_t>(f + ".height");
      t.format = in.enumValue<TexelFormat>(f + ".format", 0);
      t.wrapS = in.enumValue<WrapMode>(f + ".wrap_s", 2), t.wrapT = in.enumValue<WrapMode>(f + ".wrap_t", 2);
      // The chain's sizes follow from width and height; checked here because they size the allocations.
      if (t.width < 1 || t.width > uint32_t(kMaxTextureSize) || t.height < 1 || t.height > uint32_t(kMaxTextureSize))
        in.fail(f + ".size", std::to_string(t.width) + " x " + std::to_string(t.height) + " is outside [1, " +
                                 std::to_string(kMaxTextureSize) + "] per axis");
      const uint8_t levels = in.get<uint8_t>(f + ".levels");
      const uint32_t full = fullMipCount(t.width, t.height);
      if (levels != full)
        in.fail(f + ".levels", std::to_string(levels) + ", but a full mip chain of " + std::to_string(t.width) + " x " +
                                   std::to_string(t.height) + " has " + std::to_string(full) + " levels");
      t.levels.resize(levels);
    }
    in.done();
  }

  void texels(TabScene& s) {
    // The bytes every chain needs, summed with overflow checks, must be exactly the section's size
    // before any level is allocated.
    uint64_t need = 0;
    for (size_t i = 0; i < s.textures.size(); ++i) {
      const TabTexture& t = s.textures[i];
      const TextureDesc d{TextureKind::Tex2D, Format::RGBA8, t.width, t.height, 1, uint32_t(t.levels.size())};
      for (uint32_t l = 0; l < t.levels.size(); ++l) need += levelBytes(d, l);  // <= 2^30 * 4/3 each: no overflow
    }
    if (need > limits_.modelTextureBytes)
      fail(overLimitMessage("texels", "of texels", need, limits_.modelTextureBytes, "--model-budget-textures", true));
    const TableEntry& t = table_[uint32_t(TabSection::Texels) - 1];
    if (need != t.size)
      fail("texels section: " + std::to_string(t.size) + " bytes, but the textures' mip chains need " +
           std::to_string(need));
    Sha256 sha;
    uint64_t offset = t.offset;
    for (TabTexture& tex : s.textures) {
      const TextureDesc d{TextureKind::Tex2D, Format::RGBA8, tex.width, tex.height, 1, uint32_t(tex.levels.size())};
      for (uint32_t l = 0; l < tex.levels.size(); ++l) {
        tex.levels[l].resize(size_t(levelBytes(d, l)));
        readAt(offset, tex.levels[l].data(), tex.levels[l].size(), "texels");
        sha.update(tex.levels[l]);
        offset += tex.levels[l].size();
      }
    }
    if (sha.finish() != t.sha) fail("texels section: checksum mismatch (corrupted)");
  }

  void arrays(TabScene& s) {
    const std::vector<uint8_t> b = section(TabSection::Arrays);
    In in{b, path_, "arrays"};
    const uint32_t n = in.count("arrays", 15);
    s.arrays.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
      TextureArray& a = s.arrays[i];
      const std::string f = at("arrays", i);
      a.key.width = in.get<uint32_t>(f + ".width"), a.key.height = in.get<uint32_t>(f + ".height");
      a.key.format = in.enumValue<TexelFormat>(f + ".format", 0);
      a.key.wrapS = in.enumValue<WrapMode>(f + ".wrap_s", 2), a.key.wrapT = in.enumValue<WrapMode>(f + ".wrap_t", 2);
      a.layers = in.u32s(f + ".layers");
    }
    in.done();
  }

  void batches(TabScene& s) {
    const std::vector<uint8_t> b = section(TabSection::Batches);
    In in{b, path_, "batches"};
    const uint32_t n = in.count("batches", 12);
    s.batches.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
      OutputBatch& ob = s.batches[i];
      const std::string f = at("batches", i);
      ob.arrays = in.u32s(f + ".arrays");
      const uint32_t nt = in.count(f + ".tam", 29);
      ob.tam.resize(nt);
      for (uint32_t k = 0; k < nt; ++k) {
        TamEntry& e = ob.tam[k];
        const std::string tf = at(f + ".tam", k);
        e.array = in.get<uint32_t>(tf + ".array"), e.layer = in.get<uint32_t>(tf + ".layer");
        in.f32s(e.factor, tf + ".factor");
        e.alphaCutoff = in.get<float>(tf + ".alpha_cutoff");
        const uint8_t opaque = in.get<uint8_t>(tf + ".opaque");
        if (opaque > 1) in.fail(tf + ".opaque", std::to_string(opaque) + " is not 0 or 1");
        e.opaque = opaque == 1;
      }
      const uint32_t ng = in.count(f + ".geometry", 16);
      ob.geometry.resize(ng);
      for (uint32_t k = 0; k < ng; ++k) {
        GeometryBatch& g = ob.geometry[k];
        const std::string gf = at(f + ".geometry", k);
        g.firstVertex = in.get<uint32_t>(gf + ".first_vertex"), g.vertexCount = in.get<uint32_t>(gf + ".vertex_count");
        g.firstMesh = in.get<uint32_t>(gf + ".first_mesh"), g.meshCount = in.get<uint32_t>(gf + ".mesh_count");
      }
    }
    in.done();
  }

  void meshes(TabScene& s) {
    const std::vector<uint8_t> b = section(TabSection::Meshes);
    In in{b, path_, "meshes"};
    const uint32_t n = in.count("meshes", 50);
    s.meshes.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
      TabMesh& m = s.meshes[i];
      const std::string f = at("meshes", i);
      m.name = in.str(f + ".name");
      m.kind = in.enumValue<MeshKind>(f + ".kind", 2);
      m.modelMesh = in.get<uint32_t>(f + ".model_mesh");
      m.firstVertex = in.get<uint32_t>(f + ".first_vertex"), m.vertexCount = in.get<uint32_t>(f + ".vertex_count");
      m.textures = in.u32s(f + ".textures");
      in.f32s(m.factor, f + ".factor");
      m.alphaMode = in.enumValue<AlphaMode>(f + ".alpha_mode", 2);
      m.alphaCutoff = in.get<float>(f + ".alpha_cutoff");
      m.outputBatch = in.get<uint32_t>(f + ".output_batch"), m.tamIndex = in.get<uint32_t>(f + ".tam_index");
    }
    in.done();
  }

  void vertices(TabScene& s) {
    const TableEntry& t = table_[uint32_t(TabSection::Vertices) - 1];
    // Checked against the section's size (so the file's) before the section is read.
    if (t.size < 4 || (t.size - 4) % sizeof(Vertex) != 0)
      fail("vertices section: " + std::to_string(t.size) + " bytes is not a 4-byte count and 24-byte vertices");
    if ((t.size - 4) / sizeof(Vertex) > limits_.modelVertices)
      fail(overLimitMessage("vertices", "vertices", (t.size - 4) / sizeof(Vertex), limits_.modelVertices,
                            "--model-budget-vertices", false));
    const std::vector<uint8_t> b = section(TabSection::Vertices);
    In in{b, path_, "vertices"};
    const uint32_t n = in.count("vertices.count", sizeof(Vertex));
    s.vertices.resize(n);
    if (n) std::memcpy(s.vertices.data(), b.data() + in.pos, size_t(n) * sizeof(Vertex));
    in.pos += size_t(n) * sizeof(Vertex);
    in.done();
  }

  std::string path_;
  const ResourceLimits& limits_;
  int fd_ = -1;
  uint64_t size_ = 0;
  std::array<TableEntry, kTabSectionCount> table_{};
};

}  // namespace

std::vector<uint8_t> encodeTabFile(const TabScene& scene) {
  VectorSink sink;
  encode(scene, sink);
  return std::move(sink.b);
}

void writeTabFile(const TabScene& scene, const std::string& path) {
  validateTabScene(scene, path);
  AtomicFile file(path);
  FileSink sink(file);
  encode(scene, sink);  // the validation made every count fit its field
  file.commit();
}

TabScene readTabFile(const std::string& path, const ResourceLimits& limits) {
  Reader r(path, limits);
  return r.read();
}

}  // namespace tessera::batching
