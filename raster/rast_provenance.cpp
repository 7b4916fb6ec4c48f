// Provenance-mode rasterization of one triangle in one tile (see rast.h and provenance.h).
//
// The value path is the same as the fast path: the same exact coverage, interpolation, depth test and
// writeFragment. Around it, this file records for every touched pixel the candidate results that GL
// allows, and why:
// - EDGE_TIE / CLIP_EDGE: the centre lies within the edge margin (GL's snapping, and for an edge with
//   an endpoint made by clipping, GL's float clipping), so another legal implementation may cover it
//   or not: every candidate forks into "written" and "not written". Near an edge shared with another
//   triangle the two are correlated by edge tags (no gap, no double hit).
// - ALPHA_TEST: the program discards the fragment in some of its runs (lower bound, upper bound, value,
//   lookup candidates) and not in others: the alpha that GL filters may lie on either side of the
//   program's cutoff, so the same fork (the written outcome takes the fragment's whole box).
// - DEPTH_NEAR_EQUAL: the depth test is within the depth tolerance of flipping: the same fork. Each
//   candidate carries the depth its own chain left (CandidateDepth), so a later test is decided per
//   candidate; where the stored depth's writer has the incoming fragment's depth-writer signature
//   the tie is exact (GL's invariance, raster/depth_signature.h) and does not fork.
// - the program's output box: three runs (lower bound, upper bound, value) with the sampler in
//   interval mode, widened by the output-rounding tolerance; where one lookup of the fragment has
//   several candidates (LOD level, layer, texel), a pair of runs per candidate, each a written outcome.
// - BLEND_PRECISION: blending is evaluated at the 16 corners of (src, src alpha, dst, dst alpha) per
//   destination candidate, then widened by +-2.5 LSB for unorm.
// The tolerances are in raster/tolerances.h, each derived in docs/crosscheck.md.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "raster/fragops.h"
#include "raster/provenance.h"
#include "raster/rast.h"
#include "raster/tolerances.h"

