// Critical triangles (thesis §4.5.3): triangles whose own required atlas area exceeds the atlas.
//
// Implements: detection at the requested d_min; when more than a fraction c of the textured triangles
// is critical, d_min is raised so that at most floor(c · n) remain critical (the inner size scales as
// 1/d_min, so the d_min each triangle needs is d · inner / (A − 2b)); the remaining critical triangles
// are split recursively at the midpoint of their longest edge measured in required texels, until none
// is critical. Every later node split then terminates: a single non-critical triangle always fits.
// Does not implement: the tree (tree_build.h).
#pragma once

#include <cstdint>

#include "mta/params.h"
#include "mta/scene.h"
#include "mta/size_estimation.h"

namespace tessera::mta {

struct CriticalReport {
  uint64_t triangles = 0;           // input triangles
  uint64_t criticalAtRequested = 0;  // critical at the requested d_min
  uint64_t criticalAfterRaise = 0;   // critical at the d_min used (these were split)
  uint64_t trianglesAdded = 0;       // extra triangles created by splitting
  uint32_t maxSplitDepth = 0;
  double dMinRequested = 0.0, dMinUsed = 0.0;
};

// Requirement of triangle t alone (its own A_tex) for layer 0 at projection factor fProj.
AreaRequirement triangleRequirement(const Scene& s, const Geometry& g, uint32_t t, double fProj, uint32_t border,
                                    double* uncappedW = nullptr, double* uncappedH = nullptr);

bool isCritical(const AreaRequirement& r, uint32_t atlasSize);

// Returns the geometry with every critical triangle split; sets report (dMinUsed among others).
// Split triangles keep `source`, `alpha` and winding; positions and texcoords of every layer are
// interpolated at edge midpoints in double and stored as float. Throws Error if a triangle is still
// critical after 40 levels of splitting (only possible with absurd parameters).
Geometry handleCriticalTriangles(const Scene& s, const BuildParams& p, double dMinRequested, CriticalReport& report);

}  // namespace tessera::mta
