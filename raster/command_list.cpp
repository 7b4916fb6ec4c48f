#include "raster/command_list.h"

#include <algorithm>
#include <cstring>

namespace tessera {

std::string_view formatName(Format f) {
  switch (f) {
    case Format::RGBA8: return "RGBA8";
    case Format::R8: return "R8";
    case Format::RG32F: return "RG32F";
    case Format::RGBA32F: return "RGBA32F";
    case Format::R32UI: return "R32UI";
    case Format::D32F: return "D32F";
    default: return "?";
  }
}

std::string_view commandName(size_t index) {
  static constexpr std::string_view kNames[] = {
      "CreateTexture", "UploadTexture", "CreateBuffer", "UploadBuffer", "CreateSampler", "CreateProgram",
      "BindTexture", "BindSampler", "UseProgram", "SetUniforms", "BindVertexBuffer", "SetVertexLayout",
      "BindIndexBuffer", "SetViewport", "SetScissor", "SetDepthState", "SetBlendState", "SetRasterState",
      "SetRenderTarget", "ClearColor", "ClearDepth", "Draw", "Marker"};
  static_assert(std::size(kNames) == std::variant_size_v<Command>, "one name per command kind");
  return index < std::size(kNames) ? kNames[index] : std::string_view("?");
}

uint64_t levelBytes(const TextureDesc& d, uint32_t level) {
  return uint64_t(levelWidth(d, level)) * levelHeight(d, level) * texelBytes(d.format);
}
uint64_t uploadBytes(const TextureDesc& d, uint32_t level) {
  if (d.compression == BcFormat::None) return levelBytes(d, level);
  return bcLevelBytes(d.compression, levelWidth(d, level), levelHeight(d, level));
}
uint32_t fullMipCount(uint32_t w, uint32_t h) {
  uint32_t m = std::max(w, h), n = 1;
  while (m > 1) { m >>= 1; ++n; }
  return n;
}

BlobRange CommandList::appendBlob(std::span<const uint8_t> bytes) {
  BlobRange r{blob_.size(), bytes.size()};
  blob_.insert(blob_.end(), bytes.begin(), bytes.end());
  return r;
}

void CommandList::appendRaw(Command c) { cmds_.push_back(std::move(c)); }

ResourceId CommandList::createTexture(const TextureDesc& desc) {
  ResourceId id = nextId_++;
  cmds_.emplace_back(CreateTexture{id, desc});
  return id;
}

void CommandList::uploadTexture(ResourceId tex, uint32_t level, uint32_t layer, std::span<const uint8_t> texels) {
  cmds_.emplace_back(UploadTexture{tex, level, layer, appendBlob(texels)});
}

ResourceId CommandList::createBuffer(BufferKind kind, uint64_t size) {
  ResourceId id = nextId_++;
  cmds_.emplace_back(CreateBuffer{id, kind, size});
  return id;
}

ResourceId CommandList::createBuffer(BufferKind kind, std::span<const uint8_t> bytes) {
  ResourceId id = createBuffer(kind, bytes.size());
  uploadBuffer(id, 0, bytes);
  return id;
}

void CommandList::uploadBuffer(ResourceId buf, uint64_t offset, std::span<const uint8_t> bytes) {
  cmds_.emplace_back(UploadBuffer{buf, offset, appendBlob(bytes)});
}

ResourceId CommandList::createSampler(const SamplerState& state) {
  ResourceId id = nextId_++;
  cmds_.emplace_back(CreateSampler{id, state});
  return id;
}

ResourceId CommandList::createProgram(std::string_view name) {
  ResourceId id = nextId_++;
  cmds_.emplace_back(CreateProgram{id, std::string(name)});
  return id;
}

void CommandList::setUniforms(uint32_t slot, std::span<const float> values) {
  std::span<const uint8_t> raw(reinterpret_cast<const uint8_t*>(values.data()), values.size_bytes());
  cmds_.emplace_back(SetUniforms{slot, uint32_t(values.size() / 4), appendBlob(raw)});
}

void CommandList::clearColor(uint32_t attachment, std::array<float, 4> rgba) {
  std::array<uint32_t, 4> bits;
  std::memcpy(bits.data(), rgba.data(), sizeof bits);
  cmds_.emplace_back(ClearColor{attachment, bits});
}

void CommandList::clearColorUint(uint32_t attachment, std::array<uint32_t, 4> values) {
  cmds_.emplace_back(ClearColor{attachment, values});
}

}  // namespace tessera
