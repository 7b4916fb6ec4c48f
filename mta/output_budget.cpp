#include "mta/output_budget.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "base/error.h"
#include "base/resource_limits.h"

namespace tessera::mta {

namespace {

// 10^k for 0 <= k <= 22: every such power is exact in double.
double exactPow10(int k) {
  double p = 1.0;
  for (int i = 0; i < k; ++i) p *= 10.0;
  return p;
}

int64_t floorDiv(int64_t a, int64_t b) { return a / b - ((a % b != 0) && ((a < 0) != (b < 0))); }

// A backstop for the search; galloping and bisection over the grid take at most about 2 · log2(4,500).
constexpr uint32_t kMaxPlans = 64;

}  // namespace

double dMinGridValue(int64_t index) {
  index = std::clamp(index, kDMinGridFirst, kDMinGridLast);
  const int64_t e = floorDiv(index, 90) - 1;
  const double m = double(10 + (index - floorDiv(index, 90) * 90));
  return e >= 0 ? m * exactPow10(int(e)) : m / exactPow10(int(-e));
}

int64_t dMinGridIndexAbove(double d) {
  if (!(d >= dMinGridValue(kDMinGridFirst))) return kDMinGridFirst;  // also NaN: the finest grid value
  int64_t lo = kDMinGridFirst, hi = kDMinGridLast + 1;               // value(lo) <= d < value(hi)
  if (dMinGridValue(kDMinGridLast) <= d) return hi;
  while (hi - lo > 1) {
    const int64_t mid = lo + (hi - lo) / 2;
    (dMinGridValue(mid) <= d ? lo : hi) = mid;
  }
  return hi;
}

std::string formatDMin(double d) {
  char buf[64];
  for (int p = 1; p <= 17; ++p) {
    std::snprintf(buf, sizeof buf, "%.*g", p, d);
    if (std::strtod(buf, nullptr) == d) break;
  }
  return buf;
}

std::string groupThousands(uint64_t n) {
  std::string s = std::to_string(n), out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (i && (s.size() - i) % 3 == 0) out += ',';
    out += s[i];
  }
  return out;
}

std::string byteSizeArgument(uint64_t bytes) {
  static const char* const kUnits[] = {"TiB", "GiB", "MiB", "KiB"};
  for (int u = 0; u < 4; ++u) {
    const uint64_t unit = uint64_t(1) << (10 * (4 - u));
    if (bytes >= unit && bytes % unit == 0) return std::to_string(bytes / unit) + kUnits[u];
  }
  return std::to_string(bytes);
}

DMinFit fitDMin(const Scene& scene, const BuildParams& params, uint64_t maxBytes,
                const OutputEstimate* finestEstimate) {
  DMinFit r;
  const double finest = resolveDMin(scene, params);
  // Past this distance the whole scene's diagonal needs a quarter texel: no coarser tree is smaller.
  const double f = double(params.screenWidth) / (2.0 * params.effectiveTanHalfFov() * params.tau);
  const double dCap = std::max(finest, 4.0 * sceneDiagonal(scene) * f);
  std::map<int64_t, uint64_t> bytesAt;  // grid index (finestIndex for finest) -> estimate
  const int64_t k0 = dMinGridIndexAbove(finest), finestIndex = k0 - 1;
  BuildPlan plan;
  OutputEstimate est;
  auto evaluate = [&](double d) {
    BuildParams p = params;
    p.dMin = d;
    plan = planBuild(scene, p);
    est = estimateOutput(plan);
    ++r.plans;
    return est.totalBytes <= maxBytes;
  };
  auto keep = [&](double d) { r.found = true, r.dMin = d, r.plan = std::move(plan), r.estimate = est; };
  if (finestEstimate) {
    bytesAt[finestIndex] = finestEstimate->totalBytes;
  } else {
    const bool fits = evaluate(finest);
    bytesAt[finestIndex] = est.totalBytes;
    if (fits) {
      keep(finest);
      return r;
    }
  }
  // Gallop: k0, k0 + 1, k0 + 3, k0 + 7, ... until one fits.
  int64_t lo = finestIndex, hi = lo;  // hi > lo once a candidate fits (indices may be negative)
  for (int64_t i = k0;; i = k0 + 2 * (i - k0) + 1) {
    if (i > kDMinGridLast) i = kDMinGridLast;
    if (r.plans >= kMaxPlans || i <= lo) break;
    const double d = dMinGridValue(i);
    const bool fits = evaluate(d);
    bytesAt[i] = est.totalBytes;
    if (fits) {
      hi = i;
      keep(d);
      break;
    }
    lo = i;
    // One atlas per tree is the smallest tree; past dCap nothing changes either.
    if (est.nodes == plan.meta.trees.size() || d >= dCap) break;
  }
  if (!r.found) {  // nothing fits: report the coarsest plan tried
    r.plan = std::move(plan), r.estimate = est, r.dMin = dMinGridValue(lo);
    return r;
  }
  // Bisect: lo does not fit (or is finest), hi fits.
  while (hi - lo > 1 && r.plans < kMaxPlans) {
    const int64_t mid = lo + (hi - lo) / 2;
    const double d = dMinGridValue(mid);
    const bool fits = evaluate(d);
    bytesAt[mid] = est.totalBytes;
    if (fits)
      hi = mid, keep(d);
    else
      lo = mid;
  }
  if (hi - lo > 1)
    throw Error("mta: the search for a d_min that fits did not converge in " + std::to_string(kMaxPlans) + " plans");
  r.finerDMin = lo == finestIndex ? finest : dMinGridValue(lo);
  r.finerBytes = bytesAt.at(lo);
  return r;
}

void refuseIfTooBig(const Scene& scene, const BuildParams& params, const BuildPlan& plan,
                    const OutputEstimate& estimate, const OutputGuard& guard) {
  if (!guard.maxBytes || estimate.totalBytes <= guard.maxBytes) return;
  const BuildStats& s = plan.meta.stats;
  auto approx = [](double d) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", d);
    return std::string(buf);
  };
  std::string m = "mta build: the tree would take " + formatBytes(estimate.totalBytes) + " (" +
                  groupThousands(estimate.nodes) + " nodes, " + groupThousands(estimate.leaves) + " leaves at d_min " +
                  approx(s.dMinRequested);
  if (s.dMinUsed != s.dMinRequested) m += ", raised to " + approx(s.dMinUsed) + " for critical triangles";
  m += ") but --max-output is " + formatBytes(guard.maxBytes) + guard.maxReason + "; ";
  BuildParams p = params;
  p.dMin = s.dMinRequested;
  const DMinFit fit = fitDMin(scene, p, guard.maxBytes, &estimate);
  if (fit.found)
    m += "d_min " + formatDMin(fit.dMin) + " fits (" + formatBytes(fit.estimate.totalBytes) + ", " +
         groupThousands(fit.estimate.nodes) + " nodes): pass --d-min " + formatDMin(fit.dMin) + ", or --fit " +
         byteSizeArgument(guard.maxBytes) + ", or raise --max-output";
  else
    m += "no d_min fits: the smallest tree tried, at d_min " + formatDMin(fit.dMin) + ", takes " +
         formatBytes(fit.estimate.totalBytes) + " (" + groupThousands(fit.estimate.nodes) +
         " nodes; geometry and tables " + formatBytes(fit.estimate.metadataBytes) + ", original images " +
         formatBytes(fit.estimate.originalBytes) + "): raise --max-output";
  throw Error(m);
}

}  // namespace tessera::mta
