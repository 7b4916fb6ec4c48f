// Interval sampling: the per-pixel [lo, hi] bounds of a texture lookup in provenance mode
// (provenance.h). The exact lookups are in sample.cpp; this file calls them once per legal alternative.
//
// The alternatives a GL implementation may take for one lookup (tolerances: raster/tolerances.h, each
// derived in docs/crosscheck.md):
// - lambda: exact rho vs the spec's bounds max(mu, mv) <= f <= mu + mv (GL 4.6 §8.14.1 eq. 8.7), coarse
//   vs fine derivatives (GLSL §8.14.1), and log2 precision (tolerance::kLod8); the mag/min switch point
//   c = 1/2 where §8.14 allows it;
// - texel coordinates: the sample-position shift times the coordinate derivatives, float interpolation
//   error, and half an 8-bit weight step (tolerance::kSamplePosPx, kInterpRel, kWeightTexel);
// - array layer: r + 1/2 near an integer (tolerance::kLayer);
// - unorm filtering precision: +-1 LSB on an alternative that blends differing texels with a weight not
//   in {0, 1} (tolerance::kFilterUnorm, the mask of sampleBlended).
// Each alternative is looked up with the exact path's own plan and filter (makePlan; sampleBlended, or
// sampleBlendedGrid for a plan's grid of coordinate alternatives: the same bits). The alternatives are
// grouped by their discrete choice (level plan incl. the c = 1/2 switch, layer, NEAREST texel), giving
// each pixel's lookup a short list of candidate boxes rather than one hull (docs/crosscheck.md,
// "Lookup candidates"); the oracle's own lookup is in the first. Three exact shortcuts (skipped
// trilinear weights, shared level grids, one reduction per LINEAR plan) are off under the "reference"
// SIMD target (intervalPass).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "raster/provenance.h"
#include "raster/sample.h"
#include "raster/sample_detail.h"
#include "raster/simd_targets.h"
#include "raster/tolerances.h"

