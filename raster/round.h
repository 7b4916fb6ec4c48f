// Fast exact rounding for the per-pixel paths.
//
// Implements: roundHalfEvenNear(), round half to even of a double of magnitude <= 2^51 in two
// additions, and the unorm8 reciprocal that replaces a division by 255 * 2^24 with the same float.
// Does not implement: rounding outside that range (the callers test it and fall back to the
// mode-independent roundHalfEven of raster/setup.h or raster/sample_detail.h).
#pragma once

#include <cfloat>
#include <cstdint>

namespace tessera {

// The two-addition form needs every double operation to round once, to nearest, ties to even: no
// x87 excess precision (FLT_EVAL_METHOD 0), and the default rounding mode, which the oracle never
// changes (CONTRIBUTING.md, "Bit-reproducible").
static_assert(FLT_EVAL_METHOD == 0, "the oracle's rounding needs double operations rounded once");

// Round half to even of x, |x| <= 2^51. x + 1.5 * 2^52 lies in [2^52, 2^53), where the doubles are
// exactly the integers, so IEEE round-to-nearest-even makes the sum RNE(x) + 1.5 * 2^52 and the
// subtraction is exact. The same value as the truncate-and-correct roundHalfEven, without its
// branches (tests/raster/test_round.cpp compares the two at ties, near ties and at the range ends).
inline int64_t roundHalfEvenNear(double x) {
  constexpr double kMagic = 6755399441055744.0;  // 1.5 * 2^52
  const double shifted = x + kMagic;
  return int64_t(shifted - kMagic);
}

// A unorm8 filter sum acc (an integer in [0, 255 * 2^24]) becomes float(acc / (255 * 2^24)). A
// multiply by the double reciprocal gives the same float as the division (no divide per channel):
// both doubles are within 2^-52 relative of q = acc / (255 * 2^24), so they round to the same float
// unless a float rounding boundary (a midpoint between two floats, 25 significant bits) lies within
// 2^-52 of q. It never does: if 255 divides acc, q = n * 2^-24 with n <= 2^24 is itself a float;
// otherwise q is not dyadic and its distance to any midpoint M * 2^e (M odd) is at least
// 2^e / 255 with M < 2^25, i.e. more than 2^-33 relative. tests/raster/test_round.cpp checks it
// for every acc below 2^24 and every multiple of 255 and its neighbours.
constexpr double kUnormDenominator = 255.0 * 16777216.0;  // 255 * 2^24, exact
constexpr double kUnormReciprocal = 1.0 / kUnormDenominator;

}  // namespace tessera
