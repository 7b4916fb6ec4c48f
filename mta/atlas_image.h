// Atlas texels (thesis §4.5.2 "Texture Atlas Generation", §4.5.1 inner atlases).
//
// Implements: filling a leaf atlas area from an original image through an affine map from atlas texel
// centres to texture coordinates: the image's mip chain (raster/texture.h generateMipChain box filter)
// at the largest level L with 2^L <= footprint, then bilinear filtering with 8-bit weights (RNE of
// α·256) in exact integer arithmetic, rounded half to even once; the texture's wrap mode is honoured.
// And the inner-node rule: each child atlas downsampled 2x by 2x2 averages, unorm8 rounded half to
// even (the box filter's rules, spec choice T13), into its quadrant. And what an atlas holds where no
// area is filled, per layer (blankAtlas).
// Does not implement: layout (tree_build.h), I/O (paging_file.h).
#pragma once

#include <cstdint>
#include <vector>

#include "base/rgba_image.h"
#include "model/model.h"

namespace tessera::mta {

// An image and its mip chain, RGBA8, rows in stored order (top first; the box filter is symmetric).
struct MipImage {
  uint32_t width = 0, height = 0;
  std::vector<std::vector<uint8_t>> levels;
  uint64_t bytes() const;
};
MipImage makeMipImage(const RgbaImage& img);

// (u, v) of atlas texel centre (x + ½, y + ½): u = u0 + ux·(x + ½) + uy·(y + ½), same for v.
struct AffineMap {
  double u0 = 0, ux = 0, uy = 0, v0 = 0, vx = 0, vy = 0;
};

// Fills texels [x0, x0 + w) x [y0, y0 + h) of an A x A atlas with `channels` (3 or 4) bytes per texel.
void fillArea(uint8_t* atlas, uint32_t A, uint32_t channels, uint32_t x0, uint32_t y0, uint32_t w, uint32_t h,
              const AffineMap& map, const MipImage& img, model::Wrap wrapS, model::Wrap wrapT);

// An A x A atlas with `channels` bytes per texel before any area is filled: 0 for layer 0, 255 for layers
// >= 1. A layer >= 1 is multiplied into layer 0 (§5.1.3, program "textured_layers": a light map or an
// occlusion map), so white is its neutral value: the area of a mesh that has no texture of that layer
// stays blank and must leave the base colour unchanged (factor 1), and so must an inner atlas's empty
// quadrant where trilinear filtering reaches into it.
std::vector<uint8_t> blankAtlas(uint32_t A, uint32_t channels, uint32_t layer);

// Downsamples an A x A child atlas 2x into quadrant q of the parent atlas.
void downsampleIntoQuadrant(const uint8_t* child, uint8_t* parent, uint32_t A, uint32_t channels, int q);

}  // namespace tessera::mta
