// Per-fragment operations after the fragment program, one function per GL stage in pipeline order
// (GL 4.6 §17.3): depth test, depth write, blend, conversion and colour write.
//
// Implements: the eight depth functions on float32 depth; every GL blend equation and factor; the
// fixed-point rules (sources, destination and factors clamped to [0, 1] for unorm targets,
// §17.3.6.1); one round-half-to-even conversion to unorm8 from a double (§2.3.5.2, "round to
// nearest" with ties to even chosen, docs/spec-choices.md); float targets unclamped and rounded to
// float once; integer targets never blended (§17.3.6). Also the source-over blend of an RGBA8 texel
// computed directly (blendSourceOverRgba8, the same bytes as blend()), for the rasterizer's write.
// Does not implement: stencil, logic op, colour masks, sRGB, dithering (GL's default dither is a
// no-op here: §17.3.9 allows it to do nothing).
#pragma once

#include <cstdint>

#include "raster/round.h"
#include "raster/setup.h"
#include "raster/types.h"

namespace tessera::detail {

// The depth test (GL 4.6 §17.3.4). Inline: the early test calls it per pixel of every covered quad.
inline bool depthPasses(CompareFunc f, float incoming, float stored) {
  switch (f) {
    case CompareFunc::Never: return false;
    case CompareFunc::Less: return incoming < stored;
    case CompareFunc::Equal: return incoming == stored;
    case CompareFunc::LEqual: return incoming <= stored;
    case CompareFunc::Greater: return incoming > stored;
    case CompareFunc::NotEqual: return incoming != stored;
    case CompareFunc::GEqual: return incoming >= stored;
    case CompareFunc::Always: return true;
    default: return false;
  }
}

// A program-written fragment depth (gl_FragDepth) as the depth test and write see it: clamped to the
// depth range [0, 1], NaN -> 0 (docs/spec-choices.md F11; GL 4.6 §15.2.3, §17.3.4).
inline float clampFragDepth(float z) { return z > 0.0f ? (z < 1.0f ? z : 1.0f) : 0.0f; }

// NaN-safe unorm8 conversion: clamp to [0, 1] (NaN -> 0), then round half to even of c * 255.
// Inline: it runs per pixel and channel.
inline uint8_t toUnorm8(double c) {
  if (!(c > 0.0)) return 0;  // also NaN
  if (c >= 1.0) return 255;
  return uint8_t(roundHalfEvenNear(c * 255.0));  // 0 < c * 255 < 255: roundHalfEven's value
}

// The unorm8 value i as a double, i / 255.0 (GL 4.6 §2.3.5.1, eq. 2.1), for every byte: a blend reads
// its destination through this table instead of dividing per channel. The division is IEEE, so the
// compile-time quotient is the run-time one (tests/raster/test_blend.cpp checks every entry).
struct Unorm8Doubles {
  double v[256];
  constexpr Unorm8Doubles() : v() {
    for (int i = 0; i < 256; ++i) v[i] = double(i) / 255.0;
  }
};
inline constexpr Unorm8Doubles kUnorm8ToDouble{};

// True when `b` is the "source over" form glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA) with
// GL_FUNC_ADD for colour and alpha, the form blendSourceOverRgba8() computes directly.
inline bool isSourceOver(const BlendState& b) {
  return b.enabled && b.eqRgb == BlendEq::Add && b.eqAlpha == BlendEq::Add && b.srcRgb == BlendFactor::SrcAlpha &&
         b.srcAlpha == BlendFactor::SrcAlpha && b.dstRgb == BlendFactor::OneMinusSrcAlpha &&
         b.dstAlpha == BlendFactor::OneMinusSrcAlpha;
}

// writeFragment() of an RGBA8 texel under a source-over BlendState, with the same IEEE operations in
// the same order, so the same bytes: blend()'s unorm rules reduce to s * a + d * (1 - a) per channel
// with s = clamp01(src), a = clamp01(src alpha) and d = texel / 255. Its clamps of d, of the factors
// a and 1 - a (both in [0, 1] already) and of the sum (toUnorm8 clamps the same way, NaN included) are
// identities, and the factors are the same for every channel. tests/raster/test_blend.cpp compares it
// with blend() + toUnorm8 over every destination byte.
inline void blendSourceOverRgba8(const float src[4], uint8_t* texel) {
  const auto clamp01 = [](double v) { return v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0; };  // NaN -> 0
  const double a = clamp01(src[3]), na = 1.0 - a;
  for (int k = 0; k < 4; ++k) {
    const double s = k == 3 ? a : clamp01(src[k]);
    const double sf = s * a, df = kUnorm8ToDouble.v[texel[k]] * na;
    texel[k] = toUnorm8(sf + df);
  }
}

// Blends `src` (the program's output) with `dst` under `b`; `unorm` selects the fixed-point rules.
// Returns the result in double, before conversion.
void blend(const BlendState& b, bool unorm, const float src[4], const double dst[4], double out[4]);

// Writes one fragment to a texel of the given format (the texel pointer is the first byte).
// `bits` are the program output's raw 32-bit lanes (float bits, or uint for R32UI).
void writeFragment(Format f, uint8_t* texel, const uint32_t bits[4], const BlendState& b);

}  // namespace tessera::detail
