#include "raster/validate.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <memory>
#include <optional>
#include <unordered_map>

#include "raster/program.h"

namespace tessera {
namespace {

// Largest buffer accepted: the largest a buffer texture can address (kMaxBufferTextureTexels texels
// of the widest format, 16 bytes). Backends allocate declared sizes, so this also bounds what a
// hostile frame can make them allocate per buffer.
constexpr uint64_t kMaxBufferBytes = uint64_t(kMaxBufferTextureTexels) * 16;
// U32 attributes are converted to float for programs; above 2^24 the conversion rounds.
constexpr uint32_t kMaxExactU32 = 1u << 24;
constexpr int32_t kMaxViewportOffset = kMaxTextureSize;  // the guard-band derivation in limits.h assumes it

enum class Kind : uint8_t { Texture, Buffer, Sampler, Program };
constexpr std::string_view kindName(Kind k) {
  constexpr std::string_view kNames[] = {"texture", "buffer", "sampler", "program"};
  return kNames[size_t(k)];
}
std::string_view bufferKindName(BufferKind k) {
  constexpr std::string_view kNames[] = {"Vertex", "Index", "Texel"};
  return size_t(k) < std::size(kNames) ? kNames[size_t(k)] : "?";
}

template <class E>
bool enumOk(E e) {
  return unsigned(e) < unsigned(E::Count);
}

bool blobOk(const CommandList& list, BlobRange r) {
  const uint64_t n = list.blob().size();
  return r.offset <= n && r.size <= n - r.offset;
}

uint32_t readLe32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

// The contents of one buffer as a draw at the current command sees them: the uploads recorded so
// far, applied in order over zeros (fresh CPU storage is zeroed). Uploads stay blob ranges until a
// draw reads the buffer. The storage is then the blob itself while the last whole-buffer upload has
// not been partially overwritten (the common case: no copy at all), otherwise 64 KiB pages allocated
// only where bytes were uploaded, so a huge, mostly unwritten buffer costs (almost) nothing.
class ShadowBuffer {
 public:
  explicit ShadowBuffer(uint64_t size = 0) : size_(size) {}

  void upload(uint64_t offset, std::span<const uint8_t> bytes) {  // inside the buffer; bytes outlive *this
    if (offset == 0 && bytes.size() == size_) {
      // Replaces everything: forget pages and earlier uploads.
      direct_ = true;
      directBytes_ = bytes;
      pages_.clear();
      pending_.clear();
      return;
    }
    pending_.push_back({offset, bytes});
  }

  // Applies pending uploads; call before read().
  void flush() {
    if (pending_.empty()) return;
    if (direct_) {
      direct_ = false;
      write(0, directBytes_);
    }
    for (const auto& u : pending_) write(u.offset, u.bytes);
    pending_.clear();
  }

  // Bytes [offset, offset + n), inside the buffer: in place when one upload holds the whole buffer,
  // else copied to scratch (n <= its size).
  const uint8_t* view(uint64_t offset, size_t n, uint8_t* scratch) const {
    if (direct_) return directBytes_.data() + offset;
    read(offset, n, scratch);
    return scratch;
  }

  // Copies bytes [offset, offset + n), inside the buffer, to dst.
  void read(uint64_t offset, size_t n, uint8_t* dst) const {
    if (direct_) {
      std::memcpy(dst, directBytes_.data() + offset, n);
      return;
    }
    while (n > 0) {
      const uint64_t in = offset & (kPage - 1);
      const size_t take = size_t(std::min<uint64_t>(n, kPage - in));
      auto it = pages_.find(offset / kPage);
      if (it == pages_.end()) {
        std::memset(dst, 0, take);
      } else {
        std::memcpy(dst, it->second->data() + in, take);
      }
      offset += take, dst += take, n -= take;
    }
  }

 private:
  static constexpr uint64_t kPage = 1 << 16;
  using Page = std::array<uint8_t, kPage>;

  void write(uint64_t offset, std::span<const uint8_t> bytes) {
    size_t done = 0;
    while (done < bytes.size()) {
      const uint64_t in = offset & (kPage - 1);
      const size_t take = size_t(std::min<uint64_t>(bytes.size() - done, kPage - in));
      std::unique_ptr<Page>& page = pages_[offset / kPage];
      if (!page) page = std::make_unique<Page>();  // value-initialized: zeros
      std::memcpy(page->data() + in, bytes.data() + done, take);
      offset += take, done += take;
    }
  }

