// API-level counters of a frame, computed exactly from its CommandList (docs/counters.md defines
// every counter). They describe what a technique asks of the API — binds, state changes and their
// redundancy, draws, uploads — independently of any backend, so two techniques can be compared on
// the work they submit.
//
// Common principles
// - The state before the first command is GL's initial state as modelled by types.h: every unit
//   holds texture 0 and sampler 0, program 0, no buffers, default-constructed viewport, scissor,
//   depth, blend, raster state, vertex layout and render target, uniforms all zero. Setting that
//   value again is redundant.
// - A command is *redundant* iff the state it sets is bit-identical to the state already held; a
//   non-redundant one is a *change*. Every bind / set command is exactly one of the two.
// - Markers are counted nowhere.
// Does not implement: backend counters (pixels shaded, tiles, ...).
#pragma once

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>

#include "raster/command_list.h"

namespace tessera {

struct UnitCounters {
  uint64_t texture_binds = 0, texture_state_changes = 0, redundant_texture_binds = 0;
  uint64_t sampler_binds = 0, sampler_state_changes = 0, redundant_sampler_binds = 0;
  bool operator==(const UnitCounters&) const = default;
};

struct FrameCounters {
  uint64_t commands = 0;  // every command except Marker

  uint64_t draw_calls = 0, indexed_draw_calls = 0;
  uint64_t vertices_submitted = 0;    // sum of Draw::count
  uint64_t primitives_submitted = 0;  // sum of Draw::count / 3 (partial triangles dropped)

  uint64_t texture_binds = 0, texture_state_changes = 0, redundant_texture_binds = 0;
  uint64_t sampler_binds = 0, sampler_state_changes = 0, redundant_sampler_binds = 0;
  uint64_t program_binds = 0, program_changes = 0, redundant_program_binds = 0;
  uint64_t vertex_buffer_binds = 0, vertex_buffer_changes = 0, redundant_vertex_buffer_binds = 0;
  uint64_t index_buffer_binds = 0, index_buffer_changes = 0, redundant_index_buffer_binds = 0;
  uint64_t uniform_updates = 0, redundant_uniform_updates = 0;  // SetUniforms commands
  uint64_t render_target_changes = 0, redundant_render_target_binds = 0;
  uint64_t vertex_layout_changes = 0, redundant_vertex_layout_sets = 0;
  uint64_t viewport_changes = 0, redundant_viewport_sets = 0;
  uint64_t scissor_changes = 0, redundant_scissor_sets = 0;
  uint64_t depth_state_changes = 0, redundant_depth_state_sets = 0;
  uint64_t blend_state_changes = 0, redundant_blend_state_sets = 0;
  uint64_t raster_state_changes = 0, redundant_raster_state_sets = 0;
  uint64_t state_changes = 0;            // all non-redundant binds / sets / uniform updates above
  uint64_t redundant_state_changes = 0;  // all redundant ones

  uint64_t clears = 0;  // ClearColor + ClearDepth
  uint64_t textures_created = 0, buffers_created = 0, samplers_created = 0, programs_created = 0;
  uint64_t bytes_uploaded = 0;  // texture_bytes_uploaded + buffer_bytes_uploaded
  uint64_t texture_bytes_uploaded = 0, buffer_bytes_uploaded = 0;

  // Binds to units >= kMaxTextureUnits (an invalid list) count in the totals only.
  std::array<UnitCounters, kMaxTextureUnits> units{};

  bool operator==(const FrameCounters&) const = default;
};

FrameCounters countCommands(const CommandList& list);

// Keys are the member names. "units" lists only units with at least one texture or sampler bind,
// in unit order, each object carrying "unit": n.
nlohmann::json toJson(const FrameCounters& c);

}  // namespace tessera
