#include "mta/params.h"

#include <fmt/format.h>

#include <cmath>

#include "base/det_math.h"
#include "base/error.h"

namespace tessera::mta {

void BuildParams::validate(const std::string& prefix, bool stored) const {
  auto bad = [&](const char* field, const std::string& why) { throw Error(prefix + field + ": " + why); };
  // Every comparison is written so that NaN fails it.
  if (!(dMin >= 0.0 && std::isfinite(dMin)))
    bad("d_min", fmt::format("{} is not a finite number >= 0 (0 = derived from the scene)", dMin));
  if (!(dMinDivisor > 0.0 && std::isfinite(dMinDivisor)))
    bad("d_min_divisor", fmt::format("{} is not a finite number > 0", dMinDivisor));
  if (!(tau > 0.0 && std::isfinite(tau))) bad("tau", fmt::format("{} is not a finite number > 0", tau));
  if (atlasSize < 64 || atlasSize > 8192 || (atlasSize & (atlasSize - 1)) != 0)
    bad("atlas_size", std::to_string(atlasSize) + " is not a power of two in [64, 8192]");
  if (2 * uint64_t(border) + 1 > atlasSize / 2)
    bad("border",
        std::to_string(border) + ": 2 * border + 1 must fit in half an atlas (" + std::to_string(atlasSize / 2) + ")");
  // Checked even when tan_half_fov overrides it: the file stores it and `mta info` reports it.
  if (!(fovDegrees > 0.0 && fovDegrees < 180.0))
    bad("fov_degrees", fmt::format("{} is outside (0, 180) degrees", fovDegrees));
  if (stored || tanHalfFov != 0.0) {
    if (!(tanHalfFov >= kMinTanHalfFov && tanHalfFov <= kMaxTanHalfFov))
      bad("tan_half_fov", fmt::format("{} is outside [{}, {}]{}", tanHalfFov, kMinTanHalfFov, kMaxTanHalfFov,
                                      stored ? "" : " (0 = derived from fov_degrees)"));
  } else {
    const double t = effectiveTanHalfFov();
    if (!(t >= kMinTanHalfFov && t <= kMaxTanHalfFov))
      bad("fov_degrees",
          fmt::format("{} gives tan(fov / 2) = {}, outside [{}, {}]", fovDegrees, t, kMinTanHalfFov, kMaxTanHalfFov));
  }
  if (screenWidth < 1 || screenWidth > kMaxScreenWidth)
    bad("screen_width", std::to_string(screenWidth) + " is outside [1, " + std::to_string(kMaxScreenWidth) + "]");
  if (!(criticalThreshold >= 0.0 && criticalThreshold <= 1.0))
    bad("critical_threshold", fmt::format("{} is outside [0, 1]", criticalThreshold));
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
