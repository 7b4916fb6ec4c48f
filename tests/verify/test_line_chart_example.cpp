// The 300-frame example chart (three series, a reference line, title, axis labels, legend) checked
// against the layout line_chart.h documents. There is no golden hash: every check below is derived from
// the documented rules and the series' values, so a change of look that keeps the rules passes and a
// mis-mapped coordinate, a missing label or a stray pixel fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "tests/verify/line_chart_test_util.h"
#include "verify/line_chart.h"
#include "verify/rgba_canvas.h"

namespace tessera::verify::chart_test {

namespace {

constexpr Rgba kGridGrey{232, 232, 232, 255};
constexpr Rgba kReferenceGrey{128, 128, 128, 255};
constexpr Rgba kLegendGrey{160, 160, 160, 255};

// The column of frame i and the row of value v, from the plot's corners as line_chart.h documents
// them: frame 0 at left and frame xEnd at right, nearest column with ties to the right; yMin at bottom
// and yMax at top, nearest row with ties away from zero (rows are positive here).
int columnOf(const LineChartLayout& l, int64_t i) {
  return l.left + int(std::floor(double(i) * double(l.right - l.left) / double(l.xEnd) + 0.5));
}
double rowExact(const LineChartLayout& l, double v) {
  return double(l.bottom) - (v - l.yMin) / (l.yMax - l.yMin) * double(l.bottom - l.top);
}
int rowOf(const LineChartLayout& l, double v) { return int(std::floor(rowExact(l, v) + 0.5)); }

// Whether series s may have drawn pixel (x, y): (x, y) lies within `margin` of the bounding box of
// one of its segments (or dots), which contains every pixel Bresenham and the brush put there.
bool mayCover(const LineChartLayout& l, const Series& s, int x, int y) {
  const int margin = s.thickness + 1;
  const auto& v = s.values;
  for (size_t j = 0; j < v.size(); ++j) {
    if (!std::isfinite(v[j])) continue;
    const size_t k = j + 1 < v.size() && std::isfinite(v[j + 1]) ? j + 1 : j;
    const int x0 = columnOf(l, int64_t(j)), x1 = columnOf(l, int64_t(k));
    const int y0 = std::min(rowOf(l, v[j]), rowOf(l, v[k])), y1 = std::max(rowOf(l, v[j]), rowOf(l, v[k]));
    if (x >= x0 - margin && x <= x1 + margin && y >= y0 - margin && y <= y1 + margin) return true;
  }
  return false;
}

// The bounding box of the legend's border colour: {x0, y0, x1, y1}, or x0 > x1 if there is none.
std::array<int, 4> legendBox(const RgbaCanvas& cv) {
  std::array<int, 4> b{cv.width(), cv.height(), -1, -1};
  for (int y = 0; y < cv.height(); ++y)
    for (int x = 0; x < cv.width(); ++x)
      if (pixel(cv, x, y) == kLegendGrey)
        b = {std::min(b[0], x), std::min(b[1], y), std::max(b[2], x), std::max(b[3], y)};
  return b;
}
bool inBox(const std::array<int, 4>& b, int x, int y) { return x >= b[0] && x <= b[2] && y >= b[1] && y <= b[3]; }

// Whether `s` (font scale 2, black) appears with its top-left corner somewhere in [x0, x1] x [y0, y1]:
// its ink pixels black and the rest of its box white.
bool textAt(const RgbaCanvas& cv, const std::string& s, int x0, int x1, int y0, int y1) {
  const int w = RgbaCanvas::textWidth(s, 2), h = 2 * RgbaCanvas::kGlyphHeight;
  RgbaCanvas t(w, h, kWhite);
  t.text(0, 0, s, kBlack, 2);
  for (int y = std::max(y0, 0); y <= y1 && y + h <= cv.height(); ++y)
    for (int x = std::max(x0, 0); x <= x1 && x + w <= cv.width(); ++x) {
      bool match = true;
      for (int v = 0; v < h && match; ++v)
        for (int u = 0; u < w && match; ++u) match = pixel(cv, x + u, y + v) == pixel(t, u, v);
      if (match) return true;
    }
  return false;
}

}  // namespace

TEST(LineChart, TheExampleChartsRangesFollowTheDocumentedRules) {
  const LineChartLayout l = lineChartLayout(exampleChart());
  // 300 values per series: frames 0..299, an axis to 300. The largest finite value of the series and
  // hLines is 118 (bytes at frame 59), so the automatic range is 0 .. 200.
  EXPECT_EQ(l.xEnd, 300);
  EXPECT_EQ(l.yMin, 0.0);
  EXPECT_EQ(l.yMax, 200.0);
  // The documented mappings, reproduced here from the corners alone.
  for (int64_t i = 0; i <= 300; ++i) ASSERT_EQ(l.xPixel(i), columnOf(l, i)) << "frame " << i;
  for (int v = 0; v <= 200; ++v) ASSERT_EQ(l.yPixel(double(v)), rowOf(l, double(v))) << "value " << v;
}

TEST(LineChart, TheExampleChartsAxesRunAlongThePlotCornersItsLayoutReports) {
  const LineChart chart = exampleChart();
  const LineChartLayout l = lineChartLayout(chart);
  const RgbaCanvas cv = drawLineChart(chart);
  ASSERT_LT(l.left + 100, l.right);
  ASSERT_LT(l.top + 100, l.bottom);
  auto coveredBySeries = [&](int x, int y) {
    for (const Series& s : chart.series)
      if (mayCover(l, s, x, y)) return true;
    return false;
  };
  auto isSeriesColour = [&](Rgba p) { return p == kBlue || p == kRed || p == kGreen; };
  // The y axis is column `left` from `top` to `bottom`, the x axis row `bottom` from `left` to
  // `right`: black wherever no series can have drawn over them.
  int axisPixels = 0;
  for (int y = l.top; y <= l.bottom; ++y) {
    const Rgba p = pixel(cv, l.left, y);
    if (coveredBySeries(l.left, y)) {
      ASSERT_TRUE(p == kBlack || isSeriesColour(p)) << "y axis at row " << y;
    } else {
      ASSERT_EQ(p, kBlack) << "y axis at row " << y;
      ++axisPixels;
    }
  }
  for (int x = l.left; x <= l.right; ++x) {
    const Rgba p = pixel(cv, x, l.bottom);
    if (coveredBySeries(x, l.bottom)) {
      ASSERT_TRUE(p == kBlack || isSeriesColour(p)) << "x axis at column " << x;
    } else {
      ASSERT_EQ(p, kBlack) << "x axis at column " << x;
      ++axisPixels;
    }
  }
  EXPECT_GT(2 * axisPixels, (l.bottom - l.top) + (l.right - l.left)) << "most of the axes must be checkable";
  // The axes end at the corners: nothing beyond them; inside, the top-left corner is the grid row of
  // the top tick (200) over white.
  EXPECT_EQ(pixel(cv, l.left, l.top - 1), kWhite);
  EXPECT_EQ(pixel(cv, l.right + 1, l.bottom), kWhite);
  EXPECT_EQ(pixel(cv, l.left + 1, l.top), kGridGrey);
  EXPECT_EQ(pixel(cv, l.left + 1, l.top + 1), kWhite);
  // x ticks every 50 frames (documented for 300 frames): a black mark below the axis at each.
  for (int64_t f = 0; f <= 300; f += 50)
    for (int y = l.bottom + 1; y <= l.bottom + 3; ++y)
      EXPECT_EQ(pixel(cv, columnOf(l, f), y), kBlack) << "tick of frame " << f;
  EXPECT_EQ(pixel(cv, columnOf(l, 25), l.bottom + 2), kWhite) << "no tick between the ticks";
}

TEST(LineChart, TheExampleChartsLabelsNameTheRangeTheFramesAndTheSeries) {
  const LineChart chart = exampleChart();
  const LineChartLayout l = lineChartLayout(chart);
  const RgbaCanvas cv = drawLineChart(chart);
  // The range's ends, left of the y axis at their rows (the text centred on the row within 10 px).
  EXPECT_TRUE(textAt(cv, "0", 0, l.left - 2 - RgbaCanvas::textWidth("0", 2), l.bottom - 10, l.bottom))
      << "no '0' label at the bottom of the y axis";
  EXPECT_TRUE(textAt(cv, "200", 0, l.left - 2 - RgbaCanvas::textWidth("200", 2), l.top - 10, l.top))
      << "no '200' label at the top of the y axis";
  // Frame labels centred under their ticks (within the label's own width), below the axis.
  for (int f : {0, 50, 100, 150, 200, 250, 300}) {
    const std::string s = std::to_string(f);
    const int x = columnOf(l, f), w = RgbaCanvas::textWidth(s, 2);
    EXPECT_TRUE(textAt(cv, s, x - w, x, l.bottom + 1, l.bottom + 20)) << "no label under frame " << f;
  }
  EXPECT_TRUE(textAt(cv, "frame", 0, cv.width(), l.bottom + 15, cv.height())) << "no x-axis label";
  EXPECT_TRUE(textAt(cv, "Texture binds per frame", 0, cv.width(), 0, l.top - 10)) << "no title above the plot";
  // The legend: a bordered box inside the plot, listing every series by its label, each with its colour.
  const auto box = legendBox(cv);
  ASSERT_LE(box[0], box[2]) << "no legend border";
  EXPECT_GT(box[0], l.left);
  EXPECT_LT(box[2], l.right);
  EXPECT_GT(box[1], l.top);
  EXPECT_LT(box[3], l.bottom);
  for (const Series& s : chart.series) {
    EXPECT_TRUE(textAt(cv, s.label, box[0], box[2], box[1], box[3])) << "legend lacks " << s.label;
    bool swatch = false;
    for (int y = box[1]; y <= box[3] && !swatch; ++y)
      for (int x = box[0]; x <= box[2] && !swatch; ++x) swatch = pixel(cv, x, y) == s.color;
    EXPECT_TRUE(swatch) << "legend lacks the colour of " << s.label;
  }
}

TEST(LineChart, TheExampleChartsSeriesPassThroughTheirValuesPixels) {
  const LineChart chart = exampleChart();
  const LineChartLayout l = lineChartLayout(chart);
  const RgbaCanvas cv = drawLineChart(chart);
  const auto box = legendBox(cv);
  // Series draw in order, so a point of series k shows its colour unless a later series (or the
  // legend) may cover it. The dashed series shows its colour on most of its points and, in its gaps,
  // whatever lay below (never another series' colour where no other series passes).
  for (size_t k = 0; k < chart.series.size(); ++k) {
    const Series& s = chart.series[k];
    int checked = 0, shown = 0;
    for (size_t i = 0; i < s.values.size(); ++i) {
      if (!std::isfinite(s.values[i])) continue;
      const int x = columnOf(l, int64_t(i)), y = rowOf(l, s.values[i]);
      if (inBox(box, x, y)) continue;
      bool covered = false;
      for (size_t later = k + 1; later < chart.series.size(); ++later)
        covered = covered || mayCover(l, chart.series[later], x, y);
      if (covered) continue;
      ++checked;
      const Rgba p = pixel(cv, x, y);
      if (!s.dashed) {
        ASSERT_EQ(p, s.color) << s.label << " frame " << i << " value " << s.values[i] << " at " << x << "," << y;
      } else {
        bool other = false;
        for (const Series& o : chart.series) other = other || (&o != &s && p == o.color);
        ASSERT_FALSE(other) << s.label << " frame " << i << " at " << x << "," << y;
      }
      shown += p == s.color;
    }
    EXPECT_GT(checked, 100) << s.label << ": too few points clear of the later series to check";
    // A dash pattern of 6 on, 4 off draws 60% of the steps, and the points fall on steps about evenly:
    // well over a third of them show the colour.
    if (s.dashed) {
      EXPECT_GT(3 * shown, checked) << s.label;
    }
  }
  // The NaN run of "bytes resident" (frames 100..119) leaves a gap: between frames 101 and 118 the
  // green series draws nothing.
  const Series& bytes = chart.series[2];
  for (int x = columnOf(l, 101); x <= columnOf(l, 118); ++x)
    for (int y = l.top; y <= l.bottom; ++y) ASSERT_NE(pixel(cv, x, y), bytes.color) << x << "," << y;
}

TEST(LineChart, TheExampleChartsPlotAreaIsBackgroundGridOrTheReferenceLineWhereNoSeriesIs) {
  const LineChart chart = exampleChart();
  const LineChartLayout l = lineChartLayout(chart);
  const RgbaCanvas cv = drawLineChart(chart);
  const auto box = legendBox(cv);
  std::vector<bool> gridColumn(size_t(cv.width()), false);
  for (int64_t f = 50; f <= 300; f += 50) gridColumn[size_t(columnOf(l, f))] = true;
  // Grid rows are the rows of y ticks: find them from the tick marks left of the axis.
  std::vector<bool> gridRow(size_t(cv.height()), false);
  int gridRows = 0;
  for (int y = l.top; y < l.bottom; ++y)
    if (pixel(cv, l.left - 1, y) == kBlack && pixel(cv, l.left - 3, y) == kBlack) gridRow[size_t(y)] = true, ++gridRows;
  EXPECT_GE(gridRows, 2) << "at least the top and one inner y tick";
  EXPECT_TRUE(gridRow[size_t(l.top)]) << "200 is a tick";
  const int refRow = rowOf(l, 110.0);
  int checked = 0, reference = 0;
  for (int y = l.top; y < l.bottom; ++y)
    for (int x = l.left + 1; x <= l.right; ++x) {
      if (inBox(box, x, y)) continue;
      bool covered = false;
      for (const Series& s : chart.series) covered = covered || mayCover(l, s, x, y);
      if (covered) continue;
      ++checked;
      const Rgba p = pixel(cv, x, y);
      if (y == refRow) {
        // The reference line at 110: dashed grey, 6 on and 4 off, starting at the first plot column;
        // the gaps show the grid or the background.
        const bool on = (x - (l.left + 1)) % 10 < 6;
        if (on) {
          ASSERT_EQ(p, kReferenceGrey) << "reference line at " << x;
        } else {
          ASSERT_EQ(p, gridColumn[size_t(x)] ? kGridGrey : kWhite) << "reference gap at " << x;
        }
        reference += on;
        continue;
      }
      const bool grid = gridColumn[size_t(x)] || gridRow[size_t(y)];
      ASSERT_EQ(p, grid ? kGridGrey : kWhite) << x << "," << y;
    }
  EXPECT_GT(checked, (l.right - l.left) * (l.bottom - l.top) / 2) << "most of the plot lies clear of the series";
  EXPECT_GT(reference, 200);
}

TEST(LineChart, TheExampleChartsMarginsAreBackground) {
  const RgbaCanvas cv = drawLineChart(exampleChart());
  const LineChartLayout l = lineChartLayout(exampleChart());
  // Everything outside the plot is text or tick marks, which keep a margin from the canvas edge: the
  // outermost 4 px ring of the canvas is empty.
  for (int x = 0; x < cv.width(); ++x)
    for (int y = 0; y < cv.height(); ++y) {
      const bool ring = x < 4 || y < 4 || x >= cv.width() - 4 || y >= cv.height() - 4;
      if (ring) {
        ASSERT_EQ(pixel(cv, x, y), kWhite) << x << "," << y;
      }
    }
  // Right of the plot, beyond half of the last x label: white.
  const int lastLabelEnd = columnOf(l, 300) + RgbaCanvas::textWidth("300", 2);
  for (int x = lastLabelEnd + 1; x < cv.width(); ++x)
    for (int y = 0; y < cv.height(); ++y) ASSERT_EQ(pixel(cv, x, y), kWhite) << x << "," << y;
}

}  // namespace tessera::verify::chart_test
