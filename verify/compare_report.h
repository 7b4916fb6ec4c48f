// The report directory of an image comparison: figures as JSON plus a static, self-contained HTML page.
//
// Implements writeCompareReport(result, dir): creates `dir` if needed and writes, each atomically:
//   report.json    compareToJson(result)
//   expected.png   display version of A, actual.png of B (8-bit: as stored; 16-bit: v/257; float:
//                  clamp(v, 0, 1) * 255, NaN magenta; 32-bit integers (ids): a hash colour per value,
//                  0xffffffff black; one channel grey, two channels R,G; alpha is not shown)
//   heatmap.png    per pixel the histogram bin of the largest channel |Δ| as a colour (black = equal,
//                  blue .. dark red = 1 .. 129+ units, magenta = non-finite), the legend strip below
//   histogram.png  the error histogram as bars (log scale), counts above, bin labels below
//   index.html     expected / actual / heat map side by side at a chosen zoom, an alternating view
//                  (button, hover or auto), a pixel inspector (hover / click: x, y, both values and
//                  |Δ| per channel, from pixel values embedded in the page when each image is at most
//                  16 MiB), the summary table, the histogram and the first differing pixels.
// The page references the PNGs by relative path and needs no network or server.
// For a refused (3) or unreadable (4) comparison only report.json and index.html are written.
// Does not implement: the comparison (image_compare.h).
#pragma once

#include <string>

#include "verify/image_compare.h"
#include "verify/rgba_canvas.h"

namespace tessera::verify {

// Throws Error naming the file on any write failure.
void writeCompareReport(const CompareResult& result, const std::string& dir);

// The error histogram as a bar chart (log scale, counts above, bin labels below); also used by the
// cross-check report, whose judgement has the same bins.
RgbaCanvas histogramChart(const std::array<uint64_t, kHistogramBins>& histogram);

// Heat-map colour of a histogram bin (0 .. kHistogramBins - 1) or CompareResult::kNonFiniteBin.
Rgba heatColor(int bin);

}  // namespace tessera::verify