  struct Upload {
    uint64_t offset;
    std::span<const uint8_t> bytes;
  };
  uint64_t size_;
  bool direct_ = false;
  std::span<const uint8_t> directBytes_;
  std::unordered_map<uint64_t, std::unique_ptr<Page>> pages_;
  std::vector<Upload> pending_;
};

struct Resource {
  Kind kind;
  size_t createdBy = 0;
  bool valid = true;  // false: the creation was diagnosed; later checks that need it are skipped
  TextureDesc desc;   // textures
  BufferKind bufferKind = BufferKind::Vertex;
  uint64_t size = 0;  // buffers
  ShadowBuffer contents;
  // Vertex buffers: bit v set when checkVertices found vertex v valid under checkedLayout, so a vertex
  // that many indices (and draws) share is read and checked once. An upload or another layout clears it.
  std::vector<uint64_t> checkedVertices;
  VertexLayout checkedLayout;
  // Indices checked against checkedVertices since it was cleared, and whether every vertex of the
  // buffer has been checked in one sequential sweep since (checkVertices).
  uint64_t checkedIndices = 0;
  bool swept = false;
  SamplerState sampler;  // samplers
};

// Bytes a backend allocates for a texture with a valid description: every level of every layer.
// Buffer textures own no storage (their texels are the buffer's bytes). nullopt on overflow, which
// valid sizes cannot reach; the arithmetic is checked so that this stays true if the limits grow.
std::optional<uint64_t> textureBytes(const TextureDesc& d) {
  if (d.kind == TextureKind::Buffer) return 0;
  std::optional<uint64_t> sum = 0;
  for (uint32_t level = 0; level < d.levels && sum; ++level) {
    const std::optional<uint64_t> bytes = checkedMul(levelBytes(d, level), d.layers);
    sum = bytes ? checkedAdd(*sum, *bytes) : std::nullopt;
  }
  return sum;
}

// The running total of a frame's memory (validate.h): where it first went over the budget and what the
// whole frame needs (nullopt once the sum no longer fits in 64 bits).
class FrameMemory {
 public:
  explicit FrameMemory(uint64_t budget) : budget_(budget) {}

  void add(std::optional<uint64_t> bytes, size_t command) {
    if (total_) total_ = bytes ? checkedAdd(*total_, *bytes) : std::nullopt;
    if (!firstOver_ && (!total_ || *total_ > budget_)) firstOver_ = command;
  }

  // The diagnostic, if the frame is over the budget.
  std::optional<Diagnostic> verdict() const {
    if (!firstOver_) return std::nullopt;
    return Diagnostic{*firstOver_, overLimitMessage("frame", "of textures, buffers and render targets", total_, budget_,
                                                    "--memory-budget", true)};
  }

 private:
  uint64_t budget_;
  std::optional<uint64_t> total_ = 0;
  std::optional<size_t> firstOver_;
};

class Validator {
 public:
  Validator(const CommandList& list, const ResourceLimits& limits) : list_(list), memory_(limits.frameBytes) {}

  std::vector<Diagnostic> run() {
    const auto& cmds = list_.commands();
    for (cur_ = 0; cur_ < cmds.size(); ++cur_) std::visit([this](const auto& c) { check(c); }, cmds[cur_]);
    // Known only at the end (the message gives the whole frame's need); inserted in command order.
    if (std::optional<Diagnostic> over = memory_.verdict()) {
      const auto at = std::upper_bound(out_.begin(), out_.end(), over->command,
                                       [](size_t command, const Diagnostic& d) { return command < d.command; });
      out_.insert(at, std::move(*over));
    }
    return std::move(out_);
  }

 private:
  template <class... Args>
  void report(fmt::format_string<Args...> f, Args&&... args) {
    out_.push_back({cur_, fmt::format(f, std::forward<Args>(args)...)});
  }

  // --- resources ----------------------------------------------------------------------------

  // The resource `id` if it exists and has kind `k`; reports and returns nullptr otherwise.
  // `role` names the field in messages.
  Resource* lookup(ResourceId id, Kind k, std::string_view role) {
    // "texture id 9 ..." when the field is just the resource, "color[0]: texture id 9 ..." otherwise.
    const std::string prefix = role == kindName(k) ? std::string() : fmt::format("{}: ", role);
    auto it = res_.find(id);
    if (it == res_.end()) {
      report("{}{} id {} does not exist (not created before this command)", prefix, kindName(k), id);
      return nullptr;
    }
    if (it->second.kind != k) {
      report("{}id {} is a {} (created by command {}), not a {}", prefix, id, kindName(it->second.kind),
             it->second.createdBy, kindName(k));
      return nullptr;
    }
    return &it->second;
  }
  // As lookup(), but id 0 ("none") is accepted and yields nullptr without a report.
  Resource* lookupOrNone(ResourceId id, Kind k, std::string_view role) {
    return id == kNone ? nullptr : lookup(id, k, role);
  }

  Resource* create(ResourceId id, Kind k) {
    if (id == kNone) {
      report("id 0 is reserved for \"none\" and cannot be created");
      return nullptr;
    }
    if (auto it = res_.find(id); it != res_.end()) {
      report("duplicate create of id {} (already created by command {} as a {})", id, it->second.createdBy,
             kindName(it->second.kind));
      return nullptr;
    }
    if (id != nextId_) report("id {} is out of creation order (expected {})", id, nextId_);
    nextId_ = std::max<uint64_t>(nextId_, uint64_t(id) + 1);
    Resource& r = res_[id];
    r.kind = k;
    r.createdBy = cur_;
    return &r;
  }

