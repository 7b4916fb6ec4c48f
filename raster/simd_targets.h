// Which SIMD target the oracle's Highway kernels run on (raster/sample_simd.h, fragops_simd.h,
// interpolate_simd.h, coverage_simd.h).
//
// Implements: the list of targets this build compiled (every x86 target Highway can attain: AVX-512
// "avx3", "avx2", "sse4", "ssse3" and the one-lane "scalar"; HWY_COMPILE_ALL_ATTAINABLE is set for the
// whole raster library so every kernel file has the same list) that this CPU runs, the one running now,
// and forcing one of them, or "reference": every kernel off, the readable scalar code only. Every
// target must give the reference's bytes; tests and `tessera golden check --simd` run each in turn.
// Does not implement: the kernels, or a choice per kernel (one target for all of them).
#pragma once

#include <string>
#include <vector>

namespace tessera::simd {

// Best first, then "reference".
std::vector<std::string> availableTargets();
// The target the kernels run on now ("reference" when they are off).
std::string activeTarget();
// From now on, in every thread ("" or "best": the best available again). Throws Error naming the
// available targets when `name` is not one of them. Call between frames, not while one renders: a
// kernel is chosen when a triangle starts.
void forceTarget(const std::string& name);
// False under "reference". One relaxed atomic load.
bool kernelsOn();

}  // namespace tessera::simd
