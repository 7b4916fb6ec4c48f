// Per-pixel provenance: for each pixel of a rendered target, the set of whole results that the GL
// spec allows (candidates, each a [lo, hi] box per channel), and the classes of freedom that made
// them. The GL cross-check accepts a GL pixel iff it lies in one candidate's box. A pixel with no
// class has one candidate of exactly one value, so it must match bit for bit.
//
// Discrete freedoms (a fragment written or not at an edge or depth tie, or at an alpha test whose
// legal alpha interval straddles the cutoff) fork the candidate set; the
// continuous ones (rounding, blending and filtering precision) widen each candidate's own box. The
// lo / hi images hold the hull of the set (what a later lookup of the texture reads, and what the
// reports show). A shared edge's two triangles are correlated through edge tags: of two triangles on
// either side of one edge with identical endpoints exactly one produces a fragment at a centre near it
// (GL 4.6 §14.6.1), so a candidate remembers which way its edge went (docs/crosscheck.md).
//
// Implements: the ambiguity classes, the interval storage attached to a rendered texture, and the
// thread-local state through which the sampler reports interval bounds to programs run in
// provenance mode. Program outputs are bounded by running the fragment program three times, with
// the sampler returning the per-channel lower bound, the upper bound, and the oracle value, and again
// on each candidate's bounds where one lookup has several (ShadeProvenance). This is valid because
// every built-in program is monotone (non-decreasing) in each sampled channel.
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
  kOobFetch = 1u << 6,         // no longer set: the GLSL twins define an out-of-range fetch as vec4(0)
  kHelperDeriv = 1u << 7,      // coarse and fine derivatives give different LODs
  kFilterPrecision = 1u << 8,  // unorm filtering precision (+-1 LSB on filtered lookups)
  kBlendPrecision = 1u << 9,   // unorm blending precision (+-1 LSB per blended write)
  kOutputRounding = 1u << 10,  // the unrounded output is within interpolation tolerance of a rounding step
  kInputInterval = 1u << 11,   // a sampled texture was rendered here and its texels carry their own freedoms
  kAlphaTest = 1u << 12,       // the program's discard (alpha test) differs between the legal sampled values
  kBcInterpolant = 1u << 13,   // a sampled S3TC texel is an interpolant, whose rounding is free (+-1 per channel)
  kClassCount = 14
};
std::string_view ambiguityClassName(int bit);

struct TextureDesc;
// The class of a pixel whose sampled texel differs between a texture's lower and upper images: for an
// S3TC texture those bounds are the decoder's freedom at upload (BC_INTERPOLANT), for any other they
// are the freedoms of the rendering that produced it in this frame (INPUT_INTERVAL).
uint16_t texelIntervalClass(const TextureDesc& d);

// A shared-edge constraint carried by a candidate: the candidate assumed that the triangle on `side`
// of the edge `key` (a hash of its two snapped endpoints) did (`covered`) or did not produce the
// fragment. A later triangle of the same draw near the same edge on the other side must do the
// opposite; one on the same side (the same edge rasterized again) must do the same (GL's invariance,
// Appendix A). The key includes the draw.
struct EdgeTag {
  uint64_t key = 0;
  uint8_t side = 0;
  bool covered = false;
  bool operator==(const EdgeTag&) const = default;
};

// The depth buffer as one candidate's chain of outcomes left it (docs/crosscheck.md, DEPTH_NEAR_EQUAL):
// an interval that holds GL's stored depth in that chain (the writer's depth and its own precision),
// and the depth-writer signature of the fragment that wrote it (raster/depth_signature.h; 0 = not
// known). Valid only in the depth epoch it was recorded in; otherwise the depth is the oracle's.
struct CandidateDepth {
  float lo = 0.0f, hi = 0.0f;
  uint64_t sig = 0;
  uint32_t epoch = 0;  // 0 = never recorded
};

// One whole result of a pixel: per channel [lo, hi] in channel units (bytes for unorm, the value for
// float and uint formats), the edge constraints under which it was produced, and the depth it left.
struct Candidate {
  static constexpr int kMaxTags = 2;
  std::array<double, 4> lo{}, hi{};
  std::array<EdgeTag, kMaxTags> tags{};
  uint8_t tagCount = 0;
  CandidateDepth depth;
};

