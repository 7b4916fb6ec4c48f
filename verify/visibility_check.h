// The judgement of the visibility oracle: compares the oracle's ID images with the Embree cast and
// decides, for every mismatching pixel, whether the documented bounds explain it.
//
// Implements, per mismatching pixel, a double-precision re-evaluation of every triangle near the
// pixel centre (window_geometry.h): a triangle DEFINITELY covers the centre when it is front-facing
// (or culling is off), the centre is inside it and farther than edgeEpsilon from its boundary;
// it MAY cover it when the centre is within edgeEpsilon of its boundary (culled slivers included,
// since snapping can flip their facing). The oracle's answer is explained when
//  - background: no triangle definitely covers the centre;
//  - triangle A (its object and primitive ids): some triangle with those ids may or definitely covers
//    the centre, and no other definitely-covering triangle B is nearer by more than
//    tol(A) + tol(B), tol(T) = |grad z_T| * edgeEpsilon + 2^-23 (docs/visibility.md).
// The category is "edge" when the explanation needs snapping to move an edge over (or off) the centre
// (a triangle inside/outside in double but within edgeEpsilon of its boundary), "depth tie" when it
// needs a depth within the bound (of a nearer triangle or of the cleared depth), "reference" when the
// double reference agrees with the oracle outright (Embree's own float error).
// Does not implement: the cast (embree_trace.h) or the oracle render (visibility.cpp).
#pragma once

#include "verify/embree_trace.h"
#include "verify/visibility.h"
#include "verify/visibility_scene.h"

namespace tessera::verify {

// Depth bound of one triangle: how far the oracle's float depth at a covered pixel may lie from the
// triangle's exact plane (docs/visibility.md "Depth bound").
inline double depthTolerance(double gradient, double edgeEpsilon) { return gradient * edgeEpsilon + 0x1p-23; }

VisibilityResult classifyVisibility(const VisibilityScene& scene, const EmbreeImage& cast, const IdImages& oracle,
                                    const VisibilityOptions& options);

}  // namespace tessera::verify
