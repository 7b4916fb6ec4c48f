// The log-log plot of `tessera bench sweep` (sweep.png): frame time against pixels or triangles, one
// line per renderer, the ratio llvmpipe / oracle written at every point.
//
// Implements: one panel per series group (a workload, variant and thread count) with logarithmic x and
// y axes spanning whole decades, decade labels (formatAxisNumber of verify/line_chart.h), light grid
// lines at 1..9 x 10^k, a polyline with square markers per renderer, a legend, and the panels in a grid
// of two columns.
// Does not implement: linear axes (verify/line_chart.h draws those), fitted lines, file output (the
// caller writes the canvas with writePngRGBA8). The pixels use std::log10: a benchmark plot is not an
// output of the oracle's contract (its inputs, the times, differ from run to run anyway).
#pragma once

#include <string>
#include <vector>

#include "verify/rgba_canvas.h"

namespace tessera::cli {

struct PlotLine {
  std::string label;  // "oracle", "llvmpipe", ...
  verify::Rgba color;
  std::vector<double> x, ms;  // positive values; others are skipped
  // Written next to each point when not empty (the same length as x): "0.42" = llvmpipe / oracle.
  std::vector<std::string> notes;
};

struct PlotPanel {
  std::string title, xLabel;
  std::vector<PlotLine> lines;
};

verify::RgbaCanvas drawSweepPlot(const std::vector<PlotPanel>& panels);

}  // namespace tessera::cli
