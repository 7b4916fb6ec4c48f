#include "verify/visibility_check.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "verify/window_geometry.h"

namespace tessera::verify {

namespace {

constexpr int32_t kCell = 8;  // px; the grid only holds cells that contain a mismatching pixel
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Candidate {
  uint32_t triangle;
  bool definite;   // definitely covers the centre (and passes the clear depth)
  bool nearEdge;   // may cover it because an edge is within edgeEpsilon
  bool nearClear;  // may fail against the clear depth within the depth bound
  bool inside;     // inside in double
  double depth, tol, distance;
};

// Triangles whose box (grown by edgeEpsilon) touches each needed cell.
class CellGrid {
 public:
  CellGrid(const VisibilityScene& s, const std::vector<size_t>& pixels, double eps) {
    cols_ = (s.width + kCell - 1) / kCell;
    rows_ = (s.height + kCell - 1) / kCell;
    slot_.assign(size_t(cols_) * size_t(rows_), -1);
    for (size_t p : pixels) {
      const size_t c = cellOf(int32_t(p % size_t(s.width)), int32_t(p / size_t(s.width)));
      if (slot_[c] < 0) slot_[c] = int32_t(lists_.size()), lists_.emplace_back();
    }
    for (uint32_t i = 0; i < s.triangles.size(); ++i) {
      const WindowTriangle& t = s.triangles[i];
      const double lox = std::min({t.x[0], t.x[1], t.x[2]}) - eps, hix = std::max({t.x[0], t.x[1], t.x[2]}) + eps;
      const double loy = std::min({t.y[0], t.y[1], t.y[2]}) - eps, hiy = std::max({t.y[0], t.y[1], t.y[2]}) + eps;
      // Pixel centres are at k + 1/2; clamp to the target before converting to int.
      const int32_t x0 = int32_t(std::clamp(std::floor(lox - 0.5), 0.0, double(s.width - 1)));
      const int32_t x1 = int32_t(std::clamp(std::ceil(hix - 0.5), 0.0, double(s.width - 1)));
      const int32_t y0 = int32_t(std::clamp(std::floor(loy - 0.5), 0.0, double(s.height - 1)));
      const int32_t y1 = int32_t(std::clamp(std::ceil(hiy - 0.5), 0.0, double(s.height - 1)));
      if (hix < 0.5 || lox > s.width - 0.5 || hiy < 0.5 || loy > s.height - 0.5) continue;
      for (int32_t cy = y0 / kCell; cy <= y1 / kCell; ++cy)
        for (int32_t cx = x0 / kCell; cx <= x1 / kCell; ++cx) {
          const int32_t slot = slot_[size_t(cy) * size_t(cols_) + size_t(cx)];
          if (slot >= 0) lists_[size_t(slot)].push_back(i);
        }
    }
  }
  const std::vector<uint32_t>& at(int32_t x, int32_t y) const { return lists_[size_t(slot_[cellOf(x, y)])]; }

 private:
  size_t cellOf(int32_t x, int32_t y) const { return size_t(y / kCell) * size_t(cols_) + size_t(x / kCell); }
  int32_t cols_ = 0, rows_ = 0;
  std::vector<int32_t> slot_;
  std::vector<std::vector<uint32_t>> lists_;
};

enum class Verdict { Edge, DepthTie, Reference, Unexplained };

struct PixelVerdict {
  Verdict verdict = Verdict::Unexplained;
  std::string reason;
  double edgeUsed = 0, tieUsed = 0;  // how much of each bound the explanation needed
  double nearestEdge = kInf;
};

class MismatchJudge {
 public:
  MismatchJudge(const VisibilityScene& s, const VisibilityOptions& o) : s_(s), eps_(o.edgeEpsilon) {}

  PixelVerdict judge(const std::vector<uint32_t>& near, int32_t x, int32_t y, uint32_t oid, uint32_t oprim) {
    PixelVerdict j;
    gather(near, x, y, j.nearestEdge);
    const bool oracleBackground = oid == s_.clearIds[0] && oprim == s_.clearIds[1];
    if (oracleBackground) return judgeBackground(j);
    return judgeTriangle(j, oid, oprim);
  }