namespace tessera::sample_detail {
namespace {

// A box per channel in the lookup's value space.
struct Box {
  float lo[4], hi[4];
  void init(const float l[4], const float h[4]) {
    for (int c = 0; c < 4; ++c) lo[c] = l[c], hi[c] = h[c];
  }
  void add(const float l[4], const float h[4]) {
    for (int c = 0; c < 4; ++c) {
      if (l[c] < lo[c] || std::isnan(lo[c])) lo[c] = l[c];
      if (h[c] > hi[c] || std::isnan(hi[c])) hi[c] = h[c];
    }
  }
  bool inside(const Box& o) const {  // within o (NaN: never)
    for (int c = 0; c < 4; ++c)
      if (!(lo[c] >= o.lo[c] && hi[c] <= o.hi[c])) return false;
    return true;
  }
  bool same(const Box& o) const { return std::memcmp(this, &o, sizeof *this) == 0; }
};

// The discrete choice that a group of alternatives shares: the level plan (its levels by size, the
// texel filter), the layer, and for a NEAREST texel filter the coordinate alternative (which texel).
// Alternatives within a group differ only continuously: the level weight of a pair over lambda, and
// the LINEAR weights over the coordinate tolerance.
struct GroupKey {
  int32_t w0, h0, w1, h1;
  int32_t levels;
  bool linear;
  uint32_t layer;
  int32_t a, b;  // coordinate alternative per axis for NEAREST, -1 for LINEAR
  bool operator==(const GroupKey&) const = default;
};
struct Group {
  GroupKey key;
  Box box;
};

// All candidates of one pixel's lookup (the hull is what candidate < 0 returns).
struct LookupSet {
  int n = 0;
  bool fallback = false;
  Box c[kMaxLookupCandidates];
  Box hull;
};

inline bool sameValue(const float a[4], const float b[4]) { return std::memcmp(a, b, 4 * sizeof(float)) == 0; }

// Plans that sample identically: the same filter, wrap modes, layers, levels and level weights, and
// border texel (fields compared one by one: a Plan's padding bytes are indeterminate).
bool samePlan(const Plan& a, const Plan& b) {
  if (a.complete != b.complete || a.linear != b.linear || a.wrapS != b.wrapS || a.wrapT != b.wrapT ||
      a.lastLayer != b.lastLayer || a.levelCount != b.levelCount || std::memcmp(a.border, b.border, sizeof a.border) != 0)
    return false;
  for (int l = 0; l < a.levelCount; ++l) {
    const LevelRef &x = a.lv[l], &y = b.lv[l];
    if (x.data != y.data || x.layerStride != y.layerStride || x.w != y.w || x.h != y.h ||
        a.levelWeight[l] != b.levelWeight[l])
      return false;
  }
  return true;
}

// Candidate coordinates along one axis for one plan: both ends of the tolerance, plus every texel
// centre inside it for LINEAR (where the piecewise-linear filter has its kinks).
int coordCandidates(float x, double tol, const Plan& p, bool horizontal, float out[6]) {
  int n = 0;
  out[n++] = float(double(x) - tol);
  out[n++] = float(double(x) + tol);
  if (!p.linear) return n;
  for (int l = 0; l < p.levelCount && n < 6; ++l) {
    const double size = horizontal ? p.lv[l].w : p.lv[l].h;
    const double a = (double(x) - tol) * size - 0.5, b = (double(x) + tol) * size - 0.5;
    if (!(b - a < 4.0)) continue;  // NaN or huge: the two ends already stand for it
    for (double k = std::ceil(a); k <= b && n < 6; k += 1.0) out[n++] = float((k + 0.5) / size);
  }
  return n;
}

// The lambda alternatives whose plans add nothing to an unorm lookup's groups, classes or group
// order. Plans that blend the same two levels differ only in the second level's weight f (0 < f < 256):
// each point's accumulator is 256 S0 + f (S1 - S0) in exact integers, and the taps given weight (so
// the blended mask) do not depend on f. Over the pair's lambdas a point's value (a monotone function
// of the accumulator) is then monotone in f: the least and greatest f reach the hull of the pair's
// values, and if some f gives a value other than the oracle's, so does one of them (LOD_NEAR_SWITCH).
// Every plan of a pair makes the same group keys, so keeping the pair's first plan keeps the order
// in which groups are made. The oracle's plan (index 0) always stays. (With today's candidate order,
// oracle, least, greatest, then ascending switch points, a pair's first plan is already the oracle's,
// its least or its greatest; the rule keeps the order safe if that order changes.)
void markInteriorWeights(const Plan* plans, int n, bool* interior) {
  for (int i = 1; i < n; ++i) {
    const Plan& p = plans[i];
    if (!p.complete || p.levelCount != 2) continue;
    int first = i, least = i, greatest = i;
    for (int j = 0; j < n; ++j) {
      const Plan& q = plans[j];
      if (!q.complete || q.levelCount != 2 || q.lv[0].data != p.lv[0].data || q.lv[1].data != p.lv[1].data) continue;
      if (j < first) first = j;
      const uint32_t f = q.levelWeight[1];
      if (f < plans[least].levelWeight[1] || (f == plans[least].levelWeight[1] && j < least)) least = j;
      if (f > plans[greatest].levelWeight[1] || (f == plans[greatest].levelWeight[1] && j < greatest)) greatest = j;
    }
    interior[i] = i != first && i != least && i != greatest;
  }
}

// One pass over the legal alternatives of one pixel's lookup, reading the image that
// shadeProvenance().bound selects: the alternatives grouped by their discrete choice (GroupKey), each
// group's box the hull of its alternatives, each alternative widened by the filter precision in the
// channels where its own filter rounds (sampleBlended's mask). Group 0 holds the oracle's lookup. `der` =
// {dsdx, dtdx, dsdy, dtdy} per derivative choice (0: the oracle's, 1: the alternative), in normalized
// coordinates.
void intervalPass(const TexUnit& u, float s, float t, float r, bool array, const double der[2][4], int derCount,
                  float bias, uint16_t& classes, std::vector<Group>& groups) {
  groups.clear();
  const TextureDesc& d = u.tex->desc;
  const double W = double(d.width), H = double(d.height);
  int32_t lamOracle = 0, lamLo = 0, lamHi = 0;
  int32_t exact[2] = {0, 0};
  for (int k = 0; k < derCount; ++k) {
    const double ux = der[k][0] * W, vx = der[k][1] * H, uy = der[k][2] * W, vy = der[k][3] * H;
    const double rx = ux * ux + vx * vx, ry = uy * uy + vy * vy;
    const double mu = std::max(std::fabs(ux), std::fabs(uy)), mv = std::max(std::fabs(vx), std::fabs(vy));
    const double lower = std::max(mu, mv), upper = mu + mv;
    const int32_t e = lambdaBaseFromRho2(rx > ry ? rx : ry);
    const int32_t a = lambdaBaseFromRho2(lower * lower), b = lambdaBaseFromRho2(upper * upper);
    exact[k] = finishLambda(e, u.sampler, bias);
    const int32_t lo = std::min({e, a, b}), hi = std::max({e, a, b});
    const int32_t flo = finishLambda(lo == kLodMinusInf ? lo : lo - tolerance::kLod8, u.sampler, bias);
    const int32_t fhi = finishLambda(hi >= kLodMax ? hi : hi + tolerance::kLod8, u.sampler, bias);
    if (k == 0) lamOracle = exact[0], lamLo = flo, lamHi = fhi;
    lamLo = std::min(lamLo, flo);
    lamHi = std::max(lamHi, fhi);
  }
  if (derCount > 1 && exact[1] != exact[0]) classes |= kHelperDeriv;

  // Lambda candidates: the ends, the oracle's, and both sides of every switch point inside
  // (integers: level pairs and the mag/min switch at c = 0; k + 1/2: nearest-mip rounding). A level
  // pair (k - 1, k) spans lambda in (k - 1, k): its group is looked up at both ends of its part of the
  // range, so k - 1/256 (the weight 255/256 of level k) is a switch point too.
  constexpr int kMaxLam = 32;
  int32_t lam[kMaxLam];
  int nl = 0;
  lam[nl++] = lamOracle;
  lam[nl++] = lamLo;
  lam[nl++] = lamHi;
  const int32_t kMaxK = int32_t(d.levels) + 1;
  for (int32_t k = 0; k <= kMaxK; ++k)
    for (int32_t off : {-1, 0, 1, 128, 129}) {
      const int32_t v = k * 256 + off;
      if (v > lamLo && v < lamHi && nl < kMaxLam) lam[nl++] = v;
    }

  // Layer candidates.
  uint32_t layerOracle = 0, layerLo = 0, layerHi = 0;
  if (array) {
    layerOracle = selectLayer(r, d.layers);
    layerLo = selectLayer(r - tolerance::kLayer, d.layers);
    layerHi = selectLayer(r + tolerance::kLayer, d.layers);
    if (layerLo != layerHi) classes |= kLayerTie;
  }

  const double tolS = (std::fabs(der[0][0]) + std::fabs(der[0][2])) * tolerance::kSamplePosPx +
                      std::fabs(double(s)) * tolerance::kInterpRel;
  const double tolT = (std::fabs(der[0][1]) + std::fabs(der[0][3])) * tolerance::kSamplePosPx +
                      std::fabs(double(t)) * tolerance::kInterpRel;

  const int channels = channelCount(d.format);
  // FILTER_PRECISION's widening of one value; both are monotone (non-decreasing) in v.
  auto widenLo = [](float v) { return std::max(0.0f, float(double(v) - tolerance::kFilterUnorm)); };
  auto widenHi = [](float v) { return std::min(1.0f, float(double(v) + tolerance::kFilterUnorm)); };
  // Adds a box to the group of (plan, layer, coordinate alternative).
  int lastGroup = -1;
  auto addBox = [&](const Plan& p, uint32_t layer, int32_t a, int32_t b, const float l[4], const float h[4]) {
    GroupKey key{};
    key.w0 = p.lv[0].w, key.h0 = p.lv[0].h;
    key.w1 = p.levelCount == 2 ? p.lv[1].w : 0, key.h1 = p.levelCount == 2 ? p.lv[1].h : 0;
    key.levels = p.levelCount, key.linear = p.linear, key.layer = layer;
    key.a = p.linear ? -1 : a, key.b = p.linear ? -1 : b;
    // The alternatives of one LINEAR plan and layer come in a row and share one group.
    if (lastGroup >= 0 && groups[size_t(lastGroup)].key == key) return groups[size_t(lastGroup)].box.add(l, h);
    for (size_t i = 0; i < groups.size(); ++i)
      if (groups[i].key == key) {
        lastGroup = int(i);
        groups[i].box.add(l, h);
        return;
      }
    lastGroup = int(groups.size());
    groups.push_back({key, {}});
    groups.back().box.init(l, h);
  };
  // Adds one alternative to its group, widened by FILTER_PRECISION where its filter rounds.
  auto addSample = [&](const Plan& p, uint32_t layer, int32_t a, int32_t b, uint32_t blended, const float v[4]) {
    float l[4], h[4];
    for (int c = 0; c < 4; ++c) {
      l[c] = h[c] = v[c];
      if (c < channels && (blended >> c & 1)) l[c] = widenLo(v[c]), h[c] = widenHi(v[c]);
    }
    if (blended) classes |= kFilterPrecision;
    addBox(p, layer, a, b, l, h);
  };
  // The unorm filter's values are never NaN, so a group's box is a plain minimum and maximum, in any
  // order; the LINEAR alternatives of one plan and layer all join one group.
  const bool unorm = d.format == Format::RGBA8 || d.format == Format::R8;

  float nominal[4];
  {
    const Plan p = makePlan(u, lamOracle);
    const uint32_t blended = sampleBlended(u, p, s, t, layerOracle, nominal);
    // The nominal coordinates are the last alternative of each axis (index 2 of a NEAREST plan).
    addSample(p, layerOracle, 2, 2, blended, nominal);
    // A texture rendered in provenance mode is read through its lower or upper interval image
    // (sample.cpp); where that differs from its values, the texels' own freedoms reach this lookup.
    ShadeProvenance& sp = shadeProvenance();
    if (u.tex->prov && sp.bound != SampleBound::Value) {
      const SampleBound b = sp.bound;
      sp.bound = SampleBound::Value;  // makePlan picks the image the texels are read from
      const Plan pv = makePlan(u, lamOracle);
      float v[1][4];
      sampleN(u, pv, 1, &s, &t, &layerOracle, v);
      sp.bound = b;
      if (!sameValue(v[0], nominal))
        classes |= texelIntervalClass(u.tex->desc);
    }
  }
  // GL 4.6 §8.14: with mag LINEAR and min NEAREST_MIPMAP_NEAREST or NEAREST_MIPMAP_LINEAR the switch
  // point c may be 1/2 instead of the oracle's 0 (spec-choices T4): for lambda in (0, 1/2] the mag
  // filter is then legal too.
  const SamplerState& ss = u.sampler.state;
  const bool halfSwitch = ss.magFilter == Filter::Linear &&
                          (ss.minFilter == Filter::NearestMipmapNearest || ss.minFilter == Filter::NearestMipmapLinear);
  // Lambda candidates often give the same plan (magnification, levels clamped to the last, repeated
  // ends). A plan seen before adds nothing: its samples, groups and boxes are the same, and its
  // classes too, because the oracle's plan comes first (lam[0], pi = 0), so an earlier copy of any
  // plan already set every class a later copy could set.
  // Thread-local: a pass sees a few plans, and constructing 64 each pass cost more than comparing them.
  thread_local Plan seen[2 * kMaxLam];
  int nSeen = 0;
  thread_local Plan plans[kMaxLam];  // each lambda's plan with the oracle's switch point
  thread_local GridMemo memo;        // level grids shared by this pass's plans
  memo.begin();
  const uint64_t memoHits = memo.hits;
  for (int li = 0; li < nl; ++li) plans[li] = makePlan(u, lam[li]);
  // The shortcuts below (skipped weights, shared level grids, a plan's LINEAR alternatives reduced at
  // once) give the same groups and classes; the "reference" SIMD target runs without them, looking up
  // every alternative with sampleBlended and adding it with addSample (tests/raster/
  // test_provenance_shortcuts.cpp compares the two on every scene).
  const bool shortcuts = simd::kernelsOn();
  bool interior[kMaxLam] = {};
  if (shortcuts && (d.format == Format::RGBA8 || d.format == Format::R8)) markInteriorWeights(plans, nl, interior);
  for (int pi = 0; pi < 2 * nl; ++pi) {
    const int li = pi >> 1;
    const bool alt = pi & 1;
    if (alt && !(halfSwitch && lam[li] > 0 && lam[li] <= 128)) continue;
    if (!alt && interior[li]) {
      ++shadeProvenance().plansSkipped;
      continue;
    }
    const Plan p = alt ? makePlan(u, lam[li], 128) : plans[li];
    if (std::any_of(seen, seen + nSeen, [&](const Plan& q) { return samePlan(p, q); })) continue;
    seen[nSeen++] = p;
    const LevelRef& coarse = p.lv[p.levelCount - 1];
    const double qS = tolerance::kWeightTexel / coarse.w, qT = tolerance::kWeightTexel / coarse.h;
    float sc[7], tc[7];
    int ns = coordCandidates(s, tolS + (p.linear ? qS : 0.0), p, true, sc);
    int nt = coordCandidates(t, tolT + (p.linear ? qT : 0.0), p, false, tc);
    sc[ns++] = s;
    tc[nt++] = t;
    for (uint32_t layer = layerLo; layer <= layerHi; ++layer) {
      float vs[kGridMax * kGridMax][4];
      uint32_t masks[kGridMax * kGridMax];
      if (shortcuts) {
        sampleBlendedGrid(u, p, sc, ns, tc, nt, layer, vs, masks, &memo);
      } else {
        for (int a = 0; a < ns; ++a)
          for (int b = 0; b < nt; ++b) masks[a * nt + b] = sampleBlended(u, p, sc[a], tc[b], layer, vs[a * nt + b]);
      }
      const bool nominalLayer = layer == layerOracle;
      if (shortcuts && p.linear && unorm) {
        // What adding every alternative with addSample gives, without NaNs: per channel, the least and
        // greatest widened value among the alternatives blended there (the widening is monotone, so
        // it is applied once to their extreme) and the least and greatest of the others.
        constexpr float kInf = std::numeric_limits<float>::infinity();
        float loB[4] = {kInf, kInf, kInf, kInf}, hiB[4] = {-kInf, -kInf, -kInf, -kInf};
        float loP[4] = {kInf, kInf, kInf, kInf}, hiP[4] = {-kInf, -kInf, -kInf, -kInf};
        uint32_t anyBlended = 0;
        const int n = ns * nt;
        for (int i = 0; i < n; ++i) {
          anyBlended |= masks[i];
          for (int c = 0; c < 4; ++c) {
            const float v = vs[i][c];
            if (masks[i] >> c & 1) {
              loB[c] = std::min(loB[c], v), hiB[c] = std::max(hiB[c], v);
            } else {
              loP[c] = std::min(loP[c], v), hiP[c] = std::max(hiP[c], v);
            }
          }
        }
        float l[4], h[4];
        for (int c = 0; c < 4; ++c) {
          l[c] = hiB[c] < loB[c] ? loP[c] : std::min(loP[c], widenLo(loB[c]));
          h[c] = hiB[c] < loB[c] ? hiP[c] : std::max(hiP[c], widenHi(hiB[c]));
        }
        if (anyBlended) classes |= kFilterPrecision;
        addBox(p, layer, -1, -1, l, h);
        if (!nominalLayer) continue;
        // The classes of the per-alternative loop below: LOD_NEAR_SWITCH from the nominal coordinates
        // of another lambda, SUBTEXEL_NEAR_HALF from other coordinates at the oracle's lambda.
        const int nominalIndex = n - 1;  // (ns - 1, nt - 1)
        if ((alt || lam[li] != lamOracle) && !sameValue(vs[nominalIndex], nominal)) classes |= kLodNearSwitch;
        if (!alt && lam[li] == lamOracle)
          for (int i = 0; i < nominalIndex; ++i)
            if (!sameValue(vs[i], nominal)) {
              classes |= kSubtexelNearHalf;
              break;
            }
        continue;
      }
      for (int a = 0; a < ns; ++a)
        for (int b = 0; b < nt; ++b) {
          const float* v = vs[a * nt + b];
          addSample(p, layer, a, b, masks[a * nt + b], v);
          if (sameValue(v, nominal)) continue;
          // A class names the freedom that alone changes the value: the LOD with the nominal
          // coordinates and layer, or the coordinates with the oracle's LOD and layer. Combinations
          // only widen the interval.
          const bool nominalCoords = a == ns - 1 && b == nt - 1;
          if ((alt || lam[li] != lamOracle) && nominalCoords && nominalLayer) classes |= kLodNearSwitch;
          if (!alt && lam[li] == lamOracle && !nominalCoords && nominalLayer) classes |= kSubtexelNearHalf;
        }
    }
  }
  shadeProvenance().gridsShared += memo.hits - memoHits;
}

// The candidates of one pixel's lookup from its lower-image and upper-image passes (the same groups
// in the same order): duplicates and boxes inside another box are dropped (the union accepts the
// same values, and a monotone program maps a box inside another inside its image), the oracle's
// group stays first, and past kMaxLookupCandidates the hull is the one candidate.
void buildSet(const std::vector<Group>& lo, const std::vector<Group>& hi, LookupSet& out) {
  const size_t n = std::min(lo.size(), hi.size());
  for (size_t i = 0; i < n; ++i) {
    if (i == 0) {
      out.hull.init(lo[0].box.lo, hi[0].box.hi);
    } else {
      out.hull.add(lo[i].box.lo, hi[i].box.hi);
    }
  }
  constexpr size_t kMaxGroups = 128;
  bool overflow = lo.size() != hi.size() || n > kMaxGroups || n == 0;
  const size_t m = overflow ? 0 : n;
  Box boxes[kMaxGroups];
  for (size_t i = 0; i < m; ++i) boxes[i].init(lo[i].box.lo, hi[i].box.hi);
  bool keep[kMaxGroups];
  for (size_t i = 0; i < m; ++i) {
    keep[i] = true;
    for (size_t j = 0; j < m && keep[i]; ++j)
      if (j != i && boxes[i].inside(boxes[j]) && (!boxes[i].same(boxes[j]) || j < i)) keep[i] = false;
  }
  out.n = 0;
  out.fallback = false;
  if (m > 0 && !keep[0]) {
    // The oracle's box lies inside another: that one goes first.
    for (size_t j = 1; j < m; ++j)
      if (keep[j] && boxes[0].inside(boxes[j])) {
        out.c[out.n++] = boxes[j];
        keep[j] = false;
        break;
      }
  }
  for (size_t i = 0; i < m; ++i) {
    if (!keep[i]) continue;
    if (out.n == kMaxLookupCandidates) {
      overflow = true;
      break;
    }
    out.c[out.n++] = boxes[i];
  }
  if (overflow || out.n == 0) {
    out.n = 1;
    out.fallback = true;
    out.c[0] = out.hull;
  }
}

// The candidates of one pixel's lookup. A rendered texture (kInputInterval) is read through its
// lower image for the lower bounds and its upper image for the upper ones; any other texture once.
void lookupSet(const TexUnit& u, float s, float t, float r, bool array, const double der[2][4], int derCount,
               float bias, uint16_t& classes, LookupSet& out) {
  thread_local std::vector<Group> lo, hi;
  ShadeProvenance& sp = shadeProvenance();
  if (!u.tex->prov) {
    intervalPass(u, s, t, r, array, der, derCount, bias, classes, lo);
    buildSet(lo, lo, out);
    return;
  }
  const SampleBound b = sp.bound;
  sp.bound = SampleBound::Lo;
  intervalPass(u, s, t, r, array, der, derCount, bias, classes, lo);
  sp.bound = SampleBound::Hi;
  intervalPass(u, s, t, r, array, der, derCount, bias, classes, hi);
  sp.bound = b;
  buildSet(lo, hi, out);
}

// The lookups of the current quad, kept while the program runs again for the other bounds and
// candidates (the same inputs give the same sets).
struct CachedLookup {
  const TextureData* tex;
  SamplerQ sampler;
  float s[4], t[4], r[4], bias;
  bool hasR, hasGrad;
  double grad[4];
  LookupSet sets[4];
  uint16_t classes[4];
};

}  // namespace

// Quad lookup in provenance mode: each pixel's candidate set; out = the lower or upper bound of the
// hull or of the candidate that shadeProvenance().candidate selects.
void sampleQuadInterval(const TexUnit& u, const float s[4], const float t[4], const float* r, float bias,
                        const double* grad, float out[4][4]) {
  ShadeProvenance& pv = shadeProvenance();
  thread_local std::vector<CachedLookup> cache;
  thread_local uint64_t cacheSerial = ~uint64_t(0);
  if (cacheSerial != pv.quadSerial) cache.clear(), cacheSerial = pv.quadSerial;
  CachedLookup key{};
  key.tex = u.tex;
  key.sampler = u.sampler;
  std::memcpy(key.s, s, sizeof key.s);
  std::memcpy(key.t, t, sizeof key.t);
  if (r) std::memcpy(key.r, r, sizeof key.r);
  key.bias = bias;
  key.hasR = r != nullptr;
  key.hasGrad = grad != nullptr;
  if (grad) std::memcpy(key.grad, grad, sizeof key.grad);
  const CachedLookup* hit = nullptr;
  for (const CachedLookup& c : cache)
    if (c.tex == key.tex && std::memcmp(&c.sampler, &key.sampler, sizeof key.sampler) == 0 &&
        std::memcmp(c.s, key.s, sizeof key.s) == 0 && std::memcmp(c.t, key.t, sizeof key.t) == 0 &&
        std::memcmp(c.r, key.r, sizeof key.r) == 0 && c.bias == key.bias && c.hasR == key.hasR &&
        c.hasGrad == key.hasGrad && std::memcmp(c.grad, key.grad, sizeof key.grad) == 0) {
      hit = &c;
      break;
    }
  if (!hit) {
    for (int p = 0; p < 4; ++p) {
      double der[2][4];
      // 0: coarse (the oracle's) or the explicit gradient; 1: fine, per row / column of the quad.
      if (grad) {
        for (int k = 0; k < 4; ++k) der[0][k] = grad[k];
      } else {
        der[0][0] = double(s[1]) - s[0], der[0][1] = double(t[1]) - t[0];
        der[0][2] = double(s[2]) - s[0], der[0][3] = double(t[2]) - t[0];
      }
      const int row = (p >> 1) * 2, col = p & 1;
      der[1][0] = double(s[row + 1]) - s[row], der[1][1] = double(t[row + 1]) - t[row];
      der[1][2] = double(s[2 + col]) - s[col], der[1][3] = double(t[2 + col]) - t[col];
      key.classes[p] = 0;
      lookupSet(u, s[p], t[p], r ? r[p] : 0.0f, r != nullptr, der, 2, bias, key.classes[p], key.sets[p]);
    }
    cache.push_back(key);
    hit = &cache.back();
  }
  const bool counting = pv.bound == SampleBound::Lo && pv.candidate < 0;
  for (int p = 0; p < 4; ++p) {
    const LookupSet& set = hit->sets[p];
    pv.classes[size_t(p)] |= hit->classes[p];
    if (counting) {
      if (set.n > 1) {
        ++pv.forkingLookups[size_t(p)];
        pv.lookupCandidates[size_t(p)] = std::max(pv.lookupCandidates[size_t(p)], uint8_t(set.n));
      }
      if (set.fallback) pv.lookupFallback[size_t(p)] = true;
    }
    const Box& box = pv.candidate < 0 ? set.hull : set.c[std::min(pv.candidate, set.n - 1)];
    for (int c = 0; c < 4; ++c) out[p][c] = pv.bound == SampleBound::Lo ? box.lo[c] : box.hi[c];
  }
}

}  // namespace tessera::sample_detail
