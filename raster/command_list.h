// A frame as data: the ordered list of every resource creation, upload, state change, clear and
// draw a technique issues. Backends replay it; counters are computed from it; it serializes to a
// .tframe file (serialize.h).
//
// Common principles
// - Resources (textures, buffers, samplers, programs) are named by dense ids handed out by the
//   create* calls, in creation order. Id 0 is "none" for every resource kind.
// - Bulk bytes (uploads, uniforms) live in one blob; commands refer to ranges of it, so a command
//   is a small value and the list copies and serializes cheaply.
// - Recording never validates; validate() (validate.h) does, and every backend refuses an invalid
//   list with an Error naming the command index.
// Does not implement: execution (cpu_backend.h), counting (counters.h).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "base/error.h"
#include "raster/bc_decode.h"
#include "raster/limits.h"
#include "raster/types.h"

namespace tessera {

using ResourceId = uint32_t;
constexpr ResourceId kNone = 0;

struct BlobRange {
  uint64_t offset = 0;
  uint64_t size = 0;
};

struct TextureDesc {
  TextureKind kind = TextureKind::Tex2D;
  Format format = Format::RGBA8;
  uint32_t width = 0, height = 1, layers = 1, levels = 1;
  ResourceId buffer = kNone;  // Buffer kind only: the buffer whose bytes are the texels (glTexBuffer)
  // BC1 / BC3: a Tex2D RGBA8 texture whose uploads carry S3TC blocks (bc_decode.h). GL keeps the blocks
  // (GL_COMPRESSED_RGB_S3TC_DXT1_EXT / GL_COMPRESSED_RGBA_S3TC_DXT5_EXT); the oracle decodes them into its
  // RGBA8 storage by the rule of docs/spec-choices.md C1-C4. Until a level is uploaded it holds all-zero
  // blocks, which decode to opaque black (BC1) or transparent black (BC3).
  BcFormat compression = BcFormat::None;
};

enum class BufferKind : uint8_t { Vertex = 0, Index = 1, Texel = 2, Count };

// --- commands -------------------------------------------------------------------------------
struct CreateTexture { ResourceId id; TextureDesc desc; };
// Replaces one whole level of one layer (glTextureSubImage3D of the full level). Texels are tightly
// packed rows, bottom row first (GL's convention); for a compressed texture, the level's S3TC blocks
// (glCompressedTextureSubImage2D), block row 0 holding rows 0..3.
struct UploadTexture { ResourceId id; uint32_t level, layer; BlobRange data; };
struct CreateBuffer { ResourceId id; BufferKind kind; uint64_t size; };
struct UploadBuffer { ResourceId id; uint64_t offset; BlobRange data; };
struct CreateSampler { ResourceId id; SamplerState state; };
// A program is a name looked up in the program registry (program.h) at replay time.
struct CreateProgram { ResourceId id; std::string name; };

struct BindTexture { uint32_t unit; ResourceId texture; };
struct BindSampler { uint32_t unit; ResourceId sampler; };
struct UseProgram { ResourceId program; };
// Uniform vec4 slots [slot, slot + count) of the current program's uniform storage.
struct SetUniforms { uint32_t slot, count; BlobRange data; };
struct BindVertexBuffer { ResourceId buffer; };
struct SetVertexLayout { VertexLayout layout; };
struct BindIndexBuffer { ResourceId buffer; IndexType type; };
struct SetViewport { Rect rect; };
struct SetScissor { ScissorState state; };
struct SetDepthState { DepthState state; };
struct SetBlendState { BlendState state; };
struct SetRasterState { RasterState state; };

constexpr uint32_t kLayered = 0xffffffffu;  // RenderTarget::layer: the program chooses (gl_Layer)
struct RenderTarget {
  std::array<ResourceId, kMaxColorAttachments> color{};  // textures; kNone = unused attachment
  ResourceId depth = kNone;                               // a D32F texture or kNone
  uint32_t level = 0;                                     // mip level rendered to
  uint32_t layer = 0;  // array layer, or kLayered to attach every layer (glFramebufferTexture)
  bool operator==(const RenderTarget&) const = default;
};
// Target 0 (all kNone) is the "default framebuffer" only in name: a frame must set a target
// before drawing.
struct SetRenderTarget { RenderTarget target; };

// Clears respect the scissor (GL 4.6 §17.4.3) and clear every attached layer of a layered target.
struct ClearColor { uint32_t attachment; std::array<uint32_t, 4> bits; };  // float bits or uint values
struct ClearDepth { float depth; };

enum class Primitive : uint8_t { Triangles = 0, Count };
struct Draw {
  Primitive primitive = Primitive::Triangles;
  bool indexed = false;
  uint32_t first = 0;  // first vertex (non-indexed) or first index (indexed)
  uint32_t count = 0;  // vertices or indices; a trailing partial triangle is ignored (GL 4.6 §10.1)
};
// A free-form label (glPushDebugGroup-like); counted nowhere, kept for reports and bisection.
struct Marker { std::string text; };

using Command = std::variant<CreateTexture, UploadTexture, CreateBuffer, UploadBuffer, CreateSampler,
                             CreateProgram, BindTexture, BindSampler, UseProgram, SetUniforms,
                             BindVertexBuffer, SetVertexLayout, BindIndexBuffer, SetViewport, SetScissor,
                             SetDepthState, SetBlendState, SetRasterState, SetRenderTarget, ClearColor,
                             ClearDepth, Draw, Marker>;
// Stable names of the command kinds, indexed by Command::index(); used in errors, reports and the
// file format (the index is the on-disk opcode, so append only).
std::string_view commandName(size_t index);

// The recorded frame.
class CommandList {
 public:
  // --- resources ---
  ResourceId createTexture(const TextureDesc& desc);
  // Uploads level `level` of layer `layer`; `texels` must hold exactly the level's bytes.
  void uploadTexture(ResourceId tex, uint32_t level, uint32_t layer, std::span<const uint8_t> texels);
  ResourceId createBuffer(BufferKind kind, uint64_t size);
  void uploadBuffer(ResourceId buf, uint64_t offset, std::span<const uint8_t> bytes);
  // Convenience: create + upload in one step.
  ResourceId createBuffer(BufferKind kind, std::span<const uint8_t> bytes);
  ResourceId createSampler(const SamplerState& state);
  ResourceId createProgram(std::string_view name);

