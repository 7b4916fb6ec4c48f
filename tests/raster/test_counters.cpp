// countCommands(): small lists counted by hand, redundancy against GL's initial state, and the JSON
// shape.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "raster/counters.h"

namespace tessera {
namespace {

TEST(Counters, AnEmptyListCountsNothing) {
  const FrameCounters c = countCommands(CommandList{});
  EXPECT_EQ(c, FrameCounters{});
  const auto j = toJson(c);
  EXPECT_EQ(j.at("commands"), 0);
  EXPECT_TRUE(j.at("units").is_array());
  EXPECT_TRUE(j.at("units").empty());
}

TEST(Counters, TextureBindsAreCountedPerUnitWithRedundancy) {
  CommandList l;
  const ResourceId a = l.createTexture({TextureKind::Tex2D, Format::RGBA8, 1, 1, 1, 1});
  const ResourceId b = l.createTexture({TextureKind::Tex2D, Format::RGBA8, 1, 1, 1, 1});
  l.bindTexture(0, a);      // change
  l.bindTexture(0, a);      // redundant
  l.bindTexture(1, a);      // change: unit 1 held 0
  l.bindTexture(0, b);      // change
  l.bindTexture(0, kNone);  // change
  l.bindTexture(2, kNone);  // redundant: units start with 0
  l.bindTexture(1, a);      // redundant
  const FrameCounters c = countCommands(l);
  EXPECT_EQ(c.texture_binds, 7u);
  EXPECT_EQ(c.texture_state_changes, 4u);
  EXPECT_EQ(c.redundant_texture_binds, 3u);
  EXPECT_EQ(c.units[0], (UnitCounters{4, 3, 1, 0, 0, 0}));
  EXPECT_EQ(c.units[1], (UnitCounters{2, 1, 1, 0, 0, 0}));
  EXPECT_EQ(c.units[2], (UnitCounters{1, 0, 1, 0, 0, 0}));
  EXPECT_EQ(c.units[3], UnitCounters{});
  EXPECT_EQ(c.textures_created, 2u);
  EXPECT_EQ(c.commands, 9u);
  EXPECT_EQ(c.state_changes, 4u);
  EXPECT_EQ(c.redundant_state_changes, 3u);
}

TEST(Counters, SamplerBindsAreCountedPerUnitIndependentlyOfTextures) {
  CommandList l;
  const ResourceId s = l.createSampler({});
  const ResourceId t = l.createSampler({});
  l.bindSampler(5, s);      // change
  l.bindSampler(5, s);      // redundant
  l.bindSampler(5, t);      // change
  l.bindSampler(6, kNone);  // redundant
  l.bindTexture(5, kNone);  // redundant texture bind on the same unit
  const FrameCounters c = countCommands(l);
  EXPECT_EQ(c.sampler_binds, 4u);
  EXPECT_EQ(c.sampler_state_changes, 2u);
  EXPECT_EQ(c.redundant_sampler_binds, 2u);
  EXPECT_EQ(c.units[5], (UnitCounters{1, 0, 1, 3, 2, 1}));
  EXPECT_EQ(c.units[6], (UnitCounters{0, 0, 0, 1, 0, 1}));
  EXPECT_EQ(c.samplers_created, 2u);
  EXPECT_EQ(c.redundant_state_changes, 3u);
}

TEST(Counters, JsonListsOnlyUnitsThatWereBound) {
  CommandList l;
  l.bindSampler(7, kNone);
  l.bindTexture(2, 1);
  const auto j = toJson(countCommands(l));
  ASSERT_EQ(j.at("units").size(), 2u);
  EXPECT_EQ(j["units"][0].at("unit"), 2);
  EXPECT_EQ(j["units"][0].at("texture_binds"), 1);
  EXPECT_EQ(j["units"][0].at("texture_state_changes"), 1);
  EXPECT_EQ(j["units"][1].at("unit"), 7);
  EXPECT_EQ(j["units"][1].at("redundant_sampler_binds"), 1);
  EXPECT_EQ(j["units"][1].size(), 7u);  // "unit" + six counters
}

TEST(Counters, JsonKeysAreTheMemberNames) {
  const auto j = toJson(FrameCounters{});
  for (const char* key : {"commands",
                          "draw_calls",
                          "indexed_draw_calls",
                          "vertices_submitted",
                          "primitives_submitted",
                          "texture_binds",
                          "texture_state_changes",
                          "redundant_texture_binds",
                          "sampler_binds",
                          "sampler_state_changes",
                          "redundant_sampler_binds",
                          "program_binds",
                          "program_changes",
                          "redundant_program_binds",
                          "vertex_buffer_binds",
                          "vertex_buffer_changes",
                          "redundant_vertex_buffer_binds",
                          "index_buffer_binds",
                          "index_buffer_changes",
                          "redundant_index_buffer_binds",
                          "uniform_updates",
                          "redundant_uniform_updates",
                          "render_target_changes",
                          "redundant_render_target_binds",
                          "vertex_layout_changes",
                          "redundant_vertex_layout_sets",
                          "viewport_changes",
                          "redundant_viewport_sets",
                          "scissor_changes",
                          "redundant_scissor_sets",
                          "depth_state_changes",
                          "redundant_depth_state_sets",
                          "blend_state_changes",
                          "redundant_blend_state_sets",
                          "raster_state_changes",
                          "redundant_raster_state_sets",
                          "state_changes",
                          "redundant_state_changes",
                          "clears",
                          "textures_created",
                          "buffers_created",
                          "samplers_created",
                          "programs_created",
                          "bytes_uploaded",
                          "texture_bytes_uploaded",
                          "buffer_bytes_uploaded",
                          "units"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j.size(), 47u);
}

TEST(Counters, ProgramAndBufferBindsCountChangesAndRedundancy) {
  CommandList l;
  const ResourceId p = l.createProgram("a");
  const ResourceId q = l.createProgram("b");
  const ResourceId vb = l.createBuffer(BufferKind::Vertex, 16);
  const ResourceId ib = l.createBuffer(BufferKind::Index, 16);
  l.useProgram(kNone);                       // redundant
  l.useProgram(p);                           // change
  l.useProgram(p);                           // redundant
  l.useProgram(q);                           // change
  l.bindVertexBuffer(vb);                    // change
  l.bindVertexBuffer(vb);                    // redundant
  l.bindIndexBuffer(ib, IndexType::U16);     // change
  l.bindIndexBuffer(ib, IndexType::U16);     // redundant
  l.bindIndexBuffer(ib, IndexType::U32);     // change: the type is part of the binding
  l.bindIndexBuffer(kNone, IndexType::U16);  // change
  const FrameCounters c = countCommands(l);
  EXPECT_EQ(c.program_binds, 4u);
  EXPECT_EQ(c.program_changes, 2u);
  EXPECT_EQ(c.redundant_program_binds, 2u);
  EXPECT_EQ(c.vertex_buffer_binds, 2u);
  EXPECT_EQ(c.vertex_buffer_changes, 1u);
  EXPECT_EQ(c.redundant_vertex_buffer_binds, 1u);
  EXPECT_EQ(c.index_buffer_binds, 4u);
  EXPECT_EQ(c.index_buffer_changes, 3u);
  EXPECT_EQ(c.redundant_index_buffer_binds, 1u);
  EXPECT_EQ(c.programs_created, 2u);
  EXPECT_EQ(c.buffers_created, 2u);
  EXPECT_EQ(c.state_changes, 6u);
  EXPECT_EQ(c.redundant_state_changes, 4u);
}

TEST(Counters, UniformUpdatesAreRedundantWhenTheProgramAlreadyHoldsTheBytes) {
  CommandList l;
  const ResourceId p = l.createProgram("a");
  const ResourceId q = l.createProgram("b");
  l.useProgram(p);
  l.setUniforms(0, std::vector<float>{0, 0, 0, 0});              // redundant: uniforms start at zero
  l.setUniforms(0, std::vector<float>{1, 2, 3, 4});              // change
  l.setUniforms(0, std::vector<float>{1, 2, 3, 4});              // redundant
  l.setUniforms(1, std::vector<float>{1, 2, 3, 4});              // change: another slot
  l.setUniforms(0, std::vector<float>{1, 2, 3, 4, 1, 2, 3, 4});  // redundant: both slots hold it
  l.setUniforms(0, std::vector<float>{-0.0f, 2, 3, 4});          // change: -0 differs from +0 in bits
  l.useProgram(q);
  l.setUniforms(1, std::vector<float>{1, 2, 3, 4});  // change: q has its own storage
  l.useProgram(p);
  l.setUniforms(1, std::vector<float>{1, 2, 3, 4});  // redundant: p kept its values
  const FrameCounters c = countCommands(l);
  EXPECT_EQ(c.uniform_updates, 8u);
  EXPECT_EQ(c.redundant_uniform_updates, 4u);
  EXPECT_EQ(c.program_changes, 3u);
  EXPECT_EQ(c.state_changes, 4u + 3u);
  EXPECT_EQ(c.redundant_state_changes, 4u);
}

TEST(Counters, FixedFunctionStateIsRedundantWhenSetToTheCurrentValue) {
  CommandList l;
  l.setViewport({});                                 // redundant: default Rect
  l.setViewport({0, 0, 64, 64});                     // change
  l.setViewport({0, 0, 64, 64});                     // redundant
  l.setScissor({});                                  // redundant
  l.setScissor({true, {0, 0, 1, 1}});                // change
  l.setDepthState({});                               // redundant
  l.setDepthState({true, true, CompareFunc::Less});  // change
  l.setDepthState({true, true, CompareFunc::Less});  // redundant
  l.setRasterState({});                              // redundant
  l.setRasterState({CullMode::Back, true, 0});       // change
  l.setVertexLayout({});                             // redundant
  VertexLayout v;
  v.stride = 16;
  l.setVertexLayout(v);  // change
  l.setVertexLayout(v);  // redundant
  RenderTarget t;
  l.setRenderTarget(t);  // redundant: the initial target is all kNone
  t.color[0] = 9;
  l.setRenderTarget(t);  // change
  l.setRenderTarget(t);  // redundant
  const FrameCounters c = countCommands(l);
  EXPECT_EQ(c.viewport_changes, 1u);
  EXPECT_EQ(c.redundant_viewport_sets, 2u);
  EXPECT_EQ(c.scissor_changes, 1u);
  EXPECT_EQ(c.redundant_scissor_sets, 1u);
  EXPECT_EQ(c.depth_state_changes, 1u);
  EXPECT_EQ(c.redundant_depth_state_sets, 2u);
  EXPECT_EQ(c.raster_state_changes, 1u);
  EXPECT_EQ(c.redundant_raster_state_sets, 1u);
  EXPECT_EQ(c.vertex_layout_changes, 1u);
  EXPECT_EQ(c.redundant_vertex_layout_sets, 2u);
  EXPECT_EQ(c.render_target_changes, 1u);
  EXPECT_EQ(c.redundant_render_target_binds, 2u);
  EXPECT_EQ(c.state_changes, 6u);
  EXPECT_EQ(c.redundant_state_changes, 10u);
  EXPECT_EQ(c.commands, 16u);
}

TEST(Counters, BlendStateIsComparedBitForBit) {
  CommandList l;
  BlendState b;
  l.setBlendState(b);  // redundant
  b.constant[0] = -0.0f;
  l.setBlendState(b);  // change, although -0 == +0
  b.constant[1] = std::numeric_limits<float>::quiet_NaN();
  l.setBlendState(b);  // change
  l.setBlendState(b);  // redundant, although NaN != NaN
  const FrameCounters c = countCommands(l);
  EXPECT_EQ(c.blend_state_changes, 2u);
  EXPECT_EQ(c.redundant_blend_state_sets, 2u);
}

TEST(Counters, DrawsClearsAndUploadsAreSummed) {
  CommandList l;
  const ResourceId t = l.createTexture({TextureKind::Tex2D, Format::RGBA8, 2, 2, 1, 2});
  l.uploadTexture(t, 0, 0, std::vector<uint8_t>(16));
  l.uploadTexture(t, 1, 0, std::vector<uint8_t>(4));
  const ResourceId b = l.createBuffer(BufferKind::Vertex, std::vector<uint8_t>(100));
  l.uploadBuffer(b, 10, std::vector<uint8_t>(7));
  l.clearColor(0, {0, 0, 0, 0});
  l.clearDepth(1.0f);
  l.draw(0, 7);         // 2 triangles, the partial one dropped
  l.drawIndexed(3, 6);  // 2
  l.drawIndexed(0, 2);  // 0
  l.marker("not counted");
  const FrameCounters c = countCommands(l);
  EXPECT_EQ(c.draw_calls, 3u);
  EXPECT_EQ(c.indexed_draw_calls, 2u);
  EXPECT_EQ(c.vertices_submitted, 15u);
  EXPECT_EQ(c.primitives_submitted, 4u);
  EXPECT_EQ(c.clears, 2u);
  EXPECT_EQ(c.texture_bytes_uploaded, 20u);
  EXPECT_EQ(c.buffer_bytes_uploaded, 107u);
  EXPECT_EQ(c.bytes_uploaded, 127u);
  EXPECT_EQ(c.textures_created, 1u);
  EXPECT_EQ(c.buffers_created, 1u);
  EXPECT_EQ(c.commands, 11u);  // the marker excluded
  EXPECT_EQ(c.state_changes, 0u);
}

TEST(Counters, InvalidCommandsAreCountedWithoutCrashing) {
  CommandList l;
  l.bindTexture(100, 3);  // unit out of range: totals only
  l.bindTexture(100, 3);
  l.appendRaw(SetUniforms{63, 4, BlobRange{0, 64}});  // slots past the end and no blob
  const FrameCounters c = countCommands(l);
  EXPECT_EQ(c.texture_binds, 2u);
  EXPECT_EQ(c.texture_state_changes, 1u);
  EXPECT_EQ(c.redundant_texture_binds, 1u);
  for (const UnitCounters& u : c.units) EXPECT_EQ(u, UnitCounters{});
  EXPECT_EQ(c.uniform_updates, 1u);
  EXPECT_EQ(c.redundant_uniform_updates, 0u);
}

}  // namespace
}  // namespace tessera
