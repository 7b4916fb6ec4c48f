// Line charts of per-frame series (the frame-rate and count plots over a camera path, as in figures
// 31-32 of Buchholz's thesis) drawn on an RgbaCanvas, and several charts stacked into one figure.
//
// Implements: one chart per call with a title, a y axis with nice ticks (1, 2 or 5 x 10^k) and
// compact labels ("200k", "1.5M"), an x axis of frame indices, axis labels, light grid lines, dashed
// horizontal reference lines, series as Bresenham polylines (thickness, dashes, NaN gaps) and a
// legend box; vertical stacking of charts.
// Does not implement: logarithmic axes, x values other than 0, 1, 2, ... (one value per frame),
// anti-aliasing, markers, file output (writePngRGBA8 in raster/image_io.h). Pixels come from integer
// and IEEE double arithmetic without libm transcendentals or locale-dependent formatting, so the
// bytes are the same on every run and build.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "verify/rgba_canvas.h"

namespace tessera::verify {

struct Series {
  std::string label;
  std::vector<double> values;  // one per x (frame); NaN (or another non-finite value) = gap
  Rgba color;
  bool dashed = false;
  int thickness = 1;  // pixels; clamped to 1..16
};

struct LineChart {
  std::string title, xLabel, yLabel;
  std::vector<Series> series;
  int width = 900, height = 320;  // raised to at least 160 x 100
  double yMin = NAN, yMax = NAN;  // NaN (or another non-finite value) = auto, see drawLineChart
  std::vector<double> hLines;     // optional horizontal reference lines (e.g. a capacity), drawn dashed grey
};

// Draws the chart on a white width x height canvas.
//
// The x axis runs from frame 0 to the last frame of the longest series, rounded up to a multiple of
// its tick step (for 300 frames: ticks every 50, axis to 300). An automatic y range is 0 (or, with
// negative values, minus the nice ceiling of the most negative one) up to the smallest 1, 2 or 5 x
// 10^k that is at least the largest finite value of the series and hLines; with no finite values it
// is 0..1. An inverted or empty range [yMin, yMax] becomes [yMin, yMin + 1]. Values outside the
// range are clipped at the plot's edge; a finite value whose neighbours are gaps draws as a dot.
// Series draw in order, so later ones cover earlier ones. The legend lists every series with its
// colour, thickness and dash, in the corner of the plot where it covers the fewest drawn pixels.
// Y tick labels carry k / M / G / T suffixes once the largest tick reaches 10^4 (x labels likewise).
// Empty, all-NaN and single-point series are fine.
RgbaCanvas drawLineChart(const LineChart& chart);

// Several charts stacked vertically into one image (a multi-panel figure), in order, each at the
// left edge. The width is the widest chart's (narrower ones are padded with white); the height is
// the sum of the heights. An empty list gives a 0 x 0 canvas.
RgbaCanvas stackCharts(const std::vector<RgbaCanvas>& charts);

// Where drawLineChart puts the plot, for callers that annotate a chart and for tests.
struct LineChartLayout {
  // The plot's corners: frame 0 is at x = left, frame xEnd at x = right, yMin at y = bottom and yMax
  // at y = top. The axes are the column x = left and the row y = bottom.
  int left = 0, top = 0, right = 1, bottom = 1;
  int64_t xEnd = 1;  // the last frame of the x axis
  double yMin = 0.0, yMax = 1.0;

  // The column of a frame: integer arithmetic, ties round right.
  int xPixel(int64_t frame) const;
  // The row of a value in [yMin, yMax] (outside that range the row lies outside the plot): the
  // nearest row to yExact, ties away from zero.
  int yPixel(double value) const;
  double yExact(double value) const;
};
LineChartLayout lineChartLayout(const LineChart& chart);

// The decimal digits * 10^exp10 as an axis label, with no floating point and no locale: "0", "50",
// "2.5", "-0.05". compact replaces the last 3, 6, 9 or 12 digits by k, M, G or T ("200k", "1.5M");
// numbers of 10^15 and above, and below 10^-4, are written as "2.5e16".
std::string formatAxisNumber(int64_t digits, int exp10, bool compact);

}  // namespace tessera::verify
