// The fast roundings of raster/round.h give exactly the values of the forms they replace:
// roundHalfEvenNear equals the truncate-and-correct roundHalfEven, and a unorm8 filter sum times the
// reciprocal of 255 * 2^24 rounds to the float the division gave. The sampler and the colour writes
// rely on both; a difference would change output bytes only on rare inputs that no golden may hold.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <random>

#include "raster/round.h"
#include "raster/setup.h"

namespace tessera {

namespace {

// The division the sampler did before; volatile keeps the compiler from turning it into anything else.
float divided(uint32_t acc) {
  volatile double d = kUnormDenominator;
  return float(double(acc) / d);
}

float multiplied(uint32_t acc) { return float(double(acc) * kUnormReciprocal); }

}  // namespace

TEST(Round, HalfEvenNearMatchesTheTruncatingFormAtTiesNearTiesAndTheRangeEnds) {
  std::vector<double> xs;
  for (int64_t i = -1000; i <= 1000; ++i) {
    const double k = double(i);
    for (double d : {0.0, 0.5, -0.5, 0.25, 0.75, 0.4999999999999999, 0.5000000000000001}) xs.push_back(k + d);
  }
  const double big = 2251799813685248.0;  // 2^51, the end of the range
  for (double x : {big, -big, big - 0.5, -(big - 0.5), big - 1.5, 1125899906842624.5, -1125899906842623.5})
    xs.push_back(x);
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> any(-1e6, 1e6);
  for (int i = 0; i < 1000000; ++i) xs.push_back(any(rng));
  for (int i = 0; i < 100000; ++i) xs.push_back(double(int64_t(rng() % 1000000) - 500000) + 0.5);  // ties
  for (double x : xs) ASSERT_EQ(roundHalfEvenNear(x), detail::roundHalfEven(x)) << "x = " << x;
}

TEST(Round, HalfEvenNearRoundsUnormChannelsOfEveryFloatInTheUnitInterval) {
  // toUnorm8's argument c * 255 for every float c in (0, 1) (2^30 of them, sampled with a stride
  // that reaches every exponent and many mantissas), the product exact in double.
  for (uint32_t u = 1; u < 0x3f800000u; u += 97) {
    float c;
    std::memcpy(&c, &u, sizeof c);
    const double x = double(c) * 255.0;
    ASSERT_EQ(roundHalfEvenNear(x), detail::roundHalfEven(x)) << "c bits " << u;
  }
}

TEST(Round, UnormReciprocalGivesTheDivisionsFloatForEverySumBelow2To24) {
  for (uint32_t acc = 0; acc < (1u << 24); ++acc)
    ASSERT_EQ(std::bit_cast<uint32_t>(multiplied(acc)), std::bit_cast<uint32_t>(divided(acc))) << acc;
}

TEST(Round, UnormReciprocalGivesTheDivisionsFloatAtEveryMultipleOf255AndItsNeighbours) {
  // Multiples of 255 are the sums whose quotient is a float; their neighbours are the nearest a sum
  // comes to a float without being one.
  for (uint64_t n = 0; n <= (uint64_t(1) << 24); ++n) {
    const uint64_t m = 255 * n;
    for (uint64_t acc : {m, m + 1, m - 1}) {
      if (acc <= uint64_t(kUnormDenominator)) {
        ASSERT_EQ(std::bit_cast<uint32_t>(multiplied(uint32_t(acc))), std::bit_cast<uint32_t>(divided(uint32_t(acc))))
            << acc;
      }
    }
  }
}

TEST(Round, UnormReciprocalGivesTheDivisionsFloatForRandomSums) {
  std::mt19937_64 rng(2026);
  for (int i = 0; i < 20000000; ++i) {
    const uint32_t acc = uint32_t(rng() % (uint64_t(kUnormDenominator) + 1));
    ASSERT_EQ(std::bit_cast<uint32_t>(multiplied(acc)), std::bit_cast<uint32_t>(divided(acc))) << acc;
  }
}

}  // namespace tessera