  bool checkBlob(BlobRange r) {
    if (blobOk(list_, r)) return true;
    report("data [{}, +{}) lies outside the blob ({} bytes)", r.offset, r.size, list_.blob().size());
    return false;
  }

  // --- commands -----------------------------------------------------------------------------

  void check(const CreateTexture& c) {
    Resource* r = create(c.id, Kind::Texture);
    if (!r) return;
    r->desc = c.desc;
    r->valid = checkDesc(c.desc);
    if (r->valid) memory_.add(textureBytes(c.desc), cur_);
  }

  bool checkDesc(const TextureDesc& d) {
    if (!enumOk(d.kind) || !enumOk(d.format)) {
      report("desc.kind = {} / desc.format = {} is out of range", unsigned(d.kind), unsigned(d.format));
      return false;
    }
    bool ok = true;
    if (!enumOk(d.compression)) {
      report("desc.compression = {} is out of range (0 none, 1 BC1, 2 BC3)", unsigned(d.compression));
      return false;
    }
    // S3TC blocks decode to RGBA8, and only plain 2D textures use them: GL cannot render into a compressed
    // format, and nothing here needs compressed arrays.
    if (d.compression != BcFormat::None && (d.kind != TextureKind::Tex2D || d.format != Format::RGBA8)) {
      report("desc.compression = {} needs a Tex2D RGBA8 texture (has {} {})", bcFormatName(d.compression),
             d.kind == TextureKind::Tex2D ? "Tex2D" : d.kind == TextureKind::Tex2DArray ? "Tex2DArray" : "Buffer",
             formatName(d.format));
      return false;
    }
    if (d.kind == TextureKind::Buffer) {
      // glTexBuffer: a texel buffer seen as a 1D array of texels; one level, one layer.
      if (d.format == Format::D32F) {
        report("a Buffer texture cannot have format D32F (GL 4.6 Table 8.16 has no depth formats)");
        ok = false;
      }
      if (d.width == 0 || d.width > kMaxBufferTextureTexels) {
        report("desc.width = {} texels is out of range for a Buffer texture (1..{})", d.width, kMaxBufferTextureTexels);
        ok = false;
      }
      if (d.height != 1 || d.layers != 1 || d.levels != 1) {
        report("a Buffer texture needs height, layers and levels = 1 (has {}, {}, {})", d.height, d.layers, d.levels);
        ok = false;
      }
      if (d.buffer == kNone) {
        report("desc.buffer: a Buffer texture needs a Texel buffer");
        return false;
      }
      Resource* b = lookup(d.buffer, Kind::Buffer, "desc.buffer");
      if (!b) return false;
      if (b->bufferKind != BufferKind::Texel) {
        report("desc.buffer: buffer {} is a {} buffer, a Buffer texture needs a Texel buffer", d.buffer,
               bufferKindName(b->bufferKind));
        return false;
      }
      if (ok && uint64_t(d.width) * texelBytes(d.format) > b->size) {
        report("desc.width = {} texels of {} need {} bytes but buffer {} has {}", d.width, formatName(d.format),
               uint64_t(d.width) * texelBytes(d.format), d.buffer, b->size);
        ok = false;
      }
      return ok;
    }
    if (d.buffer != kNone) {
      report("desc.buffer = {} is only meaningful for Buffer textures", d.buffer);
      ok = false;
    }
    if (d.width == 0 || d.height == 0 || d.width > uint32_t(kMaxTextureSize) || d.height > uint32_t(kMaxTextureSize)) {
      report("size {}x{} is out of range (1..{})", d.width, d.height, kMaxTextureSize);
      return false;  // fullMipCount below needs sane sizes
    }
    const uint32_t maxLayers = d.kind == TextureKind::Tex2D ? 1u : uint32_t(kMaxArrayLayers);
    if (d.layers == 0 || d.layers > maxLayers) {
      report("desc.layers = {} is out of range (1..{})", d.layers, maxLayers);
      ok = false;
    }
    const uint32_t maxLevels = fullMipCount(d.width, d.height);
    if (d.levels == 0 || d.levels > maxLevels) {
      report("desc.levels = {} is out of range (1..{} for {}x{})", d.levels, maxLevels, d.width, d.height);
      ok = false;
    }
    return ok;
  }

