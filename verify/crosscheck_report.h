// The report directory of `tessera crosscheck --report DIR`.
//
// Implements: for every presented image i, PNGs img<i>_oracle.png, img<i>_gl.png (display versions:
// RGBA8 as stored with opaque alpha, R8 grey, float clamped, ids hash-coloured), img<i>_heat.png
// (|Δ| per pixel, heatColor of its histogram bin) and img<i>_classes.png (the ambiguity-class overlay:
// grey = exact, one colour per leading class for explained pixels, red = unexplained); report.json
// (the crosscheck JSON); and index.html, a self-contained page with oracle / GL / heat map / classes
// side by side, an alternating oracle-GL view, a pixel inspector (both values, the [lo, hi] interval
// and the class names, from data embedded in the page for images up to 1 Mpixel) and the summary
// table. Every file is written atomically.
// Does not implement: the comparison (crosscheck.h).
#pragma once

#include <string>

#include "verify/crosscheck.h"

namespace tessera::verify {

void writeCrosscheckReport(const CrosscheckResult& result, const std::string& dir);

}  // namespace tessera::verify
