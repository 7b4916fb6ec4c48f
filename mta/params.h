// Build parameters of the multiresolution texture atlas tree (Buchholz's thesis §4.2, §4.5.2).
//
// Implements: the parameter set of `tessera mta build`, its validation (the same rules for the options of
// a build and for the values a paging file stores, so that every file the builder writes is one the reader
// accepts), the deterministic tan(φ/2) and the projection factor f_proj = w_screen / (2 · d_min · tan(φ/2) · τ).
// Does not implement: the build itself (build.h), the rest of a paging file's validation (paging_file.h).
#pragma once

#include <cstdint>
#include <string>

#include "mta/block_encoding.h"

#include "raster/limits.h"

namespace tessera::mta {

// The documented ranges of the parameters (docs/mta-format.md, "Validation").
// w_screen: the renderer's frame width limit (raster/limits.h), since minDistance is rescaled to the frame.
constexpr uint32_t kMaxScreenWidth = uint32_t(kMaxTextureSize);
// tan(φ/2), φ about 0.000115° .. 179.99989°: 1 / tan and the projection built from it stay well inside
// float range for every frame shape the renderer accepts (mta/camera.h builds float matrices).
constexpr double kMinTanHalfFov = 1e-6, kMaxTanHalfFov = 1e6;

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
  // How blocks are stored (block_encoding.h): S3TC as the thesis did (§4.7); Raw (`mta build --raw`) for
  // comparison and for tests that check texel values exactly. Stored in the header, not in the metadata.
  BlockEncoding encoding = BlockEncoding::S3tc;

  // Throws Error("<prefix><field>: <reason>") for the first field outside its range; fields are named as
  // in the paging file and `mta info` (d_min, d_min_divisor, tau, atlas_size, border, fov_degrees,
  // tan_half_fov, screen_width, critical_threshold). stored: the values come from a paging file, where
  // tan_half_fov is always the value used (> 0), never 0 for "derive it from fov_degrees".
  void validate(const std::string& prefix = "mta parameter ", bool stored = false) const;
  // tan(φ/2): tanHalfFov if given, else detSin/detCos of φ/2 (a fixed Taylor series, no libm).
  double effectiveTanHalfFov() const;
};

// f_proj = w_screen / (2 · d · tan(φ/2) · τ): pixels per world unit of a segment seen orthogonally at
// distance d, divided by τ so that one texel may span τ pixels.
double projectionFactor(const BuildParams& p, double d);

}  // namespace tessera::mta
