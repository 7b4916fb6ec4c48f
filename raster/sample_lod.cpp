// Level of detail of the oracle's texture lookups (see sample.h for the rules; this file says why and
// where GL says so): the sampler's LOD parameters quantized once, log2Fixed, and lambda from the scale
// factor rho (GL 4.6 §8.14.1), all in 8.8 fixed point and integer arithmetic. The lookups that use
// lambda are in sample.cpp; the LOD range of provenance mode is in sample_interval.cpp.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "raster/sample.h"
#include "raster/sample_detail.h"

namespace tessera {

using sample_detail::finishLambda;
using sample_detail::lambdaBaseFromRho2;
using sample_detail::roundHalfEven;

namespace {

// A float LOD parameter to 8.8 fixed point, round half to even (docs/spec-choices.md T3: quantized once).
// NaN maps to 0; the range is clamped to [kLodMinusInf, kLodMax].
int32_t quantizeLod(float v) {
  if (std::isnan(v)) return 0;
  double x = double(v) * 256.0;  // exact
  if (x < double(kLodMinusInf)) x = double(kLodMinusInf);
  if (x > double(kLodMax)) x = double(kLodMax);
  return int32_t(roundHalfEven(x));  // |x| <= 2^20
}

// 64x64 -> 128-bit product of two Q1.62 numbers, returned as Q2.62 (floor). Both branches compute
// the same exact integer; the portable one serves compilers without __int128.
inline uint64_t mulQ62(uint64_t a, uint64_t b) {
#if defined(__SIZEOF_INT128__)
  return uint64_t((static_cast<unsigned __int128>(a) * b) >> 62);
#else
  const uint64_t aLo = a & 0xffffffffu, aHi = a >> 32, bLo = b & 0xffffffffu, bHi = b >> 32;
  const uint64_t ll = aLo * bLo, lh = aLo * bHi, hl = aHi * bLo, hh = aHi * bHi;
  const uint64_t mid = (ll >> 32) + (lh & 0xffffffffu) + (hl & 0xffffffffu);
  const uint64_t hi = hh + (lh >> 32) + (hl >> 32) + (mid >> 32);
  const uint64_t lo = (mid << 32) | (ll & 0xffffffffu);
  return (hi << 2) | (lo >> 62);
#endif
}

// The first `steps` bits of log2(m) for m in [1, 2) in Q1.62, bit by bit: square m; if m^2 >= 2 the
// next bit is 1 and m^2 is halved (log2Fixed says what the bits are and why `steps` of them suffice).
inline int64_t log2Bits(uint64_t m, int steps) {
  int64_t f = 0;
  for (int k = 0; k < steps; ++k) {
    m = mulQ62(m, m);  // Q2.62, < 4
    f <<= 1;
    if (m >= (uint64_t(1) << 63)) {
      f |= 1;
      m >>= 1;
    }
  }
  return f;
}

// lambda needs log2Bits(m, 8) per quad lookup: 8 dependent 128-bit products. The same value comes
// from a table of thresholds: log2Bits(., 8) is monotone in m (every squaring is non-decreasing in
// m, and where two mantissas first get different bits the larger mantissa gets the 1, which
// decides the order of the results), so log2Bits(m, 8) = the largest k with kThreshold[k] <= m,
// where kThreshold[k] is the least mantissa whose loop value is at least k, found once by bisection
// with the loop itself. Same bits by construction; tests/raster/test_sample.cpp compares the two
// forms at every threshold, on each side of it, and at random mantissas.
constexpr int kLambdaSteps = kLodFracBits;  // log2Fixed(rho^2, 7) takes 7 + 1 steps
// The table is searched in one step, not by bisection: the mantissas [1, 2) are cut into 4096 equal
// buckets by their top 12 fraction bits, and bucket b records k(b) = log2Bits of its least mantissa.
// A bucket is 2^-12 wide and consecutive thresholds lie about 2^(1/256) - 1 > 2^-9 apart, so a
// bucket holds at most one threshold (the constructor checks this) and log2Bits(m) is k(b) or
// k(b) + 1, decided by one comparison with the next threshold.
constexpr int kBucketBits = 12;
struct Log2Thresholds {
  uint64_t t[(1 << kLambdaSteps) + 1];  // t[256] = 2.0: above every mantissa, so never passed
  uint8_t bucket[1 << kBucketBits];
  Log2Thresholds() {
    constexpr uint64_t kOne = uint64_t(1) << 62, kTwo = uint64_t(1) << 63;
    t[0] = kOne;
    for (int k = 1; k < (1 << kLambdaSteps); ++k) {
      uint64_t lo = t[k - 1], hi = kTwo - 1;  // log2Bits(hi) = 255 >= k
      while (lo < hi) {  // the least m in [lo, hi] with log2Bits(m) >= k
        const uint64_t mid = lo + (hi - lo) / 2;
        if (log2Bits(mid, kLambdaSteps) >= k) {
          hi = mid;
        } else {
          lo = mid + 1;
        }
      }
      t[k] = lo;
    }
    t[1 << kLambdaSteps] = kTwo;
    int k = 0;
    for (uint64_t b = 0; b < (uint64_t(1) << kBucketBits); ++b) {
      const uint64_t start = kOne + (b << (62 - kBucketBits)), end = start + (uint64_t(1) << (62 - kBucketBits));
      while (t[k + 1] <= start) ++k;
      bucket[b] = uint8_t(k);
      // At most one threshold inside the bucket; otherwise the one-comparison search would be wrong.
      if (k + 2 <= (1 << kLambdaSteps) && t[k + 1] < end && t[k + 2] < end) std::abort();
    }
  }
};

inline int64_t log2Bits8(uint64_t m) {
  static const Log2Thresholds table;
  const int k = table.bucket[(m >> (62 - kBucketBits)) & ((1u << kBucketBits) - 1)];
  return k + (table.t[k + 1] <= m ? 1 : 0);
}

}  // namespace

namespace sample_detail {
int64_t log2BitsLoop(uint64_t m, int steps) { return log2Bits(m, steps); }
int64_t log2BitsTable(uint64_t m) { return log2Bits8(m); }
}  // namespace sample_detail

SamplerQ SamplerQ::from(const SamplerState& s) {
  SamplerQ q;
  q.state = s;
  q.minLod8 = quantizeLod(s.minLod);
  q.maxLod8 = quantizeLod(s.maxLod);
  q.bias8 = quantizeLod(s.lodBias);
  return q;
}

int64_t log2Fixed(double x, int fracBits) {
  // Fraction bits of the documented intermediate.
  constexpr int kBits = 24;
  if (!(x > 0.0)) return std::numeric_limits<int64_t>::min();  // log2 of 0 / negative / NaN
  if (std::isinf(x)) return std::numeric_limits<int64_t>::max();
  if (fracBits < 0) fracBits = 0;
  // x = m * 2^e with m in [1, 2), read from the IEEE-754 bits; m in Q1.62 (exact: 53 bits).
  uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const int biased = int(bits >> 52) & 0x7ff;
  uint64_t mant = bits & ((uint64_t(1) << 52) - 1);
  int e;
  uint64_t m;
  if (biased != 0) {  // normal
    e = biased - 1023;
    m = (mant | (uint64_t(1) << 52)) << 10;
  } else {  // subnormal: mant * 2^-1074 with the leading one at bit p
    const int p = 63 - std::countl_zero(mant);
    e = p - 1074;
    m = mant << (62 - p);
  }
  // log2(m) bit by bit: square m; if m^2 >= 2 the next bit is 1 and m^2 is halved. Each step
  // truncates at 2^-62, so the bits are those of floor(2^k * log2(m)) up to an error < 2^-36 units
  // of the 24th bit (exact for m = 1, i.e. for powers of two).
  //
  // Rounding: the spec rounds the 24-bit intermediate T = floor(2^24 log2 x) to fracBits bits. The
  // first fracBits + 1 steps of the loop compute exactly the top bits P = T >> (23 - fracBits), and
  // (T + 2^(23 - fracBits)) >> (24 - fracBits) == (P + 1) >> 1 for every T, so the loop stops after
  // fracBits + 1 steps with a bit-identical result (8 steps instead of 24 for lambda).
  // Round half up is right here: log2 of a double is an integer or irrational, so the exact value
  // is never a tie, and a truncated value whose dropped bits read exactly 1/2 lies above the
  // half-way point. The result is floor(2^fracBits * log2(x) + 1/2) = round-half-even of the exact
  // value.
  const int steps = fracBits < kBits ? fracBits + 1 : kBits;
  const int64_t f = log2Bits(m, steps);
  // floor(2^steps * log2 x); beyond 24 bits the result is only shifted (24 bits are computed).
  const int64_t floorValue = int64_t(e) * (int64_t(1) << steps) + f;
  if (fracBits >= kBits) return floorValue * (int64_t(1) << (fracBits - kBits));
  return (floorValue + 1) >> 1;  // arithmetic shift: floor division
}

namespace sample_detail {

// lambda' and lambda from lambda_base (8.8): GL 4.6 §8.14.1, eq. 8.6 - 8.8.
int32_t finishLambda(int32_t base, const SamplerQ& s, float shaderBias) {
  // lambda' = lambda_base + clamp(bias_texobj + bias_shader, -MAX_TEXTURE_LOD_BIAS, +MAX_TEXTURE_LOD_BIAS).
  constexpr int32_t kMaxBias8 = int32_t(kMaxLodBias * 256.0f);
  int32_t bias = s.bias8 + quantizeLod(shaderBias);
  if (bias < -kMaxBias8) bias = -kMaxBias8;
  if (bias > kMaxBias8) bias = kMaxBias8;
  int32_t lambda = base + bias;
  // lambda = clamp(lambda', MIN_LOD, MAX_LOD). GL leaves MIN_LOD > MAX_LOD undefined; here MAX_LOD
  // is applied last and wins, so lambda <= MAX_LOD always holds.
  if (lambda < s.minLod8) lambda = s.minLod8;
  if (lambda > s.maxLod8) lambda = s.maxLod8;
  return lambda;
}

// lambda_base (8.8) of rho^2: log2Fixed(rho^2, 7) = 128 log2(rho^2) = 256 log2(rho), rounded once.
int32_t lambdaBaseFromRho2(double rho2) {
  if (std::isnan(rho2) || std::isinf(rho2)) return kLodMax;  // NaN / Inf: most minified (spec-choices T18)
  if (rho2 == 0.0) return kLodMinusInf;  // GL: lambda = -inf for rho = 0 (also when rho^2 underflows)
  // log2Fixed(rho2, 7) (|value| <= 1075 * 128 < 2^18), its 8 loop steps from the threshold table
  // for a normal rho^2; subnormals (rho < 2^-511) take the loop.
  uint64_t bits;
  std::memcpy(&bits, &rho2, sizeof bits);
  const int biased = int(bits >> 52) & 0x7ff;
  if (biased == 0 || rho2 < 0.0) return int32_t(log2Fixed(rho2, kLodFracBits - 1));
  const uint64_t m = ((bits & ((uint64_t(1) << 52) - 1)) | (uint64_t(1) << 52)) << 10;  // Q1.62
  const int64_t floorValue = int64_t(biased - 1023) * (int64_t(1) << kLambdaSteps) + log2Bits8(m);
  return int32_t((floorValue + 1) >> 1);  // log2Fixed's rounding to 7 bits
}

}  // namespace sample_detail

int32_t computeLambda(double dudx, double dvdx, double dudy, double dvdy, const SamplerQ& s, float shaderBias) {
  // GL 4.6 §8.14.1, exact form: rho^2 = max(ux^2 + vx^2, uy^2 + vy^2) in double (no sqrt needed),
  // lambda_base = log2(rho) = 0.5 * log2(rho^2).
  int32_t base;
  if (!std::isfinite(dudx) || !std::isfinite(dvdx) || !std::isfinite(dudy) || !std::isfinite(dvdy)) {
    base = kLodMax;
  } else {
    const double rx = dudx * dudx + dvdx * dvdx;
    const double ry = dudy * dudy + dvdy * dvdy;
    base = lambdaBaseFromRho2(rx > ry ? rx : ry);
  }
  return finishLambda(base, s, shaderBias);
}

}  // namespace tessera