namespace tessera::detail {
namespace {

inline double clamp01(double v) { return v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0; }

// Bytes that RNE or any tie-breaking may produce from values in [a, b] (in [0, 1] units).
inline void unormRange(double a, double b, int& lo, int& hi) {
  a = clamp01(a), b = clamp01(b);
  lo = int(std::ceil(a * 255.0 - 0.5));
  hi = int(std::floor(b * 255.0 + 0.5));
  lo = std::clamp(lo, 0, 255), hi = std::clamp(hi, 0, 255);
}

struct FragInterval {
  double lo[4], hi[4];  // program output space
  double tol[4];        // output-rounding tolerance
};

// The fragment interval of attachment `a`, pixel `p`, from the three runs.
// posTolPx: how far (pixels) GL's sample may sit from the oracle's on the triangle's plane.
// withValue: the value run lies in the interval (false for a lookup candidate other than the oracle's,
// whose box need not contain the oracle's value; its tolerance still comes from the value run).
FragInterval fragInterval(const QuadOut* const (&o)[3], int a, int p, bool uintOut, double posTolPx,
                          bool withValue = true) {
  FragInterval f{};
  const int runs = withValue ? 3 : 2;
  for (int c = 0; c < 4; ++c) {
    if (uintOut) {
      const uint32_t v0 = o[0]->color[a][p].u[c], v1 = o[1]->color[a][p].u[c], v2 = o[runs - 1]->color[a][p].u[c];
      f.lo[c] = double(std::min({v0, v1, v2}));
      f.hi[c] = double(std::max({v0, v1, v2}));
      continue;
    }
    double v[3];
    for (int r = 0; r < 3; ++r) {
      const float x = o[r]->color[a][p].f[c];
      v[r] = std::isnan(x) ? 0.0 : double(x);
    }
    f.lo[c] = std::min({v[0], v[1], v[runs - 1]});
    f.hi[c] = std::max({v[0], v[1], v[runs - 1]});
    // Output rounding: the value run's quad gradient times the position tolerance, plus float error.
    const QuadOut& val = *o[2];
    const double g = std::fabs(double(val.color[a][1].f[c]) - val.color[a][0].f[c]) +
                     std::fabs(double(val.color[a][2].f[c]) - val.color[a][0].f[c]);
    f.tol[c] = (std::isfinite(g) ? g * posTolPx : 0.0) + std::fabs(v[2]) * tolerance::kInterpRel;
  }
  return f;
}

// What one fragment may do to one pixel. Coverage and the depth test are the discrete freedoms: each
// legal combination is an outcome, and every candidate of the pixel forks into the outcomes that
// are legal for it (an edge tag can force the coverage outcome, see EdgeTag in provenance.h).
struct PixelUpdate {
  bool covered;      // the oracle covers the centre
  bool coverTie;     // another legal snapping may flip that (EDGE_TIE / CLIP_EDGE)
  bool depthPass;    // the oracle's depth test passes
  bool depthTie;     // another legal depth may flip that (DEPTH_NEAR_EQUAL)
  bool discarded;    // the program discards the fragment (value run)
  bool discardTie;   // another legal sampled value flips that (ALPHA_TEST)
  bool keepValue;    // the oracle writes this fragment
  bool ambiguous;    // another legal outcome differs in whether it writes
  bool dontCare;     // the program used an undefined value
  double posTolPx;   // the sample-position tolerance of the triangle's plane (fragInterval)
  bool hasEdge;      // coverTie comes from exactly one edge of a triangle made without clipping
  EdgeTag edge;      // that edge, with covered = true
  uint16_t classes;  // classes of the fragment (sampler + coverage + depth)
  // The depth test per candidate (depthOutcome): the fragment's depth and its precision, the oracle's
  // stored depth before it, the test, and the fragment's depth-writer signature and epoch.
  bool depthTest, depthWrite, depthUnbounded;
  CompareFunc func;
  float z, zStored;
  double zTol;
  uint64_t depthSig;
  uint32_t depthEpoch;
  // Lookup candidates (docs/crosscheck.md): the candidates of the fragment's one lookup with more than
  // one (0: none, the three runs bound it), with the program's runs on each one's lower and upper
  // bound; lookupFallback: lookups were used as their hull.
  int lookupCount;
  const QuadOut* lookupLo;
  const QuadOut* lookupHi;
  bool lookupFallback;
};

// The depth a candidate's chain left: its own record in this epoch, else the oracle's stored depth.
inline CandidateDepth depthOf(const CandidateDepth& d, const PixelUpdate& u) {
  if (d.epoch == u.depthEpoch) return d;
  return CandidateDepth{u.zStored, u.zStored, 0, u.depthEpoch};
}

// Whether the fragment passes the depth test against a candidate's depth, and whether another legal
// implementation may decide otherwise (docs/crosscheck.md, DEPTH_NEAR_EQUAL). A stored depth written
// by a fragment with the same depth-writer signature is GL's own value for this fragment, bit for bit
// (Appendix A), so the test compares equal values exactly. Otherwise the test may flip where the
// fragment's depth interval meets the stored one; ALWAYS and NEVER never flip.
struct DepthOutcome {
  bool pass, tie;
};
inline DepthOutcome depthOutcome(const CandidateDepth& d, const PixelUpdate& u) {
  if (!u.depthTest) return {true, false};
  if (u.depthSig != 0 && d.sig == u.depthSig) return {depthPasses(u.func, u.z, u.z), false};
  const bool pass = depthPasses(u.func, u.z, d.lo);
  if (u.func == CompareFunc::Always || u.func == CompareFunc::Never) return {pass, false};
  // A fragment depth known exactly (a program-written depth from exact texels, F11: zTol = 0) against an
  // exactly known stored depth is the same comparison in every GL: no tie. Interpolated depths always
  // have zTol > 0, so this changes nothing for them.
  if (u.zTol == 0.0 && d.lo == d.hi && !u.depthUnbounded) return {pass, false};
  const bool tie = u.depthUnbounded || (double(u.z) + u.zTol >= double(d.lo) && double(u.z) - u.zTol <= double(d.hi));
  return {pass, tie};
}

// The depth a candidate holds after the fragment wrote it: the fragment's depth within its precision.
inline CandidateDepth writtenDepth(const CandidateDepth& before, const PixelUpdate& u) {
  if (!u.depthWrite) return before;
  constexpr float kInf = std::numeric_limits<float>::infinity();
  CandidateDepth d;
  const double l = double(u.z) - u.zTol, h = double(u.z) + u.zTol;
  d.lo = float(l), d.hi = float(h);  // rounded outward below
  if (double(d.lo) > l) d.lo = std::nextafter(d.lo, -kInf);
  if (double(d.hi) < h) d.hi = std::nextafter(d.hi, kInf);
  if (u.depthUnbounded) d.lo = -kInf, d.hi = kInf;
  d.sig = u.depthSig;
  d.epoch = u.depthEpoch;
  return d;
}

// Two chains merged into one candidate: the depth of either (the hull), a signature only if shared.
inline CandidateDepth mergeDepth(const CandidateDepth& a, const CandidateDepth& b) {
  if (a.epoch != b.epoch) return CandidateDepth{};  // one is not recorded: the oracle's depth
  CandidateDepth m = a;
  m.lo = std::min(a.lo, b.lo), m.hi = std::max(a.hi, b.hi);
  if (a.sig != b.sig) m.sig = 0;
  return m;
}

// Whether a fragment that the candidate's coverage outcome `covered` produced is written, given the
// candidate's depth test.
inline void writeOutcomes(const PixelUpdate& u, const DepthOutcome& d, bool covered, bool& canWrite, bool& canSkip) {
  if (!covered || (u.discarded && !u.discardTie)) {
    canWrite = false, canSkip = true;
    return;
  }
  canWrite = d.pass || d.tie;
  canSkip = !d.pass || d.tie || u.discardTie;
}

// The channel layout of a target format for candidate boxes.
struct ChannelKind {
  int n;
  bool unorm, isFloat;
};
inline ChannelKind kindOf(Format f) {
  switch (f) {
    case Format::RGBA8: return {4, true, false};
    case Format::R8: return {1, true, false};
    case Format::RG32F: return {2, false, true};
    case Format::RGBA32F: return {4, false, true};
    default: return {1, false, false};  // R32UI
  }
}

inline double loadChannel(const ChannelKind& k, const uint8_t* p, int c) {
  if (k.unorm) return p[c];
  if (k.isFloat) {
    float v;
    std::memcpy(&v, p + 4 * c, 4);
    return v;
  }
  uint32_t v;
  std::memcpy(&v, p + 4 * c, 4);
  return v;
}

inline void storeChannel(const ChannelKind& k, uint8_t* p, int c, double v, bool up) {
  if (k.unorm) {
    p[c] = uint8_t(std::clamp(v, 0.0, 255.0));
  } else if (k.isFloat) {
    // Outward rounding keeps the float image a superset of the double bound.
    float f = float(v);
    if (!up && double(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
    if (up && double(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
    std::memcpy(p + 4 * c, &f, 4);
  } else {
    const uint32_t u = uint32_t(std::clamp(v, 0.0, 4294967295.0));
    std::memcpy(p + 4 * c, &u, 4);
  }
}

// A float bound rounded outward to float, as the images hold it.
inline double floatOutward(double v, bool up) {
  if (std::isinf(v) || std::isnan(v)) return v;
  float f = float(v);
  if (!up && double(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  if (up && double(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

// The box a written fragment leaves when the pixel held `dst` before.
void writtenBox(const ChannelKind& k, const FragInterval& f, const PixelUpdate& u, const BlendState& blend,
                const Candidate& dst, Candidate& out, uint16_t& classes) {
  out.tagCount = dst.tagCount;
  out.tags = dst.tags;
  if (k.unorm && blend.enabled) {
    // Corners of (src colour, src alpha, dst colour, dst alpha) in [lo, hi]: blending is monotone in
    // each of them separately, so its range over the box is attained at a corner.
    double sLo[4], sHi[4], dLo[4] = {0, 0, 0, 1}, dHi[4] = {0, 0, 0, 1};
    for (int c = 0; c < 4; ++c) {
      sLo[c] = u.dontCare ? 0.0 : f.lo[c] - f.tol[c];
      sHi[c] = u.dontCare ? 1.0 : f.hi[c] + f.tol[c];
    }
    for (int c = 0; c < k.n; ++c) dLo[c] = dst.lo[c] / 255.0, dHi[c] = dst.hi[c] / 255.0;
    double bmin[4], bmax[4];
    for (int c = 0; c < 4; ++c) bmin[c] = 1e300, bmax[c] = -1e300;
    for (int corner = 0; corner < 16; ++corner) {
      float src[4];
      double d[4], o[4];
      for (int c = 0; c < 4; ++c) {
        const bool alpha = c == 3;
        src[c] = float(((corner >> (alpha ? 1 : 0)) & 1) ? sHi[c] : sLo[c]);
        d[c] = ((corner >> (alpha ? 3 : 2)) & 1) ? dHi[c] : dLo[c];
      }
      detail::blend(blend, true, src, d, o);
      for (int c = 0; c < 4; ++c) bmin[c] = std::min(bmin[c], o[c]), bmax[c] = std::max(bmax[c], o[c]);
    }
    for (int c = 0; c < k.n; ++c) {
      // GL 4.6 §17.3.6.1: blending with at least the destination's precision (8 bits): at most five
      // half-LSB errors before the final rounding (tolerance::kBlendUnorm, docs/crosscheck.md).
      int l, h;
      unormRange(bmin[c] - tolerance::kBlendUnorm, bmax[c] + tolerance::kBlendUnorm, l, h);
      out.lo[c] = l, out.hi[c] = h;
    }
    classes |= kBlendPrecision;
    return;
  }
  for (int c = 0; c < k.n; ++c) {
    if (k.unorm) {
      double l = f.lo[c] - f.tol[c], h = f.hi[c] + f.tol[c];
      if (u.dontCare) l = 0.0, h = 1.0;
      int wl, wh, tl, th;
      unormRange(l, h, wl, wh);
      unormRange(f.lo[c], f.hi[c], tl, th);
      // OUTPUT_ROUNDING: the tolerance reached another byte, or one value sits on an exact .5 tie.
      if (tl != wl || th != wh || (tl != th && f.lo[c] == f.hi[c])) classes |= kOutputRounding;
      out.lo[c] = wl, out.hi[c] = wh;
    } else if (k.isFloat) {
      double l = u.dontCare ? -std::numeric_limits<double>::infinity() : f.lo[c] - f.tol[c];
      double h = u.dontCare ? std::numeric_limits<double>::infinity() : f.hi[c] + f.tol[c];
      if (blend.enabled) {
        // Blended float targets are not bounded here (no built-in scene blends into one): any value
        // is accepted and the pixel is classed, so the gap is visible in every report.
        classes |= kBlendPrecision;
        l = -std::numeric_limits<double>::infinity(), h = std::numeric_limits<double>::infinity();
      }
      out.lo[c] = floatOutward(l, false), out.hi[c] = floatOutward(h, true);
    } else {
      // R32UI: the ids the program may output (one id for the built-in programs), never a range
      // from the destination.
      out.lo[c] = u.dontCare ? 0.0 : f.lo[c];
      out.hi[c] = u.dontCare ? 4294967295.0 : f.hi[c];
    }
  }
}

inline bool sameBox(const ChannelKind& k, const Candidate& a, const Candidate& b) {
  for (int c = 0; c < k.n; ++c)
    if (a.lo[c] != b.lo[c] || a.hi[c] != b.hi[c]) return false;
  return true;
}
inline bool boxInside(const ChannelKind& k, const Candidate& a, const Candidate& b) {  // a within b
  for (int c = 0; c < k.n; ++c)
    if (a.lo[c] < b.lo[c] || a.hi[c] > b.hi[c]) return false;
  return true;
}
inline bool sameTags(const Candidate& a, const Candidate& b) {
  if (a.tagCount != b.tagCount) return false;
  for (int i = 0; i < a.tagCount; ++i)
    if (!(a.tags[size_t(i)] == b.tags[size_t(i)])) return false;
  return true;
}
inline bool containsValue(const ChannelKind& k, const Candidate& a, const double v[4]) {
  for (int c = 0; c < k.n; ++c)
    if (!(v[c] >= a.lo[c] && v[c] <= a.hi[c]) && !(std::isnan(v[c]) && std::isnan(a.lo[c]))) return false;
  return true;
}

// The candidate's tag for `key`, or null.
inline const EdgeTag* findTag(const Candidate& c, uint64_t key) {
  for (int i = 0; i < c.tagCount; ++i)
    if (c.tags[size_t(i)].key == key) return &c.tags[size_t(i)];
  return nullptr;
}
// Records the outcome at a shared edge; the oldest tag gives way when full (dropping a constraint
// only makes the candidate more permissive).
inline void setTag(Candidate& c, const EdgeTag& t) {
  for (int i = 0; i < c.tagCount; ++i)
    if (c.tags[size_t(i)].key == t.key) {
      c.tags[size_t(i)] = t;
      return;
    }
  if (c.tagCount == Candidate::kMaxTags) {
    for (int i = 1; i < Candidate::kMaxTags; ++i) c.tags[size_t(i - 1)] = c.tags[size_t(i)];
    --c.tagCount;
  }
  c.tags[c.tagCount++] = t;
}

// Adds `c` to `set` unless a candidate with the same tags already contains its box; drops the ones
// that `c` contains.
void addCandidate(const ChannelKind& k, std::vector<Candidate>& set, const Candidate& c) {
  for (Candidate& o : set)
    if (sameTags(o, c) && boxInside(k, c, o)) {
      o.depth = mergeDepth(o.depth, c.depth);
      return;
    }
  // The same box under other edge assumptions: one candidate that keeps only the assumptions both
  // share (dropping a tag only makes the candidate more permissive).
  for (Candidate& o : set)
    if (sameBox(k, o, c)) {
      Candidate m = o;
      m.tagCount = 0;
      for (int i = 0; i < o.tagCount; ++i)
        for (int j = 0; j < c.tagCount; ++j)
          if (o.tags[size_t(i)] == c.tags[size_t(j)]) m.tags[m.tagCount++] = o.tags[size_t(i)];
      m.depth = mergeDepth(o.depth, c.depth);
      o = m;
      return;
    }
  Candidate added = c;
  for (const Candidate& o : set)
    if (sameTags(o, c) && boxInside(k, o, c)) added.depth = mergeDepth(added.depth, o.depth);
  std::erase_if(set, [&](const Candidate& o) { return sameTags(o, c) && boxInside(k, o, c); });
  set.push_back(added);
}

// One fragment at one pixel of one attachment: every candidate forks into the outcomes legal for
// it, each with its own box; the oracle's value is written as the fast path writes it.
void updatePixel(TextureData& tex, const TargetView& tv, uint32_t layer, int32_t x, int32_t y, const QuadOut (&o)[3],
                 int a, int p, const BlendState& blend, const PixelUpdate& u) {
  const ChannelKind k = kindOf(tex.desc.format);
  Provenance& pv = *tex.prov;
  uint8_t* val = tex.texel(tv.level, layer, uint32_t(x), uint32_t(y));
  uint8_t* lo = pv.lo->texel(tv.level, layer, uint32_t(x), uint32_t(y));
  uint8_t* hi = pv.hi->texel(tv.level, layer, uint32_t(x), uint32_t(y));
  const size_t idx = pv.index(tex, tv.level, layer, uint32_t(x), uint32_t(y));
  uint16_t& cls = pv.classes[tv.level][idx];
  std::vector<Candidate>& stored = pv.candidates[tv.level][idx];
  const uint16_t dstCls = cls;
  const QuadOut* const runs[3] = {&o[0], &o[1], &o[2]};
  const FragInterval f = fragInterval(runs, a, p, !k.unorm && !k.isFloat, u.posTolPx);
  // The fragment's candidates: one per candidate of its forking lookup, else its one interval.
  FragInterval frags[kMaxLookupCandidates];
  int nf = 0;
  for (int li = 0; li < u.lookupCount; ++li) {
    const QuadOut* const lk[3] = {&u.lookupLo[li], &u.lookupHi[li], &o[2]};
    frags[nf++] = fragInterval(lk, a, p, !k.unorm && !k.isFloat, u.posTolPx, li == 0);
  }
  if (nf == 0) frags[nf++] = f;
  if (nf > 1) pv.flags[tv.level][idx] |= kLookupForked;
  if (u.lookupFallback) pv.flags[tv.level][idx] |= kLookupFallback;

  // The set before this fragment: the stored candidates, or the one box of the images. Scratch
  // vectors of the thread: a fragment per pixel would otherwise allocate two.
  thread_local std::vector<Candidate> before, after;
  before.clear();
  after.clear();
  if (stored.empty()) {
    Candidate c;
    for (int ch = 0; ch < k.n; ++ch) c.lo[ch] = loadChannel(k, lo, ch), c.hi[ch] = loadChannel(k, hi, ch);
    c.depth = pv.depth[tv.level][idx];
    before.push_back(c);
  } else {
    before.assign(stored.begin(), stored.end());
  }
  for (Candidate& c : before) c.depth = depthOf(c.depth, u);
  double oldVal[4] = {};
  for (int ch = 0; ch < k.n; ++ch) oldVal[ch] = loadChannel(k, val, ch);

  uint16_t classes = u.classes;
  // The candidate that follows the oracle's own chain of outcomes: it must contain the oracle's value.
  int oracleChain = -1;
  for (size_t ci = 0; ci < before.size(); ++ci) {
    const Candidate& c = before[ci];
    const bool onChain = oracleChain < 0 && containsValue(k, c, oldVal);
    bool covOptions[2] = {u.covered, u.covered};
    int nCov = 1;
    const EdgeTag* tag = u.hasEdge ? findTag(c, u.edge.key) : nullptr;
    if (u.coverTie) {
      if (tag) {
        // The same edge again: the other side must do the opposite, the same side the same.
        covOptions[0] = tag->side == u.edge.side ? tag->covered : !tag->covered;
      } else {
        covOptions[0] = true, covOptions[1] = false, nCov = 2;
      }
    }
    const DepthOutcome dOut = depthOutcome(c.depth, u);
    for (int ki = 0; ki < nCov; ++ki) {
      const bool cov = covOptions[ki];
      bool canWrite, canSkip;
      writeOutcomes(u, dOut, cov, canWrite, canSkip);
      Candidate base = c;
      if (u.hasEdge && u.coverTie) {
        EdgeTag t = u.edge;
        t.covered = cov;
        setTag(base, t);
      }
      const bool oracleOutcomeCov = cov == u.covered;
      if (canSkip) {
        if (onChain && oracleOutcomeCov && !u.keepValue) oracleChain = int(after.size());
        addCandidate(k, after, base);
      }
      for (int fi = 0; canWrite && fi < nf; ++fi) {
        Candidate w;
        writtenBox(k, frags[fi], u, blend, base, w, classes);
        w.depth = writtenDepth(base.depth, u);
        if (onChain && oracleOutcomeCov && u.keepValue && fi == 0) oracleChain = int(after.size());
        addCandidate(k, after, w);
      }
    }
  }
  if (u.keepValue) {
    uint32_t bits[4];
    std::memcpy(bits, o[2].color[a][p].u, sizeof bits);
    writeFragment(tex.desc.format, val, bits, blend);
  }
  double newVal[4] = {};
  for (int ch = 0; ch < k.n; ++ch) newVal[ch] = loadChannel(k, val, ch);
  // The oracle's own value is always legal. Its chain's candidate contains it unless float rounding
  // of the fragment interval lost it; then that candidate (or the first) grows to include it.
  bool found = false;
  for (const Candidate& c : after) found = found || containsValue(k, c, newVal);
  if (!found && !after.empty()) {
    Candidate& c = after[size_t(oracleChain >= 0 && size_t(oracleChain) < after.size() ? oracleChain : 0)];
    for (int ch = 0; ch < k.n; ++ch) c.lo[ch] = std::min(c.lo[ch], newVal[ch]), c.hi[ch] = std::max(c.hi[ch], newVal[ch]);
  }

  // The hull, for the images (later lookups and the reports), and the fallback past the cap.
  Candidate hull = after.empty() ? before[0] : after[0];
  for (const Candidate& c : after)
    for (int ch = 0; ch < k.n; ++ch) hull.lo[ch] = std::min(hull.lo[ch], c.lo[ch]), hull.hi[ch] = std::max(hull.hi[ch], c.hi[ch]);
  CandidateDepth depthHull = after.empty() ? before[0].depth : after[0].depth;
  for (const Candidate& c : after) depthHull = mergeDepth(depthHull, c.depth);
  pv.depth[tv.level][idx] = depthHull;  // read only when the set below is empty
  if (after.size() > kMaxCandidates) {
    pv.flags[tv.level][idx] |= kFallback;
    after.clear();
  } else if (after.size() == 1 && after[0].tagCount == 0) {
    after.clear();
  }
  stored.assign(after.begin(), after.end());
  for (int ch = 0; ch < k.n; ++ch) storeChannel(k, lo, ch, hull.lo[ch], false), storeChannel(k, hi, ch, hull.hi[ch], true);

  // Exact when every candidate is the oracle's value (edge tags may remain for later fragments).
  bool exact = true;
  for (int ch = 0; ch < k.n && exact; ++ch) exact = hull.lo[ch] == newVal[ch] && hull.hi[ch] == newVal[ch];
  if (blend.enabled || u.ambiguous) classes |= dstCls;
  if (!u.keepValue && !u.ambiguous) classes = dstCls;
  cls = exact ? 0 : classes;
}

// Marks the depth records of a pixel's candidates as unknown.
void forgetDepth(TextureData& tex, const TargetView& tv, uint32_t layer, int32_t x, int32_t y) {
  Provenance& pv = *tex.prov;
  const size_t idx = pv.index(tex, tv.level, layer, uint32_t(x), uint32_t(y));
  pv.depth[tv.level][idx].epoch = 0;
  for (Candidate& c : pv.candidates[tv.level][idx]) c.depth.epoch = 0;
}

// Whether a candidate of the pixel, in an attachment the fragment updates, may decide the depth test
// otherwise than the oracle (`oraclePass`): a near tie, or a chain whose stored depth differs from the
// oracle's. Without such an attachment, the oracle's own stored depth decides.
bool depthMayDiffer(const DrawState& ds, const TargetView& tv, uint32_t layer, int32_t x, int32_t y, const PixelUpdate& u,
                    bool oraclePass) {
  auto differs = [&](const CandidateDepth& d) {
    const DepthOutcome o = depthOutcome(depthOf(d, u), u);
    return o.tie || o.pass != oraclePass;
  };
  bool any = false;
  for (int a = 0; a < ds.colorOutputs; ++a) {
    const TextureData* c = tv.color[size_t(a)];
    if (!c || !c->prov) continue;
    any = true;
    const Provenance& pv = *c->prov;
    const size_t idx = pv.index(*c, tv.level, layer, uint32_t(x), uint32_t(y));
    const std::vector<Candidate>& set = pv.candidates[tv.level][idx];
    if (set.empty() && differs(pv.depth[tv.level][idx])) return true;
    for (const Candidate& cand : set)
      if (differs(cand.depth)) return true;
  }
  return !any && differs(CandidateDepth{});
}

}  // namespace

void rasterizeTriangleProvenance(const Scene& scene, const TriSetup& t, const TileRect& tile, PipelineStats& stats) {
  const DrawState& ds = *scene.states[t.drawState];
  const TargetView& tv = scene.target;
  const int32_t x0 = std::max(t.minX, tile.x0), x1 = std::min(t.maxX, tile.x1);
  const int32_t y0 = std::max(t.minY, tile.y0), y1 = std::min(t.maxY, tile.y1);
  if (x0 > x1 || y0 > y1) return;

  // Edge margins (docs/crosscheck.md, EDGE_TIE and CLIP_EDGE): GL's snapping of the implementation
  // judged, plus, for an edge with an endpoint made by clipping, how far GL's float clipping may put
  // that endpoint. A fan diagonal inside a clipped polygon is no boundary: whichever sub-triangle GL
  // makes covers a centre near it exactly once, so it has no margin.
  double margin[3];
  EdgeTag edgeTags[3];
  for (int i = 0; i < 3; ++i) {
    const double len = std::sqrt(double(t.a[i]) * double(t.a[i]) + double(t.b[i]) * double(t.b[i]));
    margin[i] = t.edgeKind[i] == kEdgeInternal ? 0.0 : (scene.edgeMarginSub + t.clipMarginSub[i]) * len;
    // The edge's key: its two snapped endpoints in a canonical order; side: whether this triangle
    // runs it in that order (it lies to the left of its edges).
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    const bool forward = t.vx[j] < t.vx[k] || (t.vx[j] == t.vx[k] && t.vy[j] < t.vy[k]);
    const int p0 = forward ? j : k, p1 = forward ? k : j;
    // The draw is part of the key: GL guarantees identical snapped positions for identical inputs to
    // one program (invariance, Appendix A), not across programs without `invariant gl_Position`.
    uint64_t h = 0x9e3779b97f4a7c15ull;
    for (int64_t v : {int64_t(ds.drawSerial), t.vx[p0], t.vy[p0], t.vx[p1], t.vy[p1]}) {
      h ^= uint64_t(v) + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
      h *= 0xbf58476d1ce4e5b9ull;
      h ^= h >> 31;
    }
    edgeTags[i].key = h;
    edgeTags[i].side = forward ? 0 : 1;
    edgeTags[i].covered = true;
  }
  // Depth gradient per pixel from the plane z = sum(E_i z_i) / 2A.
  const double area = double(t.area2);
  double dzdx = 0.0, dzdy = 0.0;
  for (int i = 0; i < 3; ++i) dzdx += double(t.a[i]) * t.z[i], dzdy += double(t.b[i]) * t.z[i];
  dzdx = dzdx / area * double(kSubpixelOne), dzdy = dzdy / area * double(kSubpixelOne);
  // A vertex made by clipping may sit elsewhere in GL (CLIP_EDGE), and with it the triangle's plane:
  // values are compared over that distance too. Where GL may put it anywhere (a clipped primitive
  // with vertices near FLT_MAX), GL's triangle is unrelated to the oracle's and every value is legal.
  double clipPx = 0.0;
  for (int i = 0; i < 3; ++i) clipPx = std::max(clipPx, t.clipMarginSub[i] / double(kSubpixelOne));
  const bool unbounded = !(clipPx < 65536.0);
  const double posTolPx = tolerance::kSamplePosPx + (unbounded ? 0.0 : clipPx);
  // Depth: the sample shift above or, where GL's snapping grid is coarser, the vertex snapping move
  // (tolerance::vertexSnapPx), plus a clipped vertex's move.
  const double posTolZ = std::max(tolerance::kSamplePosPx, scene.vertexSnapPx) + (unbounded ? 0.0 : clipPx);
  const double tolZ = tolerance::kDepthAbs + (std::fabs(dzdx) + std::fabs(dzdy)) * posTolZ;
  const bool depthTest = ds.depth.test && tv.depth;
  const bool depthWrite = depthTest && ds.depth.write;
  PixelUpdate du{};  // the depth fields shared by the triangle's fragments (depthOutcome)
  du.depthTest = depthTest;
  du.depthWrite = depthWrite;
  du.depthUnbounded = unbounded;
  du.func = ds.depth.func;
  // A program-written depth is no function of the primitive's positions alone: no signature (F11).
  const bool lateDepth = ds.program->writesDepth(), readsZ = ds.program->readsFragDepth();
  const bool monotone = ds.program->monotoneInSamples();
  du.depthSig = lateDepth ? 0 : t.depthSig;
  du.depthEpoch = ds.depthEpoch;

  ShadeProvenance& sp = shadeProvenance();
  Quad quad;
  QuadOut outs[3];  // lower bound, upper bound, value
  QuadOut lookupOuts[2][kMaxLookupCandidates];  // per lookup candidate: lower bound, upper bound
  for (int32_t qy = y0 & ~1; qy <= y1; qy += 2) {
    for (int32_t qx = x0 & ~1; qx <= x1; qx += 2) {
      int64_t e[4][3];
      uint8_t cov = 0, tie = 0, nearMask[4] = {};
      for (int p = 0; p < 4; ++p) {
        const int32_t px = qx + (p & 1), py = qy + (p >> 1);
        bool covered = true, nearEdge = false, nearMiss = true;
        for (int i = 0; i < 3; ++i) {
          e[p][i] = t.a[i] * ((int64_t(px) << kSubpixelBits) + kSubpixelHalf) +
                    t.b[i] * ((int64_t(py) << kSubpixelBits) + kSubpixelHalf) + t.c[i];
          covered = covered && e[p][i] - t.bias[i] >= 0;
          const bool near = margin[i] > 0.0 && std::fabs(double(e[p][i])) <= margin[i];
          nearEdge = nearEdge || near;
          nearMask[p] |= uint8_t(near) << i;
          nearMiss = nearMiss && (margin[i] > 0.0 ? double(e[p][i]) >= -margin[i] : e[p][i] - t.bias[i] >= 0);
        }
        if (px < x0 || px > x1 || py < y0 || py > y1) continue;
        cov |= uint8_t(covered) << p;
        tie |= uint8_t((covered && nearEdge) || (!covered && nearMiss)) << p;
      }
      if (!(cov | tie)) continue;

      float z[4];
      double zTol[4];
      quad.x = qx, quad.y = qy, quad.coverage = cov;
      for (int p = 0; p < 4; ++p) {
        z[p] = quad.z[p] = interpolatePixel(t, ds.varyings, e[p], quad.var[p]);
        zTol[p] = tolZ + std::fabs(double(z[p])) * tolerance::kInterpRel;
      }

      // The program's runs: lower bound, upper bound, value, then the lookup candidates. A program
      // that reads gl_FragCoord.z sees z -/+ its precision in the bound runs (it is monotone in z,
      // Program::readsFragDepth); one that writes depth starts from the interpolated z (F11).
      QuadBatch batch{&quad, nullptr, 1, {}, t.primitiveId, t.layer, t.frontFacing};
      std::memcpy(batch.flat, t.flat, sizeof batch.flat);
      const SampleBound bounds[3] = {SampleBound::Lo, SampleBound::Hi, SampleBound::Value};
      auto setRunDepth = [&](SampleBound bound) {
        for (int p = 0; p < 4; ++p)
          quad.z[p] = !readsZ || bound == SampleBound::Value ? z[p]
                      : bound == SampleBound::Lo             ? float(double(z[p]) - zTol[p])
                                                             : float(double(z[p]) + zTol[p]);
      };
      int lookupRuns = 0;
      auto shade = [&] {
        sp.active = true;
        sp.resetPixels();
        for (int r = 0; r < 3; ++r) {
          sp.bound = bounds[r];
          setRunDepth(bounds[r]);
          outs[r].discard = 0;
          std::memcpy(outs[r].depth, quad.z, sizeof quad.z);
          batch.out = &outs[r];
          ds.program->shadeQuads(batch, ds.ctx);
        }
        // Lookup candidates (docs/crosscheck.md): where a pixel's fragment made exactly one lookup with
        // more than one candidate, the program runs again on each candidate's lower and upper bound
        // (the sampler counted them in the first run). Two or more such lookups keep the hull runs.
        lookupRuns = 0;
        for (int p = 0; p < 4; ++p)
          if (sp.forkingLookups[size_t(p)] == 1) lookupRuns = std::max(lookupRuns, int(sp.lookupCandidates[size_t(p)]));
        for (int li = 0; li < lookupRuns; ++li)
          for (int r = 0; r < 2; ++r) {
            sp.bound = bounds[r];
            sp.candidate = li;
            setRunDepth(bounds[r]);
            lookupOuts[r][li].discard = 0;
            std::memcpy(lookupOuts[r][li].depth, quad.z, sizeof quad.z);
            batch.out = &lookupOuts[r][li];
            ds.program->shadeQuads(batch, ds.ctx);
          }
        sp.candidate = -1;
        sp.active = false;
        sp.bound = SampleBound::Value;
        setRunDepth(SampleBound::Value);
      };
      if (lateDepth) {
        // gl_FragDepth decides the test, so shade first. The written depth is the program's output:
        // its legal values are those of its runs (every run's depth, clamped, F11), so the depth
        // precision is the runs' spread around the value run's depth instead of the interpolation's.
        shade();
        for (int p = 0; p < 4; ++p) {
          z[p] = clampFragDepth(outs[2].depth[p]);
          double spread = 0.0;
          for (int r = 0; r < 2; ++r) spread = std::max(spread, std::fabs(double(clampFragDepth(outs[r].depth[p])) - z[p]));
          for (int li = 0; li < lookupRuns; ++li)
            for (int r = 0; r < 2; ++r)
              spread = std::max(spread, std::fabs(double(clampFragDepth(lookupOuts[r][li].depth[p])) - z[p]));
          zTol[p] = spread;
        }
      }

      // A discarded pixel reaches no depth test (GL 4.6 §15.2); only the late test can know that.
      const uint8_t testable = lateDepth ? uint8_t((cov | tie) & ~(outs[0].discard & outs[1].discard & outs[2].discard)) : uint8_t(cov | tie);
      uint8_t pass = cov | tie, nearDepth = 0;
      float zStored[4] = {};
      if (depthTest) {
        for (int p = 0; p < 4; ++p) {
          if (!((cov | tie) >> p & 1)) continue;
          const float stored = loadDepth(*tv.depth, tv.level, t.layer, qx + (p & 1), qy + (p >> 1));
          zStored[p] = stored;
          if (!depthPasses(ds.depth.func, z[p], stored)) pass &= uint8_t(~(1u << p));
          if (!(testable >> p & 1)) continue;
          // Ambiguous when some candidate's chain may decide the test otherwise (depthOutcome).
          PixelUpdate q = du;
          q.z = z[p], q.zStored = stored, q.zTol = zTol[p];
          if (depthMayDiffer(ds, tv, t.layer, qx + (p & 1), qy + (p >> 1), q, pass >> p & 1))
            nearDepth |= uint8_t(1u << p);
        }
      }
      const uint8_t valueWrite = cov & pass;
      uint8_t ambiguous = (tie & (pass | nearDepth)) | (cov & nearDepth);
      if (lateDepth) {
        // Shaded whatever the test says: count as the fast path does (covered pixels, late test).
        const uint8_t kept = uint8_t(cov & ~outs[2].discard);
        stats.fragments_depth_failed += quadPixels(uint32_t(kept & ~pass));
        if (cov) {
          stats.quads_shaded += 1;
          stats.fragments_shaded += quadPixels(uint32_t(cov));
          stats.helper_invocations += 4 - quadPixels(uint32_t(cov));
          stats.fragments_discarded += quadPixels(uint32_t(cov & outs[2].discard));
        }
      } else {
        stats.fragments_depth_failed += quadPixels(uint32_t(cov & ~pass));
      }
      if (!(valueWrite | ambiguous)) continue;
      if (!lateDepth) shade();
      // ALPHA_TEST (docs/crosscheck.md): the runs bound every legal sampled value and the programs are
      // monotone, so a pixel that some runs discard and others keep may go either way in GL.
      uint8_t discardAny = uint8_t(outs[0].discard | outs[1].discard | outs[2].discard);
      uint8_t discardAll = uint8_t(outs[0].discard & outs[1].discard & outs[2].discard);
      for (int li = 0; li < lookupRuns; ++li)
        for (int r = 0; r < 2; ++r) {
          discardAny = uint8_t(discardAny | lookupOuts[r][li].discard);
          discardAll = uint8_t(discardAll & lookupOuts[r][li].discard);
        }
      const uint8_t discardTie = uint8_t(discardAny & ~discardAll);
      ambiguous = uint8_t(ambiguous | (discardTie & (valueWrite | ambiguous)));


      if (!lateDepth) {
        stats.quads_shaded += 1;
        stats.fragments_shaded += quadPixels(uint32_t(valueWrite));
        stats.helper_invocations += 4 - quadPixels(uint32_t(valueWrite));
        stats.fragments_discarded += quadPixels(uint32_t(valueWrite & outs[2].discard));
      }
      for (int p = 0; p < 4; ++p) {
        const bool keep = (valueWrite >> p & 1) && !(outs[2].discard >> p & 1);
        const bool amb = ambiguous >> p & 1;
        if (!keep && !amb) continue;
        const int32_t x = qx + (p & 1), y = qy + (p >> 1);
        if (keep && depthWrite) storeDepth(*tv.depth, tv.level, t.layer, x, y, z[p]);
        PixelUpdate u;
        u.covered = cov >> p & 1;
        u.coverTie = tie >> p & 1;
        u.depthPass = pass >> p & 1;
        u.depthTie = nearDepth >> p & 1;
        u.discarded = outs[2].discard >> p & 1;
        u.discardTie = discardTie >> p & 1;
        u.keepValue = keep;
        u.ambiguous = amb;
        // A program that is not monotone in what it samples (Program::monotoneInSamples) cannot be
        // bounded by its runs on the interval images: where it read a texel carrying an interval, every
        // output is legal (classed INPUT_INTERVAL); where it read only exact texels its runs agree.
        const bool freeInput = !monotone && (sp.classes[size_t(p)] & (kInputInterval | kBcInterpolant)) != 0;
        u.dontCare = sp.dontCare[size_t(p)] || unbounded || freeInput;
        u.posTolPx = posTolPx;
        u.depthTest = du.depthTest, u.depthWrite = du.depthWrite, u.depthUnbounded = du.depthUnbounded;
        u.func = du.func, u.depthSig = du.depthSig, u.depthEpoch = du.depthEpoch;
        u.z = z[p], u.zStored = zStored[p], u.zTol = zTol[p];
        u.lookupCount = sp.forkingLookups[size_t(p)] == 1 ? int(sp.lookupCandidates[size_t(p)]) : 0;
        u.lookupLo = lookupOuts[0];
        u.lookupHi = lookupOuts[1];
        u.lookupFallback = sp.forkingLookups[size_t(p)] > 1 || sp.lookupFallback[size_t(p)];
        // A tie near exactly one edge that is no clipped edge is correlated with the triangle on the
        // other side of that edge (EdgeTag).
        const uint8_t nm = nearMask[p];
        // nm has a bit per edge (0..2); the clamp only tells the compiler the index stays in range.
        const int ei = std::min(std::countr_zero(uint32_t(nm)), 2);
        u.hasEdge = u.coverTie && std::popcount(uint32_t(nm)) == 1 && t.edgeKind[ei] == kEdgeOriginal;
        if (u.hasEdge) u.edge = edgeTags[ei];
        uint16_t tieClass = 0;
        if (u.coverTie)
          for (int i = 0; i < 3; ++i)
            if (nm >> i & 1) tieClass |= t.edgeKind[i] == kEdgeClipped ? kClipEdge : kEdgeTie;
        u.classes = uint16_t(sp.classes[size_t(p)] | (sp.dontCare[size_t(p)] ? kOobFetch : 0) | tieClass |
                             ((nearDepth >> p & 1) || readsZ ? kDepthNearEqual : 0) | (u.discardTie ? kAlphaTest : 0));
        for (int a = 0; a < ds.colorOutputs; ++a) {
          TextureData* c = tv.color[size_t(a)];
          if (!c || !c->prov) continue;
          switch (c->desc.format) {
            case Format::RGBA8:
            case Format::R8:
            case Format::RG32F:
            case Format::RGBA32F:
            case Format::R32UI: updatePixel(*c, tv, t.layer, x, y, outs, a, p, ds.blend, u); break;
            default: break;
          }
        }
        // Attachments the program has no output for are not forked here: a depth this fragment may
        // write leaves their chains' depth records unknown (the oracle's depth decides for them).
        if (depthWrite)
          for (int a = ds.colorOutputs; a < kMaxColorAttachments; ++a)
            if (TextureData* c = tv.color[size_t(a)]; c && c->prov) forgetDepth(*c, tv, t.layer, x, y);
        if (keep) ++stats.pixels_written;
      }
    }
  }
}

}  // namespace tessera::detail