  void check(const UploadTexture& c) {
    const bool blob = checkBlob(c.data);
    Resource* t = lookup(c.id, Kind::Texture, "id");
    if (!t || !t->valid) return;
    const TextureDesc& d = t->desc;
    if (d.kind == TextureKind::Buffer) {
      report("texture {} is a Buffer texture; upload its buffer instead", c.id);
      return;
    }
    if (c.level >= d.levels) report("level {} is out of range (texture {} has {} levels)", c.level, c.id, d.levels);
    if (c.layer >= d.layers) report("layer {} is out of range (texture {} has {} layers)", c.layer, c.id, d.layers);
    if (c.level < d.levels && blob && c.data.size != uploadBytes(d, c.level)) {
      report("data has {} bytes but level {} of texture {} ({}x{} {}{}) has {}", c.data.size, c.level, c.id,
             levelWidth(d, c.level), levelHeight(d, c.level), formatName(d.format),
             d.compression == BcFormat::None ? "" : std::string(" as ") + bcFormatName(d.compression) + " blocks",
             uploadBytes(d, c.level));
    }
  }

  void check(const CreateBuffer& c) {
    Resource* r = create(c.id, Kind::Buffer);
    if (!r) return;
    r->bufferKind = c.kind;
    r->size = c.size;
    r->contents = ShadowBuffer(c.size);
    memory_.add(c.size, cur_);
    if (!enumOk(c.kind)) {
      report("kind = {} is out of range", unsigned(c.kind));
      r->valid = false;
    }
    if (c.size > kMaxBufferBytes) {
      report("size {} exceeds the limit of {} bytes", c.size, kMaxBufferBytes);
      r->valid = false;
    }
  }

  void check(const UploadBuffer& c) {
    const bool blob = checkBlob(c.data);
    Resource* b = lookup(c.id, Kind::Buffer, "id");
    if (!b || !b->valid) return;
    if (c.offset > b->size || c.data.size > b->size - c.offset) {
      report("bytes [{}, +{}) are out of range of buffer {} ({} bytes)", c.offset, c.data.size, c.id, b->size);
      return;
    }
    if (blob) b->contents.upload(c.offset, list_.bytes(c.data));
    b->checkedVertices.clear(), b->checkedIndices = 0, b->swept = false;
  }

  void check(const CreateSampler& c) {
    Resource* r = create(c.id, Kind::Sampler);
    if (!r) return;
    r->sampler = c.state;
    const SamplerState& s = c.state;
    if (!enumOk(s.wrapS) || !enumOk(s.wrapT) || !enumOk(s.minFilter) || !enumOk(s.magFilter)) {
      report("a wrap or filter mode is out of range");
      r->valid = false;
      return;
    }
    if (s.magFilter != Filter::Nearest && s.magFilter != Filter::Linear) {
      report("magFilter must be Nearest or Linear (GL 4.6 §8.14.3)");
      r->valid = false;
    }
    // The LOD parameters are quantized to fixed point; a NaN or infinity has no fixed-point value.
    if (!std::isfinite(s.minLod) || !std::isfinite(s.maxLod) || !std::isfinite(s.lodBias)) {
      report("minLod, maxLod and lodBias must be finite (are {}, {}, {})", s.minLod, s.maxLod, s.lodBias);
      r->valid = false;
    }
  }

  void check(const CreateProgram& c) {
    Resource* r = create(c.id, Kind::Program);
    if (!r) return;
    if (findProgram(c.name) == nullptr) {
      report("program name \"{}\" is not in the program registry", c.name);
      r->valid = false;
    }
  }

  bool checkUnit(uint32_t unit) {
    if (unit < uint32_t(kMaxTextureUnits)) return true;
    report("unit {} is out of range (0..{})", unit, kMaxTextureUnits - 1);
    return false;
  }
  void check(const BindTexture& c) {
    const Resource* t = lookupOrNone(c.texture, Kind::Texture, "texture");
    if (checkUnit(c.unit)) unitTexture_[c.unit] = t ? c.texture : kNone;
  }
  void check(const BindSampler& c) {
    const Resource* s = lookupOrNone(c.sampler, Kind::Sampler, "sampler");
    if (checkUnit(c.unit)) unitSampler_[c.unit] = s ? c.sampler : kNone;
  }
  void check(const UseProgram& c) {
    lookupOrNone(c.program, Kind::Program, "program");
    program_ = c.program;
  }

  void check(const SetUniforms& c) {
    const bool blob = checkBlob(c.data);
    if (program_ == kNone) report("no program in use (uniforms are state of the current program)");
    if (uint64_t(c.slot) + c.count > uint64_t(kMaxUniformSlots)) {
      report("slots [{}, {}) exceed the {} uniform slots", c.slot, uint64_t(c.slot) + c.count, kMaxUniformSlots);
    }
    if (blob && c.data.size != uint64_t(c.count) * 16) {
      report("data has {} bytes but {} vec4 slots need {}", c.data.size, c.count, uint64_t(c.count) * 16);
    }
  }

