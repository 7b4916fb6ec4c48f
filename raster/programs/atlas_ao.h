// The texel neighbourhoods of atlas_sprite_ao (ambient occlusion and edges on an atlas region), shared
// by the program and the RTTA recorder, which checks that the border covers them.
// Does not implement: the program (atlas_sprite_ao.cpp) or its twin (atlas_sprite_ao.glsl spells the
// same offsets in the same order).
#pragma once

#include <array>
#include <cstdint>

namespace tessera::programs {

struct AoOffset {
  int32_t dx, dy;
};

// The occlusion kernel: 4 opposite pairs (o, -o) at Chebyshev distance 2 on the axes and diagonals;
// the pair's second difference z(o) + z(-o) - 2 z is 0 on a plane (window depth is affine in window
// coordinates across a planar primitive, GL 4.6 §14.6.1), negative in a concave crease. Its radius is
// the border an atlas region needs so that the kernel never reads another object's texels.
inline constexpr std::array<AoOffset, 4> kAoPairs{{{2, 0}, {0, 2}, {2, 2}, {2, -2}}};
inline constexpr int32_t kAoRadius = 2;
// The edge filter: the 4-neighbours.
inline constexpr std::array<AoOffset, 4> kEdgeNeighbours{{{-1, 0}, {1, 0}, {0, -1}, {0, 1}}};

}  // namespace tessera::programs