// The most candidates a pixel keeps. A larger set collapses to its hull (one candidate, no tags),
// and the pixel is flagged kFallback so reports count it.
constexpr size_t kMaxCandidates = 16;
// kLookupForked: a fragment of the pixel took its candidates from a texture lookup's candidates.
// kLookupFallback: a lookup's candidates were used as their hull (more than kMaxLookupCandidates
// boxes, or two lookups of one fragment with more than one candidate each); reports count it.
enum PixelFlag : uint8_t { kFallback = 1u << 0, kLookupForked = 1u << 1, kLookupFallback = 1u << 2 };

// The most candidates one texture lookup keeps (docs/crosscheck.md, "Lookup candidates"): more
// distinct boxes collapse to their hull and the pixel is flagged kLookupFallback.
constexpr int kMaxLookupCandidates = 8;

// The interval images of one rendered texture: same format and shape as the texture.
struct Provenance {
  std::unique_ptr<TextureData> lo, hi;  // the hull of each pixel's candidates
  std::vector<std::vector<uint16_t>> classes;  // per level: layers * w * h, bottom row first
  std::vector<std::vector<uint8_t>> flags;     // per level, same layout: PixelFlag bits
  // Per level, same layout: the candidates of a pixel whose set is not its hull alone (two or more
  // candidates, or tags). Empty means one candidate, [lo, hi] of the images.
  std::vector<std::vector<std::vector<Candidate>>> candidates;
  // Per level, same layout: the depth of a pixel whose candidate set is empty (its one candidate).
  std::vector<std::vector<CandidateDepth>> depth;
  explicit Provenance(const TextureData& tex);
  size_t index(const TextureData& tex, uint32_t level, uint32_t layer, uint32_t x, uint32_t y) const;
  uint16_t& cls(const TextureData& tex, uint32_t level, uint32_t layer, uint32_t x, uint32_t y);
};

// What the sampler should return while a program runs in provenance mode.
enum class SampleBound : uint8_t { Value = 0, Lo = 1, Hi = 2 };

// A lookup in provenance mode has a list of candidates per pixel (its discrete freedoms: level plan,
// layer, NEAREST texel), each a box. With `candidate` < 0 the sampler returns the hull of the list;
// with k >= 0 it returns candidate k of a lookup with more than one (the last one when it has fewer),
// and the single box of any other lookup. The rasterizer re-runs the program per candidate when a
// pixel has exactly one lookup with more than one candidate (rast_provenance.cpp).
struct ShadeProvenance {
  bool active = false;
  SampleBound bound = SampleBound::Value;
  int candidate = -1;
  uint64_t quadSerial = 0;            // changes per shaded quad (the sampler caches lookups per quad)
  std::array<uint16_t, 4> classes{};  // per quad pixel, ORed in by the sampler
  std::array<bool, 4> dontCare{};     // per quad pixel: an undefined value was used
  // Per quad pixel, counted by the sampler in the hull run of the lower bound (bound Lo, candidate < 0):
  std::array<uint8_t, 4> forkingLookups{};   // lookups with more than one candidate
  std::array<uint8_t, 4> lookupCandidates{};  // the largest such candidate count
  std::array<bool, 4> lookupFallback{};       // a lookup's candidates collapsed to their hull
  // Work the lookup shortcuts skipped on this thread (sample_interval.cpp; StageTimes, not GL
  // counters): lambda alternatives not looked up because their plan lies inside a trilinear level
  // pair's weights, and level grids taken from a pass's memo. Kept across quads; the rasterizer moves
  // them into its per-thread record after each tile.
  uint64_t plansSkipped = 0, gridsShared = 0;
  void resetPixels() {
    classes = {};
    dontCare = {};
    forkingLookups = {};
    lookupCandidates = {};
    lookupFallback = {};
    candidate = -1;
    ++quadSerial;
  }
};
// Thread-local: each rasterizer thread shades its own quads.
ShadeProvenance& shadeProvenance();

}  // namespace tessera