  // --- state ---
  void bindTexture(uint32_t unit, ResourceId tex) { cmds_.emplace_back(BindTexture{unit, tex}); }
  void bindSampler(uint32_t unit, ResourceId smp) { cmds_.emplace_back(BindSampler{unit, smp}); }
  void useProgram(ResourceId prog) { cmds_.emplace_back(UseProgram{prog}); }
  void setUniforms(uint32_t slot, std::span<const float> values);  // values.size() % 4 == 0
  void bindVertexBuffer(ResourceId buf) { cmds_.emplace_back(BindVertexBuffer{buf}); }
  void setVertexLayout(const VertexLayout& layout) { cmds_.emplace_back(SetVertexLayout{layout}); }
  void bindIndexBuffer(ResourceId buf, IndexType type) { cmds_.emplace_back(BindIndexBuffer{buf, type}); }
  void setViewport(Rect r) { cmds_.emplace_back(SetViewport{r}); }
  void setScissor(ScissorState s) { cmds_.emplace_back(SetScissor{s}); }
  void setDepthState(DepthState s) { cmds_.emplace_back(SetDepthState{s}); }
  void setBlendState(BlendState s) { cmds_.emplace_back(SetBlendState{s}); }
  void setRasterState(RasterState s) { cmds_.emplace_back(SetRasterState{s}); }
  void setRenderTarget(const RenderTarget& t) { cmds_.emplace_back(SetRenderTarget{t}); }

  // --- work ---
  void clearColor(uint32_t attachment, std::array<float, 4> rgba);
  void clearColorUint(uint32_t attachment, std::array<uint32_t, 4> values);
  void clearDepth(float depth) { cmds_.emplace_back(ClearDepth{depth}); }
  void draw(uint32_t first, uint32_t count) { cmds_.emplace_back(Draw{Primitive::Triangles, false, first, count}); }
  void drawIndexed(uint32_t first, uint32_t count) { cmds_.emplace_back(Draw{Primitive::Triangles, true, first, count}); }
  void marker(std::string_view text) { cmds_.emplace_back(Marker{std::string(text)}); }

  // --- access ---
  const std::vector<Command>& commands() const { return cmds_; }
  std::span<const uint8_t> bytes(BlobRange r) const { return {blob_.data() + r.offset, size_t(r.size)}; }
  const std::vector<uint8_t>& blob() const { return blob_; }
  uint32_t resourceCount() const { return nextId_ - 1; }

  // Empties the list for recording the next frame into it, keeping the storage of the commands and
  // the blob: a renderer that records every frame (mta::TreeRenderer uploads every resident atlas,
  // tens of MB) then neither regrows the blob nor faults fresh pages in for it each frame. Ids start
  // again at 1, so the list is the same as a newly constructed one recording the same calls.
  void clear() {
    cmds_.clear();
    blob_.clear();
    nextId_ = 1;
  }

  // Keeps the first n commands (the blob is kept whole, so every range stays valid). Used to replay a
  // prefix of a frame, e.g. for draw-level bisection.
  void truncate(size_t n) {
    if (n < cmds_.size()) cmds_.resize(n);
  }

  // Raw construction for readers (serialize.cpp): appends without interpretation.
  void appendRaw(Command c);
  BlobRange appendBlob(std::span<const uint8_t> bytes);
  void setNextId(uint32_t next) { nextId_ = next; }
  uint32_t nextId() const { return nextId_; }

 private:
  std::vector<Command> cmds_;
  std::vector<uint8_t> blob_;
  uint32_t nextId_ = 1;  // shared id space over all resource kinds
};

// Bytes of level `level` of one layer of a 2D / array texture (tightly packed), as stored by the oracle.
uint64_t levelBytes(const TextureDesc& d, uint32_t level);
// Bytes an UploadTexture of that level carries: levelBytes, or the level's S3TC blocks when compressed.
uint64_t uploadBytes(const TextureDesc& d, uint32_t level);
// max(1, size >> level); inline because texel addressing calls them per pixel.
inline uint32_t levelWidth(const TextureDesc& d, uint32_t level) {
  const uint32_t w = level >= 32 ? 1u : d.width >> level;
  return w > 0 ? w : 1u;
}
inline uint32_t levelHeight(const TextureDesc& d, uint32_t level) {
  const uint32_t h = level >= 32 ? 1u : d.height >> level;
  return h > 0 ? h : 1u;
}
// Number of levels of a full chain for w x h: floor(log2(max(w, h))) + 1.
uint32_t fullMipCount(uint32_t w, uint32_t h);

}  // namespace tessera
