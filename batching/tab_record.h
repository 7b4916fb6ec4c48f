// Recording a frame of a batched scene as a CommandList, in two variants over the same vertex buffer,
// the same triangles and the same drawing order, so that their images and counters can be compared:
// - batched ("w TAB", Algorithm 2 of Trapp & Döllner 2015, §4.1): per output batch, bind every texture
//   array on units 1.. (one texture state change each, with the sampler of its wrap modes), bind the TAM
//   (an RGBA32F buffer texture, two texels per entry: texarray_batch's material layout) on unit 0, use
//   texarray_batch, and draw each geometry batch (one draw call each);
// - baseline ("w/o TAB"): each batched mesh drawn with `textured`, its texture on unit 0; the texture,
//   sampler, tint (base-colour factor) and alpha-test uniforms are set only when they change, as a
//   renderer tracking its state would.
// Both variants first draw every untextured mesh in one vertex_color draw (colour = the mesh's base
// colour factor) and last draw the BLEND meshes with `textured`, back to front (distance from the eye
// to the centre of the mesh's bounding box, in double; ties in mesh order), with blending
// (SRC_ALPHA, ONE_MINUS_SRC_ALPHA; alpha ONE, ONE_MINUS_SRC_ALPHA) and depth writes off.
// Resources (targets, buffers, textures with their full mip chains, samplers, programs) are created and
// uploaded before the first draw. Filtering is trilinear (LINEAR_MIPMAP_LINEAR, mag LINEAR).
// Does not implement: choosing cameras (the CLI uses mta/camera_path.h), executing (raster/cpu_backend.h).
#pragma once

#include <array>
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "batching/tab_scene.h"
#include "raster/command_list.h"

namespace tessera::batching {

enum class Variant : uint8_t { Baseline = 0, Batched = 1 };
const char* variantName(Variant v);

struct TabView {
  glm::mat4 mvp{1.0f};    // the float view-projection the rasterizer uses
  glm::dvec3 eye{0.0};    // for sorting BLEND meshes
  uint32_t width = 640, height = 480;
  std::array<float, 4> clear{0.62f, 0.74f, 0.88f, 1.0f};
};

// What the frame draws, by kind (the CommandList's counters give the totals).
struct TabDraws {
  uint64_t textured = 0;    // batched: geometry batches; baseline: batched meshes
  uint64_t untextured = 0;  // 0 or 1
  uint64_t blend = 0;       // BLEND meshes
};

CommandList recordTabFrame(const TabScene& scene, Variant variant, const TabView& view, TabDraws* draws = nullptr);
// The same, recorded into `out` (cleared first, its storage kept): a path renders every frame into
// the same lists, so the uploads of the texture arrays cost one copy and no fresh pages per frame.
void recordTabFrame(const TabScene& scene, Variant variant, const TabView& view, CommandList& out, TabDraws* draws = nullptr);

}  // namespace tessera::batching
