#include "verify/visibility_rewrite.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <optional>
#include <type_traits>

#include "base/error.h"
#include "raster/program.h"
#include "raster/validate.h"
#include "verify/vertex_fetch.h"

namespace tessera::verify {

namespace {

constexpr uint32_t kBackground = 0xffffffffu;  // id attachments where no triangle wins
constexpr uint32_t kIdStride = 20;             // vec4 position + one U32 object id

// Replays the state that decides what a draw reads; shared by both passes.
struct Tracker {
  bool withBuffers = true;  // false: state only (safe on a list that has not been validated)
  std::map<ResourceId, std::vector<uint8_t>> buffers;
  std::map<ResourceId, std::string> programNames;
  std::map<ResourceId, TextureDesc> textures;
  std::map<ResourceId, std::array<float, 64>> uniforms;  // slots 0-15 of each program's storage
  ResourceId program = kNone, vertexBuffer = kNone, indexBuffer = kNone;
  IndexType indexType = IndexType::U16;
  VertexLayout layout;
  RenderTarget target;
  DepthState depth;
  BlendState blend;
  ScissorState scissor;

  void apply(const CommandList& list, const Command& command) {
    std::visit(
        [&](const auto& c) {
          using T = std::decay_t<decltype(c)>;
          if constexpr (std::is_same_v<T, CreateBuffer>)
            if (withBuffers) buffers[c.id].assign(size_t(c.size), 0);
          if constexpr (std::is_same_v<T, UploadBuffer>) {
            const auto bytes = list.bytes(c.data);
            std::vector<uint8_t>& b = buffers[c.id];
            if (withBuffers && c.offset <= b.size() && bytes.size() <= b.size() - c.offset)  // always, in a validated list
              std::memcpy(b.data() + c.offset, bytes.data(), bytes.size());
          }
          if constexpr (std::is_same_v<T, CreateProgram>) programNames[c.id] = c.name;
          if constexpr (std::is_same_v<T, CreateTexture>) textures[c.id] = c.desc;
          if constexpr (std::is_same_v<T, UseProgram>) program = c.program;
          if constexpr (std::is_same_v<T, SetUniforms>) {
            auto& m = uniforms.try_emplace(program, std::array<float, 64>{}).first->second;  // GL's initial values: 0
            const auto bytes = list.bytes(c.data);
            for (uint32_t s = c.slot; s < c.slot + c.count && s < 16 && size_t(s - c.slot + 1) * 16 <= bytes.size(); ++s)
              std::memcpy(&m[size_t(s) * 4], bytes.data() + size_t(s - c.slot) * 16, 16);
          }
          if constexpr (std::is_same_v<T, BindVertexBuffer>) vertexBuffer = c.buffer;
          if constexpr (std::is_same_v<T, BindIndexBuffer>) indexBuffer = c.buffer, indexType = c.type;
          if constexpr (std::is_same_v<T, SetVertexLayout>) layout = c.layout;
          if constexpr (std::is_same_v<T, SetRenderTarget>) target = c.target;
          if constexpr (std::is_same_v<T, SetDepthState>) depth = c.state;
          if constexpr (std::is_same_v<T, SetBlendState>) blend = c.state;
          if constexpr (std::is_same_v<T, SetScissor>) scissor = c.state;
        },
        command);
  }
  std::string programName() const {
    const auto it = programNames.find(program);
    return it == programNames.end() ? std::string() : it->second;
  }
};

std::optional<RenderTarget> presentedTarget(const CommandList& list) {
  std::optional<RenderTarget> t;
  for (const Command& c : list.commands())
    if (const auto* s = std::get_if<SetRenderTarget>(&c)) t = s->target;
  return t;
}

// Renumbers every resource id a command names (new resources take ids 1..shift).
Command renumber(Command command, ResourceId shift, const CommandList& from, CommandList& to) {
  auto id = [shift](ResourceId& r) {
    if (r != kNone) r += shift;
  };
  std::visit(
      [&](auto& c) {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, CreateTexture>) id(c.id), id(c.desc.buffer);
        if constexpr (std::is_same_v<T, UploadTexture>) id(c.id), c.data = to.appendBlob(from.bytes(c.data));
        if constexpr (std::is_same_v<T, CreateBuffer> || std::is_same_v<T, CreateSampler> ||
                      std::is_same_v<T, CreateProgram>)
          id(c.id);
        if constexpr (std::is_same_v<T, UploadBuffer>) id(c.id), c.data = to.appendBlob(from.bytes(c.data));
        if constexpr (std::is_same_v<T, SetUniforms>) c.data = to.appendBlob(from.bytes(c.data));
        if constexpr (std::is_same_v<T, BindTexture>) id(c.texture);
        if constexpr (std::is_same_v<T, BindSampler>) id(c.sampler);
        if constexpr (std::is_same_v<T, UseProgram>) id(c.program);
        if constexpr (std::is_same_v<T, BindVertexBuffer> || std::is_same_v<T, BindIndexBuffer>) id(c.buffer);
        if constexpr (std::is_same_v<T, SetRenderTarget>) {
          for (ResourceId& r : c.target.color) id(r);
          id(c.target.depth);
        }
      },
      command);
  return command;
}

}  // namespace

