#include "raster/counters.h"

#include <cstring>
#include <unordered_map>

namespace tessera {
namespace {

// Bit-identical comparison: floats by bit pattern, so -0 vs +0 is a change and setting the same
// NaN again is redundant (operator== would say the opposite for both).
bool sameBits(const BlendState& a, const BlendState& b) {
  return a.enabled == b.enabled && a.eqRgb == b.eqRgb && a.eqAlpha == b.eqAlpha && a.srcRgb == b.srcRgb &&
         a.dstRgb == b.dstRgb && a.srcAlpha == b.srcAlpha && a.dstAlpha == b.dstAlpha &&
         std::memcmp(a.constant.data(), b.constant.data(), sizeof a.constant) == 0;
}

struct Tally {
  uint64_t* changes;
  uint64_t* redundant;
  // Records one bind / set of `held` to `value`; returns whether it was redundant.
  template <class T, class Same>
  bool set(T& held, const T& value, Same same) {
    const bool r = same(held, value);
    ++*(r ? redundant : changes);
    if (!r) held = value;
    return r;
  }
  template <class T>
  bool set(T& held, const T& value) {
    return set(held, value, [](const T& a, const T& b) { return a == b; });
  }
};

class Counter {
 public:
  explicit Counter(const CommandList& list) : list_(list) {}

  FrameCounters run() {
    for (const Command& cmd : list_.commands()) {
      if (!std::holds_alternative<Marker>(cmd)) ++c_.commands;  // markers are counted nowhere
      std::visit([this](const auto& c) { count(c); }, cmd);
    }
    c_.bytes_uploaded = c_.texture_bytes_uploaded + c_.buffer_bytes_uploaded;
    c_.state_changes = c_.texture_state_changes + c_.sampler_state_changes + c_.program_changes +
                       c_.vertex_buffer_changes + c_.index_buffer_changes +
                       (c_.uniform_updates - c_.redundant_uniform_updates) + c_.render_target_changes +
                       c_.vertex_layout_changes + c_.viewport_changes + c_.scissor_changes + c_.depth_state_changes +
                       c_.blend_state_changes + c_.raster_state_changes;
    c_.redundant_state_changes = c_.redundant_texture_binds + c_.redundant_sampler_binds + c_.redundant_program_binds +
                                 c_.redundant_vertex_buffer_binds + c_.redundant_index_buffer_binds +
                                 c_.redundant_uniform_updates + c_.redundant_render_target_binds +
                                 c_.redundant_vertex_layout_sets + c_.redundant_viewport_sets +
                                 c_.redundant_scissor_sets + c_.redundant_depth_state_sets +
                                 c_.redundant_blend_state_sets + c_.redundant_raster_state_sets;
    return c_;
  }

 private:
  struct UnitState {
    ResourceId texture = kNone, sampler = kNone;
  };
  using Uniforms = std::array<uint8_t, size_t(kMaxUniformSlots) * 16>;

  void count(const Marker&) {}

  void count(const CreateTexture&) { ++c_.textures_created; }
  void count(const CreateBuffer&) { ++c_.buffers_created; }
  void count(const CreateSampler&) { ++c_.samplers_created; }
  void count(const CreateProgram&) { ++c_.programs_created; }
  void count(const UploadTexture& u) { c_.texture_bytes_uploaded += u.data.size; }
  void count(const UploadBuffer& u) { c_.buffer_bytes_uploaded += u.data.size; }

  void count(const BindTexture& b) {
    ++c_.texture_binds;
    const bool redundant =
        Tally{&c_.texture_state_changes, &c_.redundant_texture_binds}.set(units_[b.unit].texture, b.texture);
    if (b.unit < uint32_t(kMaxTextureUnits)) {
      UnitCounters& u = c_.units[b.unit];
      ++u.texture_binds;
      ++(redundant ? u.redundant_texture_binds : u.texture_state_changes);
    }
  }
  void count(const BindSampler& b) {
    ++c_.sampler_binds;
    const bool redundant =
        Tally{&c_.sampler_state_changes, &c_.redundant_sampler_binds}.set(units_[b.unit].sampler, b.sampler);
    if (b.unit < uint32_t(kMaxTextureUnits)) {
      UnitCounters& u = c_.units[b.unit];
      ++u.sampler_binds;
      ++(redundant ? u.redundant_sampler_binds : u.sampler_state_changes);
    }
  }
  void count(const UseProgram& p) {
    ++c_.program_binds;
    Tally{&c_.program_changes, &c_.redundant_program_binds}.set(program_, p.program);
  }
  void count(const BindVertexBuffer& b) {
    ++c_.vertex_buffer_binds;
    Tally{&c_.vertex_buffer_changes, &c_.redundant_vertex_buffer_binds}.set(vertexBuffer_, b.buffer);
  }
  void count(const BindIndexBuffer& b) {
    ++c_.index_buffer_binds;
    // The binding is the pair (buffer, type): re-binding the same buffer with another type changes it.
    Tally{&c_.index_buffer_changes, &c_.redundant_index_buffer_binds}.set(indexBuffer_, std::pair(b.buffer, b.type));
  }

  void count(const SetUniforms& s) {
    ++c_.uniform_updates;
    // Uniforms are per-program state (GL: glUniform writes the current program), initially zero.
    auto [it, inserted] = uniforms_.try_emplace(program_);
    if (inserted) it->second.fill(0);
    Uniforms& held = it->second;
    const uint64_t begin = uint64_t(s.slot) * 16, bytes = uint64_t(s.count) * 16;
    const uint64_t blobSize = list_.blob().size();
    // An update that does not fit (invalid list) is counted as a change and stores nothing.
    if (begin + bytes > held.size() || s.data.size != bytes || s.data.offset > blobSize ||
        s.data.size > blobSize - s.data.offset) {
      return;
    }
    const auto src = list_.bytes(s.data);
    if (std::memcmp(held.data() + begin, src.data(), src.size()) == 0) {
      ++c_.redundant_uniform_updates;
    } else {
      std::memcpy(held.data() + begin, src.data(), src.size());
    }
  }