  // Binding checks for vertex / index buffers: the buffer must be of the matching kind.
  void checkBufferBinding(ResourceId id, BufferKind want, std::string_view cmd) {
    Resource* b = lookupOrNone(id, Kind::Buffer, "buffer");
    if (b && b->valid && b->bufferKind != want) {
      report("buffer {} is a {} buffer, {} needs a {} buffer", id, bufferKindName(b->bufferKind), cmd,
             bufferKindName(want));
    }
  }
  void check(const BindVertexBuffer& c) {
    checkBufferBinding(c.buffer, BufferKind::Vertex, "BindVertexBuffer");
    vertexBuffer_ = c.buffer;
  }
  void check(const BindIndexBuffer& c) {
    checkBufferBinding(c.buffer, BufferKind::Index, "BindIndexBuffer");
    if (!enumOk(c.type)) report("type = {} is out of range", unsigned(c.type));
    indexBuffer_ = c.buffer;
    indexType_ = c.type;
  }

  void check(const SetVertexLayout& c) {
    layoutSet_ = true;
    layout_ = c.layout;
    layoutOk_ = true;
    uint32_t seen = 0;  // bit per location
    bool anyEnabled = false;
    for (int i = 0; i < kMaxAttribs; ++i) {
      const VertexAttrib& a = c.layout.attribs[i];
      if (a.components == 0) continue;
      anyEnabled = true;
      if (a.components > 4 || a.location >= kMaxAttribs || !enumOk(a.type)) {
        report("attribs[{}]: components = {}, location = {}, type = {} must be 1..4, 0..{}, F32/U32", i, a.components,
               a.location, unsigned(a.type), kMaxAttribs - 1);
        layoutOk_ = false;
        continue;
      }
      if (seen & (1u << a.location)) {
        report("attribs[{}]: location {} is used by two attributes", i, a.location);
        layoutOk_ = false;
      }
      seen |= 1u << a.location;
    }
    // GL's minimum MAX_VERTEX_ATTRIB_STRIDE is 2048 and MAX_VERTEX_ATTRIB_RELATIVE_OFFSET 2047
    // (GL 4.6 Table 23.55); llvmpipe has exactly these, so a frame beyond them is not portable.
    if (c.layout.stride > 2048) {
      report("stride {} exceeds GL's guaranteed GL_MAX_VERTEX_ATTRIB_STRIDE (2048)", c.layout.stride);
      layoutOk_ = false;
    }
    for (size_t i = 0; i < c.layout.attribs.size(); ++i)
      if (c.layout.attribs[i].components != 0 && c.layout.attribs[i].offset > 2047) {
        report("attribs[{}]: offset {} exceeds GL's guaranteed GL_MAX_VERTEX_ATTRIB_RELATIVE_OFFSET (2047)", i,
               c.layout.attribs[i].offset);
        layoutOk_ = false;
      }
    if (anyEnabled && c.layout.stride == 0) {
      // GL reads stride 0 as "tightly packed"; a literal reading would repeat vertex 0. Neither
      // backend may guess, so it is rejected.
      report("stride 0 is ambiguous (GL reads it as tightly packed); give the stride in bytes");
      layoutOk_ = false;
    }
  }

  void check(const SetViewport& c) {
    const Rect& r = c.rect;
    if (r.w <= 0 || r.h <= 0 || r.w > kMaxTextureSize || r.h > kMaxTextureSize) {
      report("viewport size {}x{} is out of range (1..{})", r.w, r.h, kMaxTextureSize);
    }
    if (r.x < -kMaxViewportOffset || r.x > kMaxViewportOffset || r.y < -kMaxViewportOffset ||
        r.y > kMaxViewportOffset) {
      report("viewport origin ({}, {}) is out of range (-{}..{})", r.x, r.y, kMaxViewportOffset, kMaxViewportOffset);
    }
  }
  void check(const SetScissor& c) {
    if (c.state.rect.w < 0 || c.state.rect.h < 0) {
      report("scissor size {}x{} is negative", c.state.rect.w, c.state.rect.h);
    }
  }
  void check(const SetDepthState& c) {
    if (!enumOk(c.state.func)) report("func = {} is out of range", unsigned(c.state.func));
  }
  void check(const SetBlendState& c) {
    const BlendState& b = c.state;
    if (!enumOk(b.eqRgb) || !enumOk(b.eqAlpha) || !enumOk(b.srcRgb) || !enumOk(b.dstRgb) || !enumOk(b.srcAlpha) ||
        !enumOk(b.dstAlpha)) {
      report("a blend equation or factor is out of range");
    }
  }
  void check(const SetRasterState& c) {
    if (!enumOk(c.state.cull)) report("cull = {} is out of range", unsigned(c.state.cull));
  }

