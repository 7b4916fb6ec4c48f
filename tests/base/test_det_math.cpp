// Deterministic trigonometry: values worked out independently (exact identities and rational
// multiples of π), the error bound that base/det_math.h states, and detTan = detSin / detCos.
#include <gtest/gtest.h>

#include <cmath>

#include "base/det_math.h"

namespace tessera {
namespace {

TEST(DetMath, SineAtKnownAnglesInTheInnerHalfPeriodIsWithin4p5e16OfTheExactValue) {
  // On [-π/2, π/2] the truncated series is accurate to 4.4e-16 (base/det_math.h); cos(x) is sin(x + π/2),
  // so its argument reaches the outer half period, where the stated 1.71e-13 bound applies.
  const double inner = 4.5e-16, outer = 1.71e-13;
  EXPECT_EQ(detSin(0.0), 0.0);
  EXPECT_NEAR(detSin(kPi / 2), 1.0, inner);
  EXPECT_NEAR(detSin(-kPi / 2), -1.0, inner);
  EXPECT_NEAR(detSin(kPi / 6), 0.5, inner);
  EXPECT_NEAR(detSin(kPi / 4), std::sqrt(0.5), inner);  // sqrt is correctly rounded (IEEE 754)
  EXPECT_NEAR(detCos(0.0), 1.0, inner);
  EXPECT_NEAR(detCos(kPi / 3), 0.5, outer);
  EXPECT_NEAR(detCos(kPi / 2), 0.0, outer);
}

TEST(DetMath, TheAbsoluteErrorStaysBelowTheBoundTheHeaderStatesOverAWholePeriod) {
  // sin² + cos² = 1 needs no reference implementation (no libm): each term is off by at most the
  // stated bound, so the sum is off by at most about twice that.
  double worst = 0.0;
  for (int i = -1000; i <= 1000; ++i) {
    const double x = kPi * i / 1000.0;
    worst = std::fmax(worst, std::fabs(detSin(x) * detSin(x) + detCos(x) * detCos(x) - 1.0));
  }
  EXPECT_LT(worst, 4e-13) << "sin² + cos² drifts from 1 by more than twice the stated 1.71e-13 bound";
}

TEST(DetMath, RangeReductionMakesFarArgumentsAgreeWithTheirReducedForm) {
  for (int k = -5; k <= 5; ++k) EXPECT_NEAR(detSin(0.3 + 2 * kPi * k), detSin(0.3), 1e-14) << k;
}

TEST(DetMath, TangentIsTheQuotientOfTheTwoSoCallersKeepTheirBits) {
  for (double x : {0.1, 0.5, 1.0, -0.7, 30.0 * kPi / 180.0}) EXPECT_EQ(detTan(x), detSin(x) / detCos(x)) << x;
  EXPECT_NEAR(detTan(kPi / 4), 1.0, 4.5e-16);
}

}  // namespace
}  // namespace tessera
