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
// 2^level / ρ. Per axis (anisotropic): the pixels one texel spans along its own s and t edges (the columns
// of the inverse Jacobian), the larger of the two; 1/ρ looks along the screen axes only and can miss a
// texel stretched along one edge. A magnification violation is a pixel drawn with a node atlas whose level-0 ratio exceeds τ
// while the original texture would have given a finer one (the build never stores more texels than
// the original has, so an original that is itself magnified does not count against the atlas); it is
// counted on the isotropic ratio and on the per-axis one.
// Also: heat maps of either (the colour scale is heatColor), histograms over ratio bins, and totals.
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

constexpr uint8_t kIsotropicViolation = 1, kPerAxisViolation = 2;  // TexelFrame::violation bits

// A texel 2^20 times longer on screen than wide (a million to one) comes only from degenerate texcoords.
inline constexpr double kDegenerateAnisotropy = 1048576.0;

struct TexelFrame {
  uint32_t width = 0, height = 0;
  std::vector<float> ratio;      // at the level sampled; NaN where no texture was sampled
  std::vector<float> ratioBase;  // at level 0
  std::vector<float> axisRatio;  // per axis (the larger of s and t) at the level sampled; NaN as above
  std::vector<uint8_t> source;   // 0 background, 1 atlas, 2 original texture, 3 white (untextured / dummy)
  std::vector<uint8_t> violation;  // kIsotropicViolation | kPerAxisViolation
  uint64_t pixelsAtlas = 0, pixelsOriginal = 0, pixelsWhite = 0;
  uint64_t magnificationViolations = 0;  // isotropic (GL's ρ)
  uint64_t violationsInLeafAtlases = 0;  // of which the atlas was a leaf's (the others: inner nodes)
  uint64_t atlasAboveTau = 0;    // atlas pixels above τ at level 0, violations or not (capped by the original)
  double maxAtlasRatioBase = 0.0;
  uint64_t perAxisViolations = 0, atlasAxisAboveTau = 0;  // the same on the per-axis ratio
  // Over atlas pixels whose original texcoords are not degenerate (below): a triangle with collinear
  // texcoords stretches its texels into lines, and its per-axis ratio is infinite in the original and
  // whatever rounding leaves of it in the atlas (railway.glb has 237 such triangles; 1.1e13 was seen).
  double maxAtlasAxisBase = 0.0;
  // Atlas pixels whose original mapping is anisotropic beyond kDegenerateAnisotropy (per-axis pixels over
  // 1/ρ): the texcoords are collinear or nearly. Their violations are still judged (against an infinite or
  // huge original, so rarely), they only stay out of maxAtlasAxisBase.
  uint64_t atlasPixelsDegenerateTexcoords = 0;
  std::array<uint64_t, kRatioBins> histogram{};      // textured pixels (atlas + original) by ratio bin
  std::array<uint64_t, kRatioBins> axisHistogram{};  // the same by per-axis ratio bin
};

TexelFrame analyzeTexels(const TreeRenderer& renderer, const Camera& camera, const FrameResult& frame,
                         const std::vector<uint32_t>& triangleIds, double tau);

// The heat maps' colour of a ratio (pixels per texel at the level sampled), on a logarithmic scale: dark
// blue (1/4 and below) .. green (1) for minification, green .. yellow (τ), orange .. dark red (4τ and
// above) beyond τ. Special pixels have the colours below.
std::array<uint8_t, 4> heatColor(double ratio, double tau);
// The same colour from log2(ratio) and log2(τ) (the colour bar samples the scale evenly in log2).
std::array<uint8_t, 4> heatColorLog2(double log2Ratio, double log2Tau);
// log2 to 16 fractional bits without libm (raster/sample.h log2Fixed): -64 for v <= 0, 64 for +inf.
double log2Exact(double v);
constexpr std::array<uint8_t, 4> kHeatBackground{90, 90, 90, 255}, kHeatWhiteTexture{45, 45, 45, 255},
    kHeatViolation{255, 0, 255, 255};

// RGBA8 rows top first: heatColor of each textured pixel's ratio (isotropic, or per axis), magenta for
// that measure's violations, kHeatBackground / kHeatWhiteTexture elsewhere. No colour bar (the CLI adds it).
std::vector<uint8_t> heatMap(const TexelFrame& t, double tau, bool perAxis = false);

nlohmann::json toJson(const TexelFrame& t);

}  // namespace tessera::mta