  void check(const SetRenderTarget& c) {
    target_ = c.target;
    const RenderTarget& t = c.target;
    struct Attached {
      std::string name;
      const TextureDesc* desc;
    };
    std::vector<Attached> attached;
    auto attach = [&](ResourceId id, std::string name, bool depth) {
      if (id == kNone) return;
      Resource* r = lookup(id, Kind::Texture, name);
      if (!r || !r->valid) return;
      const TextureDesc& d = r->desc;
      if (d.kind == TextureKind::Buffer) {
        report("{}: texture {} is a Buffer texture and cannot be rendered to", name, id);
        return;
      }
      if (d.compression != BcFormat::None) {
        report("{}: texture {} is {}-compressed and cannot be rendered to", name, id, bcFormatName(d.compression));
        return;
      }
      if (depth && d.format != Format::D32F) {
        report("{}: texture {} has format {}; depth attachments must be D32F", name, id, formatName(d.format));
      }
      if (!depth && d.format == Format::D32F) {
        report("{}: texture {} has format D32F, which is not colour-renderable", name, id);
      }
      if (t.level >= d.levels) {
        report("level {} is out of range for {} (texture {} has {} levels)", t.level, name, id, d.levels);
        return;
      }
      if (t.layer == kLayered) {
        if (d.kind != TextureKind::Tex2DArray) {
          report("{}: a layered target needs array textures; texture {} is 2D", name, id);
        }
      } else if (t.layer >= d.layers) {
        report("layer {} is out of range for {} (texture {} has {} layers)", t.layer, name, id, d.layers);
      }
      attached.push_back({std::move(name), &d});
    };
    for (int i = 0; i < kMaxColorAttachments; ++i) {
      attach(t.color[i], fmt::format("color[{}]", i), false);
      for (int j = 0; j < i; ++j) {
        if (t.color[i] != kNone && t.color[i] == t.color[j]) {
          report("texture {} is attached as color[{}] and color[{}]", t.color[i], j, i);
        }
      }
    }
    attach(t.depth, "depth", true);
    // GL 4.6 §9.4.2 allows differing sizes (rendering uses the intersection); the oracle requires
    // equal ones so that no backend has to reproduce that rule.
    for (size_t i = 1; i < attached.size(); ++i) {
      const auto& a = attached[0];
      const auto& b = attached[i];
      const uint32_t aw = levelWidth(*a.desc, t.level), ah = levelHeight(*a.desc, t.level);
      const uint32_t bw = levelWidth(*b.desc, t.level), bh = levelHeight(*b.desc, t.level);
      if (aw != bw || ah != bh) {
        report("attachment sizes differ at level {}: {} is {}x{}, {} is {}x{}", t.level, a.name, aw, ah, b.name, bw,
               bh);
      }
    }
  }

  bool hasTarget() const {
    return target_.depth != kNone ||
           std::any_of(target_.color.begin(), target_.color.end(), [](ResourceId id) { return id != kNone; });
  }

  void check(const ClearColor& c) {
    if (!hasTarget()) {
      report("no render target set");
    } else if (c.attachment >= uint32_t(kMaxColorAttachments)) {
      report("attachment {} is out of range (0..{})", c.attachment, kMaxColorAttachments - 1);
    } else if (target_.color[c.attachment] == kNone) {
      report("colour attachment {} is not attached to the current render target", c.attachment);
    }
  }
  void check(const ClearDepth& c) {
    if (!hasTarget()) {
      report("no render target set");
    } else if (target_.depth == kNone) {
      report("the current render target has no depth attachment");
    }
    if (std::isnan(c.depth)) report("depth is NaN");
  }

  void check(const Marker&) {}

  void check(const Draw& d) {
    if (!enumOk(d.primitive)) report("primitive = {} is out of range", unsigned(d.primitive));
    bool ready = enumOk(d.primitive);
    auto require = [&](bool ok, std::string_view what) {
      if (!ok) {
        report("{}", what);
        ready = false;
      }
    };
    require(program_ != kNone, "no program in use");
    require(vertexBuffer_ != kNone, "no vertex buffer bound");
    require(layoutSet_, "no vertex layout set");
    require(hasTarget(), "no render target set");
    require(!d.indexed || indexBuffer_ != kNone, "indexed draw without an index buffer");
    checkFeedbackLoops();
    if (!ready || !layoutOk_ || d.count == 0) return;

    // Problems with the bound resources themselves were reported when they were bound or created.
    Resource* vb = usable(vertexBuffer_, BufferKind::Vertex);
    if (!vb) return;
    if (d.indexed) {
      Resource* ib = usable(indexBuffer_, BufferKind::Index);
      if (!ib || !enumOk(indexType_)) return;
      const uint64_t isz = indexType_ == IndexType::U16 ? 2 : 4;
      const uint64_t end = (uint64_t(d.first) + d.count) * isz;
      if (end > ib->size) {
        report("indices [{}, {}) read bytes [{}, {}) past the end of index buffer {} ({} bytes)", d.first,
               uint64_t(d.first) + d.count, d.first * isz, end, indexBuffer_, ib->size);
        return;
      }
      ShadowBuffer& indices = ib->contents;
      indices.flush();
      const uint64_t base = d.first * isz;
      if (isz == 2) {
        checkVertices(
            *vb, d.count,
            [&indices, base](uint32_t k) {
              uint8_t b[2];
              indices.read(base + 2 * uint64_t(k), 2, b);
              return uint32_t(b[0]) | uint32_t(b[1]) << 8;
            },
            d.first);
      } else {
        checkVertices(
            *vb, d.count,
            [&indices, base](uint32_t k) {
              uint8_t b[4];
              indices.read(base + 4 * uint64_t(k), 4, b);
              return readLe32(b);
            },
            d.first);
      }
    } else {
      if (uint64_t(d.first) + d.count - 1 > UINT32_MAX) {
        report("vertices [{}, {}) go beyond vertex index 2^32 - 1", d.first, uint64_t(d.first) + d.count);
        return;
      }
      const uint32_t first = d.first;
      checkVertices(
          *vb, d.count, [first](uint32_t k) { return first + k; }, -1);
    }
  }