 private:
  void gather(const std::vector<uint32_t>& near, int32_t x, int32_t y, double& nearestEdge) {
    cands_.clear();
    const double px = x + 0.5, py = y + 0.5;
    for (uint32_t i : near) {
      const WindowTriangle& t = s_.triangles[i];
      const Rect& r = s_.draws[t.draw].clampRect;
      if (x < r.x || y < r.y || x >= r.x + r.w || y >= r.y + r.h) continue;  // the draw cannot touch it
      const PointQuery q = queryPoint(t, px, py);
      nearestEdge = std::min(nearestEdge, q.boundaryDistance);
      Candidate c{i, false, false, false, q.inside, q.depth, depthTolerance(q.gradient, eps_), q.boundaryDistance};
      const bool edge = q.boundaryDistance <= eps_;
      if (t.culled) {
        if (!edge) continue;  // a culled triangle can only reappear as a sliver along its edges
        c.nearEdge = true;
      } else if (q.inside && !edge) {
        c.definite = true;
      } else if (edge) {
        c.nearEdge = true;
      } else {
        continue;
      }
      // The first fragment must pass against the cleared depth: LESS needs z < clear.
      const bool lequal = s_.draws[t.draw].depthFunc == CompareFunc::LEqual;
      const double zc = s_.clearDepth;
      const bool surelyFails = lequal ? c.depth - c.tol > zc : c.depth - c.tol >= zc;
      const bool surelyPasses = lequal ? c.depth + c.tol <= zc : c.depth + c.tol < zc;
      if (surelyFails) continue;
      if (!surelyPasses) c.definite = false, c.nearClear = true;
      cands_.push_back(c);
    }
  }

  // Does the double reference let this triangle's first fragment pass against the cleared depth?
  bool passesClear(const Candidate& c) const {
    const bool lequal = s_.draws[s_.triangles[c.triangle].draw].depthFunc == CompareFunc::LEqual;
    return lequal ? c.depth <= s_.clearDepth : c.depth < s_.clearDepth;
  }

  PixelVerdict& judgeBackground(PixelVerdict& j) const {
    bool edge = false, tie = false;
    for (const Candidate& c : cands_) {
      if (c.definite) {
        j.reason = "background in the oracle, but triangle " + describe(c) + " covers the pixel centre";
        return j;
      }
      if (!c.inside) continue;  // outside in double too: nothing to explain
      if (c.nearClear && !(c.nearEdge && passesClear(c))) {
        tie = true;  // its depth is within the bound of the cleared depth: failing the test is legal
      } else if (c.nearEdge) {
        edge = true;  // inside in double, yet not drawn: snapping took the pixel centre from it
        j.edgeUsed = std::max(j.edgeUsed, c.distance);
      }
    }
    j.verdict = edge ? Verdict::Edge : tie ? Verdict::DepthTie : Verdict::Reference;
    return j;
  }

  PixelVerdict& judgeTriangle(PixelVerdict& j, uint32_t oid, uint32_t oprim) const {
    const Candidate* a = nullptr;
    for (const Candidate& c : cands_) {
      const WindowTriangle& t = s_.triangles[c.triangle];
      if (t.objectId != oid || t.primitiveId != oprim) continue;
      if (!a || (c.definite && !a->definite) || (c.definite == a->definite && c.depth < a->depth)) a = &c;
    }
    if (!a) {
      j.reason = "no triangle with the oracle's ids lies within edgeEpsilon of the pixel centre";
      return j;
    }
    // Outside in double, yet drawn: snapping moved an edge over the centre. Failing the cleared depth
    // in double, yet drawn: within the depth bound.
    bool edge = a->nearEdge && !a->inside, tie = a->nearClear && !passesClear(*a);
    if (edge) j.edgeUsed = a->distance;
    for (const Candidate& b : cands_) {
      const WindowTriangle& t = s_.triangles[b.triangle];
      if (t.objectId == oid && t.primitiveId == oprim) continue;
      if (b.depth > a->depth) continue;  // farther: the oracle's choice is consistent with it
      if (b.definite) {
        const double gap = a->depth - b.depth;
        if (gap > a->tol + b.tol) {
          j.reason = "triangle " + describe(b) + " covers the centre and is nearer by " + std::to_string(gap) +
                     " (bound " + std::to_string(a->tol + b.tol) + ")";
          return j;
        }
        tie = true;  // nearer or exactly as near: which one wins is decided by rounding
        j.tieUsed = std::max(j.tieUsed, gap);
      } else if (b.inside && b.nearEdge) {
        // Nearer and inside in double, yet not shown: either it lost the depth test within the bound
        // (steep slivers have a large one) or snapping took the pixel centre from it.
        const double gap = a->depth - b.depth;
        if (gap <= a->tol + b.tol) {
          tie = true;
          j.tieUsed = std::max(j.tieUsed, gap);
        } else {
          edge = true;
          j.edgeUsed = std::max(j.edgeUsed, b.distance);
        }
      }
    }
    j.verdict = edge ? Verdict::Edge : tie ? Verdict::DepthTie : Verdict::Reference;
    return j;
  }

  std::string describe(const Candidate& c) const {
    const WindowTriangle& t = s_.triangles[c.triangle];
    return "(object " + std::to_string(t.objectId) + ", primitive " + std::to_string(t.primitiveId) + ", draw " +
           std::to_string(t.draw) + ", depth " + std::to_string(c.depth) + ", edge distance " +
           std::to_string(c.distance) + " px)";
  }

