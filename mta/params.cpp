#include "mta/params.h"

#include <cmath>

#include "base/error.h"
#include "base/det_math.h"

namespace tessera::mta {

void BuildParams::validate() const {
  auto bad = [](const std::string& field, const std::string& why) { throw Error("mta parameter " + field + ": " + why); };
  if (!(dMin >= 0.0) || !std::isfinite(dMin)) bad("d_min", "must be a finite number >= 0 (0 = derived from the scene)");
  if (dMin == 0.0 && !(dMinDivisor > 0.0 && std::isfinite(dMinDivisor))) bad("d_min_divisor", "must be > 0");
  if (!(tau > 0.0) || !std::isfinite(tau)) bad("tau", "must be > 0");
  if (atlasSize < 64 || atlasSize > 8192 || (atlasSize & (atlasSize - 1)) != 0)
    bad("atlas_size", std::to_string(atlasSize) + " is not a power of two in [64, 8192]");
  if (2 * uint64_t(border) + 1 > atlasSize / 2) bad("border", "2 * border + 1 must fit in half an atlas");
  if (tanHalfFov == 0.0 && !(fovDegrees > 0.0 && fovDegrees < 180.0)) bad("fov", "must be in (0, 180) degrees");
  if (tanHalfFov < 0.0 || !std::isfinite(tanHalfFov)) bad("tan_half_fov", "must be > 0");
  if (screenWidth == 0) bad("screen_width", "must be > 0");
  if (!(criticalThreshold >= 0.0 && criticalThreshold <= 1.0)) bad("critical_threshold", "must be in [0, 1]");
}

double BuildParams::effectiveTanHalfFov() const {
  if (tanHalfFov > 0.0) return tanHalfFov;
  const double half = fovDegrees * kPi / 360.0;  // deterministic: no libm tan (CONTRIBUTING.md)
  return detSin(half) / detCos(half);
}

double projectionFactor(const BuildParams& p, double d) {
  return double(p.screenWidth) / (2.0 * d * p.effectiveTanHalfFov() * p.tau);
}

}  // namespace tessera::mta