  // GL 4.6 §9.3.1: sampling a texture level that is also attached to the render target is undefined
  // (a feedback loop); docs/spec-choices.md F8 rejects it. Which units a program samples is not
  // known here, so every bound unit counts. The unit's sampler decides the levels it can read: a
  // mipmap min filter reaches every level, otherwise only level 0 (GL's base level). Sampler 0
  // means the default sampler state, whose min filter is a mipmap one.
  void checkFeedbackLoops() {
    for (int u = 0; u < kMaxTextureUnits; ++u) {
      const ResourceId tex = unitTexture_[size_t(u)];
      if (tex == kNone) continue;
      std::string attachment;
      for (int a = 0; a < kMaxColorAttachments; ++a) {
        if (target_.color[size_t(a)] == tex) attachment = fmt::format("color[{}]", a);
      }
      if (target_.depth == tex) attachment = "depth";
      if (attachment.empty()) continue;
      const ResourceId smp = unitSampler_[size_t(u)];
      const bool mipmapped = smp == kNone || usesMipmaps(res_.at(smp).sampler.minFilter);
      if (mipmapped || target_.level == 0) {
        report(
            "texture {} on unit {} is also attached to the render target as {} at level {} (a feedback loop, "
            "undefined in GL 4.6 §9.3.1)",
            tex, u, attachment, target_.level);
      }
    }
  }

  Resource* usable(ResourceId id, BufferKind want) {
    auto it = res_.find(id);
    if (it == res_.end()) return nullptr;
    Resource& r = it->second;
    return r.kind == Kind::Buffer && r.valid && r.bufferKind == want ? &r : nullptr;
  }

  // Checks the `count` vertices vertexOf(0 .. count-1) of a draw against the layout: every
  // attribute fetch inside the buffer, position finite, U32 values exact as float. Reports the first
  // problem of each kind only, so a broken million-vertex draw gives a handful of lines.
  // `firstIndex` is the draw's first index for indexed draws (to name the index), else -1.
  template <class VertexOf>
  void checkVertices(Resource& vb, uint32_t count, VertexOf vertexOf, int64_t firstIndex) {
    struct Attr {
      uint32_t offset, bytes;
      uint8_t location, components;
      AttribType type;
    };
    Attr attrs[kMaxAttribs];
    int n = 0;
    for (const VertexAttrib& a : layout_.attribs) {
      if (a.components != 0) attrs[n++] = {a.offset, 4u * a.components, a.location, a.components, a.type};
    }
    if (n == 0) return;
    // Highest vertex whose every fetch ends inside the buffer (fetch end grows with the vertex).
    const uint64_t stride = layout_.stride;
    int64_t maxVertex = INT64_MAX;
    for (int i = 0; i < n; ++i) {
      const uint64_t need = uint64_t(attrs[i].offset) + attrs[i].bytes;
      maxVertex = need > vb.size ? -1 : std::min<int64_t>(maxVertex, int64_t((vb.size - need) / stride));
    }
    ShadowBuffer& data = vb.contents;
    data.flush();
    // Speed only (the diagnostics are the same): the vertices found valid before. Kept for buffers of
    // up to 2^26 vertices (an 8 MiB bitmap).
    if (!(vb.checkedLayout == layout_))
      vb.checkedVertices.clear(), vb.checkedIndices = 0, vb.swept = false, vb.checkedLayout = layout_;
    const bool remember = maxVertex >= 0 && maxVertex < (int64_t(1) << 26);
    if (remember && vb.checkedVertices.empty()) vb.checkedVertices.assign(size_t(maxVertex) / 64 + 1, 0);
    // Once the draws have checked about half as many indices as the buffer has vertices, every vertex
    // is checked in one sequential sweep (no index reads, no scattered vertex reads); the loop below
    // then reads only the bitmap for valid vertices, and reports the invalid ones as before.
    if (remember && !vb.swept && (vb.checkedIndices += count) > uint64_t(maxVertex) / 2) {
      vb.swept = true;
      for (uint64_t v = 0; v <= uint64_t(maxVertex); ++v)
        if (vertexValid(data, v, stride, attrs, n)) vb.checkedVertices[v >> 6] |= uint64_t(1) << (v & 63);
    }
    bool reportedFinite = false, reportedU32 = false;
    for (uint32_t k = 0; k < count; ++k) {
      const uint32_t v = vertexOf(k);
      if (remember && int64_t(v) <= maxVertex && (vb.checkedVertices[v >> 6] >> (v & 63) & 1)) continue;
      if (int64_t(v) > maxVertex) {
        for (int i = 0; i < n; ++i) {
          const uint64_t begin = uint64_t(v) * stride + attrs[i].offset, end = begin + attrs[i].bytes;
          if (end <= vb.size) continue;
          const std::string which = firstIndex >= 0 ? fmt::format("index {} = ", firstIndex + k) : std::string();
          report(
              "{}vertex {}: attribute at location {} reads bytes [{}, {}) past the end of vertex buffer {} "
              "({} bytes)",
              which, v, attrs[i].location, begin, end, vertexBuffer_, vb.size);
          break;
        }
        return;
      }
      if (reportedFinite && reportedU32) continue;  // keep scanning only for out-of-range fetches
      const bool checkedAll = !reportedFinite && !reportedU32;  // both checks run on this vertex
      for (int i = 0; i < n; ++i) {
        const Attr& a = attrs[i];
        const bool position = a.location == 0 && a.type == AttribType::F32;
        if (!(position && !reportedFinite) && !(a.type == AttribType::U32 && !reportedU32)) continue;
        uint8_t scratch[16];
        const uint8_t* fetched = data.view(uint64_t(v) * stride + a.offset, a.bytes, scratch);
        for (int c = 0; c < a.components; ++c) {
          const uint32_t bits = readLe32(fetched + 4 * c);
          if (position && (bits & 0x7f800000u) == 0x7f800000u) {
            report("vertex {}: position (location 0) component {} is {}", v, c, std::bit_cast<float>(bits));
            reportedFinite = true;
            break;
          }
          if (a.type == AttribType::U32 && bits >= kMaxExactU32) {
            report(
                "vertex {}: U32 attribute at location {} component {} = {} is >= 2^24 (programs receive it as "
                "float)",
                v, a.location, c, bits);
            reportedU32 = true;
            break;
          }
        }
      }
      if (remember && checkedAll && !reportedFinite && !reportedU32) vb.checkedVertices[v >> 6] |= uint64_t(1) << (v & 63);
    }
  }

