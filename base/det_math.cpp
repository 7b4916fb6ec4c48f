#include "base/det_math.h"

#include <cmath>

namespace tessera {

double detSin(double x) {
  // Reduce to [-pi, pi] with a fixed constant, then a Taylor series to x^23 (absolute error at most
  // 1.71e-13 there, largest near +-pi: base/det_math.h).
  // std::floor is exact (IEEE round-to-integral), so it is as deterministic as + and *.
  const double twoPi = 2.0 * kPi;
  x = x - twoPi * std::floor((x + kPi) / twoPi);
  const double x2 = x * x;
  double term = x, sum = x;
  for (int n = 1; n <= 11; ++n) {
    term = -term * x2 / double((2 * n) * (2 * n + 1));
    sum = sum + term;
  }
  return sum;
}

double detCos(double x) { return detSin(x + 0.5 * kPi); }

double detTan(double x) { return detSin(x) / detCos(x); }

}  // namespace tessera