  void count(const SetRenderTarget& s) {
    Tally{&c_.render_target_changes, &c_.redundant_render_target_binds}.set(target_, s.target);
  }
  void count(const SetVertexLayout& s) {
    Tally{&c_.vertex_layout_changes, &c_.redundant_vertex_layout_sets}.set(layout_, s.layout);
  }
  void count(const SetViewport& s) { Tally{&c_.viewport_changes, &c_.redundant_viewport_sets}.set(viewport_, s.rect); }
  void count(const SetScissor& s) { Tally{&c_.scissor_changes, &c_.redundant_scissor_sets}.set(scissor_, s.state); }
  void count(const SetDepthState& s) {
    Tally{&c_.depth_state_changes, &c_.redundant_depth_state_sets}.set(depth_, s.state);
  }
  void count(const SetBlendState& s) {
    Tally{&c_.blend_state_changes, &c_.redundant_blend_state_sets}.set(blend_, s.state, sameBits);
  }
  void count(const SetRasterState& s) {
    Tally{&c_.raster_state_changes, &c_.redundant_raster_state_sets}.set(raster_, s.state);
  }

  void count(const ClearColor&) { ++c_.clears; }
  void count(const ClearDepth&) { ++c_.clears; }
  void count(const Draw& d) {
    ++c_.draw_calls;
    if (d.indexed) ++c_.indexed_draw_calls;
    c_.vertices_submitted += d.count;
    c_.primitives_submitted += d.count / 3;
  }

  const CommandList& list_;
  FrameCounters c_;
  std::unordered_map<uint32_t, UnitState> units_;  // a map, so out-of-range units of invalid lists are exact too
  std::unordered_map<ResourceId, Uniforms> uniforms_;
  ResourceId program_ = kNone, vertexBuffer_ = kNone;
  std::pair<ResourceId, IndexType> indexBuffer_{kNone, IndexType::U16};
  RenderTarget target_{};
  VertexLayout layout_{};
  Rect viewport_{};
  ScissorState scissor_{};
  DepthState depth_{};
  BlendState blend_{};
  RasterState raster_{};
};

// Every FrameCounters member except `units`, once: the JSON keys come from this list. The
// static_assert below fails when a member is added to the struct but not here.
// clang-format off
#define TESSERA_FRAME_COUNTERS(X)                                                                              \
  X(commands) X(draw_calls) X(indexed_draw_calls) X(vertices_submitted) X(primitives_submitted)               \
  X(texture_binds) X(texture_state_changes) X(redundant_texture_binds) X(sampler_binds)                       \
  X(sampler_state_changes) X(redundant_sampler_binds) X(program_binds) X(program_changes)                     \
  X(redundant_program_binds) X(vertex_buffer_binds) X(vertex_buffer_changes) X(redundant_vertex_buffer_binds) \
  X(index_buffer_binds) X(index_buffer_changes) X(redundant_index_buffer_binds) X(uniform_updates)            \
  X(redundant_uniform_updates) X(render_target_changes) X(redundant_render_target_binds)                      \
  X(vertex_layout_changes) X(redundant_vertex_layout_sets) X(viewport_changes) X(redundant_viewport_sets)     \
  X(scissor_changes) X(redundant_scissor_sets) X(depth_state_changes) X(redundant_depth_state_sets)           \
  X(blend_state_changes) X(redundant_blend_state_sets) X(raster_state_changes) X(redundant_raster_state_sets)  \
  X(state_changes) X(redundant_state_changes) X(clears) X(textures_created) X(buffers_created)                \
  X(samplers_created) X(programs_created) X(bytes_uploaded) X(texture_bytes_uploaded) X(buffer_bytes_uploaded)
// clang-format on

#define TESSERA_PLUS_ONE(name) +1
static_assert(sizeof(FrameCounters) ==
                  sizeof(uint64_t) * (0 TESSERA_FRAME_COUNTERS(TESSERA_PLUS_ONE)) + sizeof(FrameCounters::units),
              "every FrameCounters member must be listed in TESSERA_FRAME_COUNTERS");
static_assert(sizeof(UnitCounters) == 6 * sizeof(uint64_t), "toJson lists six unit counters");

}  // namespace

FrameCounters countCommands(const CommandList& list) { return Counter(list).run(); }

nlohmann::json toJson(const FrameCounters& c) {
  nlohmann::json j = nlohmann::json::object();
#define TESSERA_TO_JSON(name) j[#name] = c.name;
  TESSERA_FRAME_COUNTERS(TESSERA_TO_JSON)
#undef TESSERA_TO_JSON
  nlohmann::json units = nlohmann::json::array();
  for (int i = 0; i < kMaxTextureUnits; ++i) {
    const UnitCounters& u = c.units[i];
    if (u.texture_binds == 0 && u.sampler_binds == 0) continue;  // never bound
    units.push_back({{"unit", i},
                     {"texture_binds", u.texture_binds},
                     {"texture_state_changes", u.texture_state_changes},
                     {"redundant_texture_binds", u.redundant_texture_binds},
                     {"sampler_binds", u.sampler_binds},
                     {"sampler_state_changes", u.sampler_state_changes},
                     {"redundant_sampler_binds", u.redundant_sampler_binds}});
  }
  j["units"] = std::move(units);
  return j;
}

#undef TESSERA_PLUS_ONE
#undef TESSERA_FRAME_COUNTERS

}  // namespace tessera
