// Texture sampling of the oracle: LOD, mip selection, wrap, filter, arrays, buffer fetch.
//
// Implements GL 4.6 §8.14 (LOD), §8.14.2 (texel selection, Table 8.20 wrap modes), §8.9 (buffer
// textures) and EXT_texture_array's layer rule, with the choices of docs/spec-choices.md:
// - implicit LOD from *coarse* per-quad derivatives: ddx = c[1] - c[0], ddy = c[2] - c[0];
// - exact rho: rho^2 = max(ux^2 + vx^2, uy^2 + vy^2) in double, u = s * width, v = t * height of the
//   base level (for arrays the layer is not part of rho);
// - lambda_base = 0.5 * log2(rho^2) from log2Fixed() (no libm), lambda quantized to 8 fractional bits;
//   rho == 0 gives lambda = kLodMinusInf; NaN/Inf derivatives give lambda = +kLodMax (most minified);
// - lambda' = lambda_base + clamp(bias_sampler + bias_shader, -16, 16), then clamp(minLod, maxLod);
// - magnification iff lambda <= 0 (c = 0);
// - NEAREST_MIPMAP_*: level = lambda <= 1/2 ? 0 : ceil(lambda + 1/2) - 1, clamped to the last level;
// - LINEAR_MIPMAP_*: levels floor(lambda), +1 (clamped), blend weight = the 8 fractional bits of lambda;
// - u = s * size in float32; NEAREST texel floor(u); LINEAR i0 = floor(u - 1/2), alpha = frac(u - 1/2)
//   rounded to 8 bits (round half to even on alpha * 256);
// - unorm8 filtering in exact integer arithmetic; the value is converted to float once;
// - array layer = clamp(floor(r + 1/2), 0, layers - 1) with r + 1/2 in float32;
// - buffer texelFetch outside [0, N) returns (0, 0, 0, 0);
// - an incomplete texture (no texture bound, integer format with a LINEAR filter, mipmap filter on
//   a texture with one level is fine) returns (0, 0, 0, 1) (GL 4.6 §8.17 / §11.1.3.5).
// Does not implement: cube maps, 3D textures, shadow compare, anisotropy, sRGB, texel offsets.
#pragma once

#include <cstdint>

#include "raster/texture.h"
#include "raster/types.h"

namespace tessera {

// LOD values in 8.8 fixed point (lambda * 256).
constexpr int32_t kLodMinusInf = -(1 << 20);
constexpr int32_t kLodMax = 1 << 20;

// A sampler with its LOD parameters quantized once (round half to even to 1/256).
struct SamplerQ {
  SamplerState state;
  int32_t minLod8 = 0, maxLod8 = 0, bias8 = 0;
  static SamplerQ from(const SamplerState& s);
};

// What a program sees on a texture unit.
struct TexUnit {
  const TextureData* tex = nullptr;  // nullptr: no texture bound (incomplete)
  SamplerQ sampler;
};

// floor(256 * log2(x) + 1/2)-accurate fixed-point log2 for x > 0 finite, computed with integer
// arithmetic only (exponent extraction + repeated squaring of the mantissa, 24 fraction bits, then
// rounded half to even to `fracBits` bits). Deterministic on every platform.
int64_t log2Fixed(double x, int fracBits);

// Quantized lambda (8.8) from the four coarse derivative components (already scaled by the
// base-level size), the sampler and a shader bias (float, quantized like the sampler bias).
int32_t computeLambda(double dudx, double dvdx, double dudy, double dvdy, const SamplerQ& s, float shaderBias);

// Filtered lookup at a given lambda for one pixel (2D: layer 0). Writes RGBA as float; R8 → (r,0,0,1),
// RG32F → (r,g,0,1), R32UI → the integer converted to float in .x (use fetchUint for exact values).
void sampleAtLambda(const TexUnit& u, float s, float t, uint32_t layer, int32_t lambda8, float out[4]);

// Quad forms: coordinates of the four pixels of a 2x2 quad (order: (0,0), (1,0), (0,1), (1,1) in
// window space); one lambda per quad from coarse derivatives. out[pixel][channel].
void sampleQuad2D(const TexUnit& u, const float s[4], const float t[4], float bias, float out[4][4]);
void sampleQuad2DArray(const TexUnit& u, const float s[4], const float t[4], const float r[4], float bias,
                       float out[4][4]);
// n quads of one triangle (a program's batch): out[q] = sampleQuad2D(u, s[q], t[q], bias, out[q]), the
// same bytes; consecutive quads whose plans differ at most in the level weights (the same levels, any
// lambda between them) go to the SIMD kernel in one call, with per-quad weights, filling vectors
// wider than one quad.
void sampleQuads2D(const TexUnit& u, size_t n, const float (*s)[4], const float (*t)[4], float bias,
                   float (*out)[4][4]);
// textureGrad on a 2D array with explicit (quad-uniform) derivatives in normalized coordinates.
void sampleGrad2DArray(const TexUnit& u, const float s[4], const float t[4], const float r[4], float dsdx,
                       float dtdx, float dsdy, float dtdy, float out[4][4]);

// texelFetch(tex, ivec3(x, y, layer), 0) per quad pixel (texel_fetch.cpp): level 0, exact; a 2D
// texture has one layer. Outside the level or the layers: (0, 0, 0, 0) (as buffer fetches: the twins
// test against textureSize, spec-choices T11); no texture: (0, 0, 0, 1). Provenance mode reads a
// rendered texture through its interval images in the bound runs (INPUT_INTERVAL).
void fetchQuad2DArray(const TexUnit& u, const int64_t x[4], const int64_t y[4], const int64_t layer[4],
                      float out[4][4]);

// Array layer selection: clamp(floor(r + 0.5f), 0, layers - 1).
uint32_t selectLayer(float r, uint32_t layers);

// texelFetch on a buffer texture (format RGBA32F, RG32F, R8, RGBA8 or R32UI) or level 0 of a 2D texture.
void fetchBuffer(const TexUnit& u, int64_t index, float out[4]);
uint32_t fetchBufferUint(const TexUnit& u, int64_t index);

// Wrap of an integer texel coordinate (GL 4.6 Table 8.20). Returns -1 for a border texel.
int32_t wrapCoord(Wrap w, int64_t i, int32_t size);

namespace detail {
// The calling thread's plan cache: one lambda reused while rho^2, shader bias and unit repeat from quad
// to quad, and one plan while lambda and unit repeat. beginPlanCache opens it with a new epoch, so
// nothing of an earlier triangle is reused; the fast-path rasterizer calls it per triangle of a tile,
// and endPlanCache after the tile (provenance mode never opens it). Speed only: a lookup gives the
// same bits with the cache open or closed (tests/raster/test_plan_cache.cpp).
void beginPlanCache();
void endPlanCache();
// The calling thread's SIMD kernels (raster/sample_simd.h), resolved once for a tile's work instead of
// per triangle (a dispatch calls into libhwy): set before a tile, cleared after it; without them a
// lookup resolves the kernel itself. The target must not change in between (simd::forceTarget).
void bindSampleKernels();
void unbindSampleKernels();
}  // namespace detail

}  // namespace tessera
