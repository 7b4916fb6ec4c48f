// Build parameters of the multiresolution texture atlas tree (Buchholz's thesis §4.2, §4.5.2).
//
// Implements: the parameter set of `tessera mta build`, its validation, the deterministic tan(φ/2)
// and the projection factor f_proj = w_screen / (2 · d_min · tan(φ/2) · τ).
// Does not implement: the build itself (build.h).
#pragma once

#include <cstdint>
#include <string>

namespace tessera::mta {

struct BuildParams {
  // d_min: absolute when > 0; otherwise d_min = D / dMinDivisor with D the scene's bounding-box diagonal
  // (the thesis used D/72 for Berlin, §4.7.1).
  double dMin = 0.0;
  double dMinDivisor = 72.0;
  double tau = 1.0;              // pixel-per-texel ratio τ: a texel may cover up to τ pixels (in width)
  uint32_t atlasSize = 512;      // A: every atlas is A x A; a power of two >= 64
  uint32_t border = 8;           // b: texture border in texels (§4.5.2)
  double fovDegrees = 60.0;      // φ, the horizontal field of view
  double tanHalfFov = 0.0;       // > 0: used instead of fovDegrees (tan(φ/2) given directly)
  uint32_t screenWidth = 1024;   // w_screen in pixels
  double criticalThreshold = 0.1;  // c: raise d_min when more than this fraction of triangles is critical
  uint64_t memoryLimit = uint64_t(4) << 30;  // peak resident bytes allowed (VmRSS), 0 = unchecked
  uint32_t threads = 0;          // 0 = all hardware threads (the bytes never depend on it)
  bool progress = false;         // progress lines on stderr every ~2 s

  // Throws Error naming the first invalid field.
  void validate() const;
  // tan(φ/2): tanHalfFov if given, else detSin/detCos of φ/2 (a fixed Taylor series, no libm).
  double effectiveTanHalfFov() const;
};

// f_proj = w_screen / (2 · d · tan(φ/2) · τ): pixels per world unit of a segment seen orthogonally at
// distance d, divided by τ so that one texel may span τ pixels.
double projectionFactor(const BuildParams& p, double d);

}  // namespace tessera::mta