  const VisibilityScene& s_;
  double eps_;
  std::vector<Candidate> cands_;
};

}  // namespace

VisibilityResult classifyVisibility(const VisibilityScene& scene, const EmbreeImage& cast, const IdImages& oracle,
                                    const VisibilityOptions& options) {
  if (oracle.width != scene.width || oracle.height != scene.height)
    throw Error("visibility: the oracle images are " + std::to_string(oracle.width) + "x" +
                std::to_string(oracle.height) + " but the presented target is " + std::to_string(scene.width) + "x" +
                std::to_string(scene.height));
  const size_t n = size_t(scene.width) * size_t(scene.height);
  VisibilityResult r;
  r.width = scene.width, r.height = scene.height;
  r.draws = scene.draws.size();
  r.triangles = cast.triangles;
  r.primitivesClipped = scene.primitivesClipped;
  r.pixels = n;
  r.edgeEpsilon = options.edgeEpsilon;
  r.embreeVersion = cast.version, r.embreeIsa = cast.isa;
  r.buildMs = cast.buildMs, r.castMs = cast.castMs;

  // The cast as ID images, in the oracle's layout.
  IdImages& e = r.embree;
  e.width = scene.width, e.height = scene.height;
  e.object.assign(n, scene.clearIds[0]);
  e.primitive.assign(n, scene.clearIds[1]);
  e.depth.assign(n, scene.clearDepth);
  for (size_t p = 0; p < n; ++p) {
    const uint32_t tri = cast.triangle[p];
    if (tri == kNoHit) continue;
    const WindowTriangle& t = scene.triangles[tri];
    e.object[p] = t.objectId;
    e.primitive[p] = t.primitiveId;
    const double px = double(p % size_t(scene.width)) + 0.5, py = double(p / size_t(scene.width)) + 0.5;
    e.depth[p] = float(queryPoint(t, px, py).depth);
  }

  const bool haveDepth = oracle.depth.size() == n;
  std::vector<size_t> mismatched;
  for (size_t p = 0; p < n; ++p) {
    const uint32_t tri = cast.triangle[p];
    if (oracle.object[p] == e.object[p] && oracle.primitive[p] == e.primitive[p]) {
      ++r.matching;
      if (haveDepth && tri != kNoHit) {
        const WindowTriangle& t = scene.triangles[tri];
        const PointQuery q =
            queryPoint(t, double(p % size_t(scene.width)) + 0.5, double(p / size_t(scene.width)) + 0.5);
        const double diff = std::fabs(double(oracle.depth[p]) - q.depth);
        ++r.depthChecked;
        r.depthMaxAbsDiff = std::max(r.depthMaxAbsDiff, diff);
        if (diff > depthTolerance(q.gradient, options.edgeEpsilon)) ++r.depthOutOfTolerance;
      }
      continue;
    }
    mismatched.push_back(p);
    const bool oracleBg = oracle.object[p] == scene.clearIds[0] && oracle.primitive[p] == scene.clearIds[1];
    if (oracleBg != (tri == kNoHit)) ++r.backgroundMismatches;
  }
  r.mismatches = mismatched.size();
  r.exactMatchPercent = n ? 100.0 * double(r.matching) / double(n) : 100.0;
  if (mismatched.empty()) return r;

  const CellGrid grid(scene, mismatched, options.edgeEpsilon);
  MismatchJudge judge(scene, options);
  for (size_t p : mismatched) {
    const int32_t x = int32_t(p % size_t(scene.width)), y = int32_t(p / size_t(scene.width));
    const PixelVerdict j = judge.judge(grid.at(x, y), x, y, oracle.object[p], oracle.primitive[p]);
    switch (j.verdict) {
      case Verdict::Edge:
        ++r.explainedEdge;
        r.maxEdgeDistanceUsed = std::max(r.maxEdgeDistanceUsed, j.edgeUsed);
        break;
      case Verdict::DepthTie:
        ++r.explainedDepthTie;
        r.maxDepthTieUsed = std::max(r.maxDepthTieUsed, j.tieUsed);
        break;
      case Verdict::Reference:
        ++r.explainedReference;
        break;
      case Verdict::Unexplained:
        ++r.unexplained;
        if (r.firstUnexplained.size() < options.maxListed) {
          UnexplainedPixel u;
          u.x = x, u.y = y;
          u.oracleObject = oracle.object[p], u.oraclePrimitive = oracle.primitive[p];
          u.embreeObject = e.object[p], u.embreePrimitive = e.primitive[p];
          u.oracleDepth = haveDepth ? double(oracle.depth[p]) : std::numeric_limits<double>::quiet_NaN();
          u.embreeDepth = cast.triangle[p] == kNoHit ? std::numeric_limits<double>::quiet_NaN() : double(e.depth[p]);
          u.edgeDistance = j.nearestEdge;
          u.reason = j.reason;
          r.firstUnexplained.push_back(u);
        }
        break;
    }
  }
  return r;
}

}  // namespace tessera::verify
