// The workloads of `tessera bench sweep` (docs/bench.md): frames built with parameters so that one
// cost grows while the rest stays put.
//
// Implements: fill_layers (fill-bound: full-screen textured layers with overdraw, at any size, in the
// variants of FillVariant) and tiny_tris (setup-bound: any number of triangles of about 1 pixel each on
// a fixed-size target). Both are ordinary CommandLists built with builder.h, so every backend runs them.
// Does not implement: registration in scenes::all() (these frames are benchmark inputs, not rules of the
// oracle made visible: they have no goldens and no cross-check), timing (tools/cli/bench_sweep_*.cpp).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "raster/command_list.h"

namespace tessera::scenes {

// fill_layers: kFillLayers full-screen quads, each covering every pixel once, drawn back to front.
//   trilinear:       program "textured", a 256x256 RGBA8 texture with its full mip chain, sampled
//                    LINEAR_MIPMAP_LINEAR with REPEAT; the texture coordinates are scaled with the target
//                    so that a pixel covers 1.5 texels at every size (LOD about 0.58: both levels blend);
//   flat_color:      program "flat_color", no texture;
//   trilinear_depth: trilinear with a D32F target, depth test LESS and depth writes (layers nearer one
//                    after the other, so every fragment passes and writes);
//   trilinear_blend: trilinear with blending SRC_ALPHA, ONE_MINUS_SRC_ALPHA (tint alpha 0.5).
constexpr int kFillLayers = 4;
inline const std::vector<std::string>& fillVariants() {
  static const std::vector<std::string> v = {"trilinear", "flat_color", "trilinear_depth", "trilinear_blend"};
  return v;
}
// Throws Error naming the variant when it is not one of fillVariants().
CommandList buildFillLayers(int w, int h, std::string_view variant);

// tiny_tris: `triangles` right triangles with legs of sqrt(2) px (area 1 px) at pseudo-random sub-pixel
// positions, one per cell of a grid spread over the w x h target, program "flat_color", no depth, one
// draw (indexed, 3 vertices each).
CommandList buildTinyTris(int w, int h, int triangles);

}  // namespace tessera::scenes