  // Whether vertex v, whose every fetch is inside the buffer, passes checkVertices' checks: a finite
  // F32 position (location 0) and U32 values below 2^24.
  template <class Attr>
  static bool vertexValid(const ShadowBuffer& data, uint64_t v, uint64_t stride, const Attr* attrs, int n) {
    for (int i = 0; i < n; ++i) {
      const Attr& a = attrs[i];
      const bool position = a.location == 0 && a.type == AttribType::F32;
      if (!position && a.type != AttribType::U32) continue;
      uint8_t scratch[16];
      const uint8_t* fetched = data.view(v * stride + a.offset, a.bytes, scratch);
      for (int c = 0; c < a.components; ++c) {
        const uint32_t bits = readLe32(fetched + 4 * c);
        if (position && (bits & 0x7f800000u) == 0x7f800000u) return false;
        if (a.type == AttribType::U32 && bits >= kMaxExactU32) return false;
      }
    }
    return true;
  }

  const CommandList& list_;
  FrameMemory memory_;
  std::vector<Diagnostic> out_;
  size_t cur_ = 0;
  std::unordered_map<ResourceId, Resource> res_;
  uint64_t nextId_ = 1;

  std::array<ResourceId, kMaxTextureUnits> unitTexture_{}, unitSampler_{};  // only existing resources
  ResourceId program_ = kNone, vertexBuffer_ = kNone, indexBuffer_ = kNone;
  IndexType indexType_ = IndexType::U16;
  bool layoutSet_ = false, layoutOk_ = false;
  VertexLayout layout_{};
  RenderTarget target_{};
};

}  // namespace

std::vector<Diagnostic> validate(const CommandList& list, const ResourceLimits& limits) {
  return Validator(list, limits).run();
}

void validateOrThrow(const CommandList& list, std::string_view frameName, const ResourceLimits& limits) {
  const std::vector<Diagnostic> diags = validate(list, limits);
  if (diags.empty()) return;
  constexpr size_t kShown = 10;
  std::string msg =
      fmt::format("{}: {} problem{} in the command list", frameName, diags.size(), diags.size() == 1 ? "" : "s");
  for (size_t i = 0; i < diags.size() && i < kShown; ++i) {
    const Diagnostic& d = diags[i];
    msg +=
        fmt::format("\n  command {} ({}): {}", d.command, commandName(list.commands()[d.command].index()), d.message);
  }
  if (diags.size() > kShown) msg += fmt::format("\n  ... and {} more", diags.size() - kShown);
  throw Error(msg);
}

}  // namespace tessera
