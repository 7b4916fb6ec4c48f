// Texel-per-pixel analysis of an atlas tree frame: for every pixel, how many pixels one texel of the
// texture level actually sampled covers, computed from the analytic texture-coordinate Jacobian.
//
// Implements: per pixel, from the frame's triangle-id image (TreeRenderer::triangleIds), the
// perspective-correct texcoord derivatives of the covering triangle at the pixel centre, in double,
// from the same float MVP the frame was drawn with (2D homogeneous rasterization: u(p) = a·p / c·p with
// a = M⁻ᵀu, c = M⁻ᵀ1, so clipped triangles need no special case); GL's scale factor
// ρ = max(|∂(s,t)/∂x|, |∂(s,t)/∂y|) in texels of level 0 (GL 4.6 §8.14.1, eq. 8.7, with exact rather than
// implementation-approximated derivatives); the level sampled, floor(log2 ρ) clamped to the chain (the
// finer of the two levels trilinear filtering blends; level 0 when magnifying), and the ratio
// 2^level / ρ. A magnification violation is a pixel drawn with a node atlas whose level-0 ratio exceeds τ
// while the original texture would have given a finer one (the build never stores more texels than
// the original has, so an original that is itself magnified does not count against the atlas).
// Also: a heat map, a histogram over ratio bins, and totals.
// Does not implement: rendering (tree_renderer.h).
#pragma once

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "mta/tree_renderer.h"

namespace tessera::mta {

// Ratio bins: edges 2^(k/2) for k = -4 .. 6 (0.25 .. 8); bin 0 below 0.25, the last at or above 8.
constexpr int kRatioBins = 12;
double ratioBinLower(int bin);  // 0 for bin 0

struct TexelFrame {
  uint32_t width = 0, height = 0;
  std::vector<float> ratio;      // at the level sampled; NaN where no texture was sampled
  std::vector<float> ratioBase;  // at level 0
  std::vector<uint8_t> source;   // 0 background, 1 atlas, 2 original texture, 3 white (untextured / dummy)
  std::vector<uint8_t> violation;
  uint64_t pixelsAtlas = 0, pixelsOriginal = 0, pixelsWhite = 0;
  uint64_t magnificationViolations = 0;
  uint64_t violationsInLeafAtlases = 0;  // of which the atlas was a leaf's (the others: inner nodes)
  uint64_t atlasAboveTau = 0;    // atlas pixels above τ at level 0, violations or not (capped by the original)
  double maxAtlasRatioBase = 0.0;
  std::array<uint64_t, kRatioBins> histogram{};  // textured pixels (atlas + original) by ratio bin
};

TexelFrame analyzeTexels(const TreeRenderer& renderer, const Camera& camera, const FrameResult& frame,
                         const std::vector<uint32_t>& triangleIds, double tau);

// RGBA8 rows top first: grey background, dark grey for white-texture pixels, blue..green for ratios
// up to 1, yellow up to τ, red above τ, magenta for violations.
std::vector<uint8_t> heatMap(const TexelFrame& t, double tau);

nlohmann::json toJson(const TexelFrame& t);

}  // namespace tessera::mta