bool needsObjectIdRewrite(const CommandList& list) {
  const std::optional<RenderTarget> presented = presentedTarget(list);
  if (!presented) return false;
  Tracker t;
  t.withBuffers = false;
  for (const Command& c : list.commands()) {
    t.apply(list, c);
    if (std::holds_alternative<Draw>(c) && t.target == *presented && t.programName() != "object_id") return true;
  }
  return false;
}

CommandList rewriteToObjectIds(const CommandList& list, std::string_view frameName, const ResourceLimits& limits) {
  validateOrThrow(list, frameName, limits);
  if (!needsObjectIdRewrite(list)) return list;
  const RenderTarget presented = *presentedTarget(list);
  const std::string where = "visibility: " + std::string(frameName);
  if (presented.layer == kLayered)
    throw Error(where + ": the presented target is layered; the rewrite to object_id does not model layer selection");

  // Pass 1: the vertices of every draw to the presented target, with its draw index as object id.
  struct Rewritten {
    std::vector<uint8_t> vertices;
    uint32_t count = 0;
    std::array<float, 16> mvp{};     // slots 0-3
    std::array<float, 32> planes{};  // slots 8-15: user clip planes, for programs that use them
  };
  std::map<size_t, Rewritten> draws;  // by command index
  Tracker t;
  uint32_t drawIndex = 0;
  for (size_t i = 0; i < list.commands().size(); ++i) {
    const Command& c = list.commands()[i];
    t.apply(list, c);
    const auto* d = std::get_if<Draw>(&c);
    if (!d) continue;
    const uint32_t index = drawIndex++;
    if (!(t.target == presented)) continue;
    const Program* program = findProgram(t.programName());
    if (program && program->hasGeometryStage())
      throw Error(where + ": command " + std::to_string(i) + ": program '" + t.programName() +
                  "' has a geometry stage that moves vertices; the rewrite to object_id keeps the vertex stage only");
    // atlas_sprite: its position is attribute 0 as is (no MVP in slots 0-3) and its fragment depth comes
    // from a texture, so neither the rewrite's geometry nor "the nearest surface" would be the frame's.
    if (program && program->writesDepth())
      throw Error(where + ": command " + std::to_string(i) + ": program '" + t.programName() +
                  "' writes its fragment depth; the rewrite to object_id models interpolated depth only");
    Rewritten r;
    r.count = d->count - d->count % 3;  // a trailing partial triangle draws nothing (GL 4.6 §10.1)
    if (const auto it = t.uniforms.find(t.program); it != t.uniforms.end()) {
      std::copy(it->second.begin(), it->second.begin() + 16, r.mvp.begin());
      // Of the built-in programs only vertex_color writes clip distances (from slots 8-15, with the
      // expression object_id uses); every other one writes 0, so object_id gets zero planes.
      if (t.programName() == "vertex_color") std::copy(it->second.begin() + 32, it->second.end(), r.planes.begin());
    }
    const std::vector<uint8_t>& vb = t.buffers[t.vertexBuffer];
    r.vertices.resize(size_t(r.count) * kIdStride);
    for (uint32_t v = 0; v < r.count; ++v) {
      const uint32_t vertex = d->indexed ? readIndex(t.buffers[t.indexBuffer], t.indexType, uint64_t(d->first) + v)
                                         : d->first + v;
      VertexIn in{};
      fetchVertex(vb, t.layout, vertex, in);
      std::memcpy(&r.vertices[size_t(v) * kIdStride], in.attr[0].data(), 16);
      std::memcpy(&r.vertices[size_t(v) * kIdStride + 16], &index, 4);
    }
    draws[i] = std::move(r);
  }

  // Pass 2: the new resources first (ids 1..shift), then the frame with ids renumbered.
  CommandList out;
  ResourceId sizeFrom = presented.color[0] != kNone ? presented.color[0] : presented.depth;
  const TextureDesc& desc = t.textures[sizeFrom];
  TextureDesc idDesc;
  idDesc.format = Format::R32UI;
  idDesc.width = levelWidth(desc, presented.level);
  idDesc.height = levelHeight(desc, presented.level);
  const ResourceId objectTex = out.createTexture(idDesc);
  const ResourceId primitiveTex = out.createTexture(idDesc);
  TextureDesc depthDesc = idDesc;
  depthDesc.format = Format::D32F;
  const ResourceId depthTex = out.createTexture(depthDesc);
  const ResourceId objectId = out.createProgram("object_id");
  std::map<size_t, ResourceId> buffers;
  for (const auto& [command, r] : draws)
    if (r.count) buffers[command] = out.createBuffer(BufferKind::Vertex, r.vertices);
  const ResourceId shift = out.nextId() - 1;
  out.setNextId(list.nextId() + shift);

  RenderTarget idTarget;
  idTarget.color[0] = objectTex;
  idTarget.color[1] = primitiveTex;
  idTarget.depth = depthTex;
  VertexLayout idLayout;
  idLayout.stride = kIdStride;
  idLayout.attribs[0] = {0, 4, AttribType::F32, 0};
  idLayout.attribs[1] = {2, 1, AttribType::U32, 16};
  auto fresh = [](ResourceId r, ResourceId s) { return r == kNone ? kNone : r + s; };

  Tracker s;  // the original state, to restore after each rewritten draw
  s.withBuffers = false;
  bool targetCleared = false;
  for (size_t i = 0; i < list.commands().size(); ++i) {
    const Command& c = list.commands()[i];
    s.apply(list, c);
    if (const auto* rt = std::get_if<SetRenderTarget>(&c); rt && rt->target == presented) {
      out.setRenderTarget(idTarget);
      if (!targetCleared) {
        targetCleared = true;
        if (s.scissor.enabled) out.setScissor(ScissorState{});
        out.clearColorUint(0, {kBackground, 0, 0, 0});
        out.clearColorUint(1, {kBackground, 0, 0, 0});
        out.clearDepth(1.0f);
        if (s.scissor.enabled) out.setScissor(s.scissor);
      }
      continue;
    }
    const bool onPresented = s.target == presented;
    if (onPresented && std::holds_alternative<ClearColor>(c)) {
      // A colour clear of the presented target clears the id attachments to the background.
      out.clearColorUint(0, {kBackground, 0, 0, 0});
      out.clearColorUint(1, {kBackground, 0, 0, 0});
      continue;
    }
    const auto it = draws.find(i);
    if (it == draws.end()) {
      out.appendRaw(renumber(c, shift, list, out));
      continue;
    }
    const Rewritten& r = it->second;
    if (!r.count) continue;  // draws nothing either way
    out.useProgram(objectId);
    out.setUniforms(0, r.mvp);
    out.setUniforms(8, r.planes);
    out.bindVertexBuffer(buffers[i]);
    out.setVertexLayout(idLayout);
    const bool depthOk = s.depth.test && s.depth.write &&
                         (s.depth.func == CompareFunc::Less || s.depth.func == CompareFunc::LEqual);
    if (!depthOk) out.setDepthState(DepthState{true, true, CompareFunc::Less});
    if (s.blend.enabled) out.setBlendState(BlendState{});
    out.draw(0, r.count);
    if (s.blend.enabled) out.setBlendState(s.blend);
    if (!depthOk) out.setDepthState(s.depth);
    out.useProgram(fresh(s.program, shift));
    out.bindVertexBuffer(fresh(s.vertexBuffer, shift));
    out.setVertexLayout(s.layout);
  }
  return out;
}

}  // namespace tessera::verify
