// Per-pixel provenance: for each pixel of a rendered target, the interval of values that the GL
// spec allows, and the classes of freedom that widen it. The GL cross-check accepts a GL pixel iff it
// lies in its interval. A pixel with no class has an interval of exactly one value, so it must match
// bit for bit.
//
// Implements: the ambiguity classes, the interval storage attached to a rendered texture, and the
// thread-local state through which the sampler reports interval bounds to programs run in
// provenance mode. Program outputs are bounded by running the fragment program three times, with
// the sampler returning the per-channel lower bound, the upper bound, and the oracle value. This is
// valid because every built-in program is monotone (non-decreasing) in each sampled channel.
// Does not implement: the tolerances (raster/tolerances.h, each derived in docs/crosscheck.md;
// rast_provenance.cpp, rast.cpp and sample_interval.cpp apply them) or the comparison (verify/).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

namespace tessera {

struct TextureData;

enum AmbiguityClass : uint16_t {
  kEdgeTie = 1u << 0,          // the centre lies within the snapping tolerance of an edge
  kClipEdge = 1u << 1,         // near an edge made by clipping (GL may clip in float)
  kLodNearSwitch = 1u << 2,    // the LOD range over legal rho/log2/derivative choices changes the value
  kSubtexelNearHalf = 1u << 3, // the texel-coordinate tolerance changes the texels or weights used
  kLayerTie = 1u << 4,         // r + 1/2 is within tolerance of an integer
  kDepthNearEqual = 1u << 5,   // the depth test is within the depth tolerance of flipping
  kOobFetch = 1u << 6,         // an out-of-range buffer fetch: the value is undefined in GL
  kHelperDeriv = 1u << 7,      // coarse and fine derivatives give different LODs
  kFilterPrecision = 1u << 8,  // unorm filtering precision (+-1 LSB on filtered lookups)
  kBlendPrecision = 1u << 9,   // unorm blending precision (+-1 LSB per blended write)
  kOutputRounding = 1u << 10,  // the unrounded output is within interpolation tolerance of a rounding step
  kClassCount = 11
};
std::string_view ambiguityClassName(int bit);

// The interval images of one rendered texture: same format and shape as the texture.
struct Provenance {
  std::unique_ptr<TextureData> lo, hi;
  std::vector<std::vector<uint16_t>> classes;  // per level: layers * w * h, bottom row first
  explicit Provenance(const TextureData& tex);
  uint16_t& cls(const TextureData& tex, uint32_t level, uint32_t layer, uint32_t x, uint32_t y);
};

// What the sampler should return while a program runs in provenance mode.
enum class SampleBound : uint8_t { Value = 0, Lo = 1, Hi = 2 };

struct ShadeProvenance {
  bool active = false;
  SampleBound bound = SampleBound::Value;
  std::array<uint16_t, 4> classes{};  // per quad pixel, ORed in by the sampler
  std::array<bool, 4> dontCare{};     // per quad pixel: an undefined value was used
  void resetPixels() {
    classes = {};
    dontCare = {};
  }
};
// Thread-local: each rasterizer thread shades its own quads.
ShadeProvenance& shadeProvenance();

}  // namespace tessera
