// The line charts of verify/line_chart.h and the drawing primitives of verify/rgba_canvas.h they use
// (the full example chart against its documented layout: test_line_chart_example.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "tests/verify/line_chart_test_util.h"
#include "verify/line_chart.h"
#include "verify/rgba_canvas.h"

namespace tessera::verify::chart_test {

// ---- RgbaCanvas: font ----

TEST(RgbaCanvasFont, TheGlyphsThatPredateTheFullFontKeepTheirPixels) {
  // Captured from rgba_canvas.cpp before the letters and punctuation were added.
  const std::vector<std::pair<char, std::vector<std::string>>> before = {
      {'0', {"###", "#.#", "#.#", "#.#", "###"}}, {'1', {".#.", "##.", ".#.", ".#.", "###"}},
      {'2', {"###", "..#", "###", "#..", "###"}}, {'3', {"###", "..#", "###", "..#", "###"}},
      {'4', {"#.#", "#.#", "###", "..#", "..#"}}, {'5', {"###", "#..", "###", "..#", "###"}},
      {'6', {"###", "#..", "###", "#.#", "###"}}, {'7', {"###", "..#", "..#", "..#", "..#"}},
      {'8', {"###", "#.#", "###", "#.#", "###"}}, {'9', {"###", "#.#", "###", "..#", "###"}},
      {'-', {"...", "...", "###", "...", "..."}}, {'+', {"...", ".#.", "###", ".#.", "..."}},
      {'.', {"...", "...", "...", "...", ".#."}}, {'%', {"#.#", "..#", ".#.", "#..", "#.#"}},
      {'>', {"#..", ".#.", "..#", ".#.", "#.."}}, {' ', {"...", "...", "...", "...", "..."}},
      {'N', {"#.#", "###", "###", "###", "#.#"}}, {'a', {"...", "##.", ".##", "#.#", "###"}},
      {'L', {"#..", "#..", "#..", "#..", "###"}}, {'S', {"###", "#..", "###", "..#", "###"}},
      {'B', {"##.", "#.#", "##.", "#.#", "##."}}, {'i', {".#.", "...", ".#.", ".#.", ".#."}},
      {'n', {"...", "##.", "#.#", "#.#", "#.#"}}, {'f', {".##", "#..", "##.", "#..", "#.."}},
  };
  for (const auto& [ch, rows] : before) EXPECT_EQ(glyphPixels(ch), rows) << "glyph '" << ch << "'";
  EXPECT_EQ(glyphPixels('\x01'), (std::vector<std::string>{"###", "#.#", "#.#", "#.#", "###"}));

  // The same string at scale 2: every glyph is its scale-1 pixels doubled in both directions, glyphs
  // follow each other at an advance of 4 * 2 px from (1, 2), and nothing else is drawn.
  const std::string s = "0123456789-+.%> NaLSBinf";
  const Rgba ink{10, 20, 30, 255};
  RgbaCanvas c(200, 20, kWhite);
  c.text(1, 2, s, ink, 2);
  std::vector<std::vector<std::string>> glyphs;
  for (char ch : s) glyphs.push_back(glyphPixels(ch));
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 200; ++x) {
      const int u = x - 1, v = y - 2;
      const bool inCell = u >= 0 && v >= 0 && v < 10 && u / 8 < int(s.size()) && u % 8 < 6;
      const bool on = inCell && glyphs[size_t(u / 8)][size_t(v / 2)][size_t((u % 8) / 2)] == '#';
      ASSERT_EQ(pixel(c, x, y), on ? ink : kWhite) << x << "," << y;
    }
  EXPECT_EQ(RgbaCanvas::textWidth(s, 2), 190);
}

TEST(RgbaCanvasFont, EveryPrintableCharacterButZeroDiffersFromTheUnknownBox) {
  // '0' has always been drawn with the box's pixels; every other printable character has a glyph.
  const std::vector<std::string> box = glyphPixels('\x01');
  for (int ch = 32; ch < 127; ++ch) {
    if (ch == '0') continue;
    EXPECT_NE(glyphPixels(char(ch)), box) << "character '" << char(ch) << "'";
  }
}

TEST(RgbaCanvasFont, UpperAndLowerCaseLettersAreDistinctGlyphs) {
  for (char ch = 'a'; ch <= 'z'; ++ch) {
    const char upper = char(ch - 'a' + 'A');
    if (ch == 'o' || ch == 'x') continue;  // small versions of the same shape, still distinct below
    EXPECT_NE(glyphPixels(ch), glyphPixels(upper)) << ch;
  }
  EXPECT_NE(glyphPixels('o'), glyphPixels('O'));
  EXPECT_NE(glyphPixels('x'), glyphPixels('X'));
}

TEST(RgbaCanvasFont, TurnedTextIsTheTextRotatedCounterClockwise) {
  const std::string s = "texture_binds (MiB)";
  const int w = RgbaCanvas::textWidth(s, 2), h = RgbaCanvas::kGlyphHeight * 2;
  RgbaCanvas flat(w, h, kWhite), turned(h, w, kWhite);
  flat.text(0, 0, s, kBlack, 2);
  turned.textUp(0, 0, s, kBlack, 2);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) ASSERT_EQ(pixel(turned, v, w - 1 - u), pixel(flat, u, v)) << u << "," << v;
}

// ---- RgbaCanvas: lines ----

TEST(RgbaCanvasLine, ALineHasOnePixelPerStepAndIncludesBothEnds) {
  RgbaCanvas c(20, 10, kWhite);
  c.line(2, 1, 11, 4, kRed);
  EXPECT_EQ(count(c, kRed), 10);
  EXPECT_EQ(pixel(c, 2, 1), kRed);
  EXPECT_EQ(pixel(c, 11, 4), kRed);
  RgbaCanvas d(20, 10, kWhite);
  d.line(11, 4, 2, 1, kRed);  // either direction covers a line
  EXPECT_EQ(count(d, kRed), 10);
  RgbaCanvas e(5, 5, kWhite);
  e.line(2, 2, 2, 2, kRed);
  EXPECT_EQ(count(e, kRed), 1);
}

TEST(RgbaCanvasLine, ThicknessStampsASquareAtEveryStep) {
  RgbaCanvas c(20, 10, kWhite);
  c.line(5, 5, 5, 5, kRed, 3);
  EXPECT_EQ(count(c, kRed), 9);
  EXPECT_EQ(pixel(c, 4, 4), kRed);
  EXPECT_EQ(pixel(c, 6, 6), kRed);
  RgbaCanvas d(20, 10, kWhite);
  d.line(2, 5, 11, 5, kRed, 2);
  EXPECT_EQ(count(d, kRed), 22);  // rows 5 and 6, columns 2 to 12: the even brush reaches right and down
}

TEST(RgbaCanvasLine, ADashContinuesAcrossTheSegmentsThatShareIt) {
  RgbaCanvas c(40, 5, kWhite);
  Dash dash{6, 4, 0};
  c.line(0, 2, 9, 2, kRed, 1, &dash);  // steps 0-9: six drawn
  EXPECT_EQ(dash.at, 0);
  c.line(10, 2, 14, 2, kRed, 1, &dash);  // steps 0-4 of the next period: all drawn
  EXPECT_EQ(dash.at, 5);
  EXPECT_EQ(count(c, kRed), 11);
  EXPECT_EQ(pixel(c, 6, 2), kWhite);
  EXPECT_EQ(pixel(c, 12, 2), kRed);
}

TEST(RgbaCanvasLine, LinesOffTheCanvasAreClipped) {
  RgbaCanvas c(10, 10, kWhite);
  c.line(-20, -5, 30, 15, kRed, 3);
  EXPECT_GT(count(c, kRed), 0);
}

// ---- axis labels ----

TEST(FormatAxisNumber, WritesExactDecimalsWithCompactSuffixes) {
  EXPECT_EQ(formatAxisNumber(0, 3, true), "0");
  EXPECT_EQ(formatAxisNumber(50, 0, false), "50");
  EXPECT_EQ(formatAxisNumber(25, -1, false), "2.5");
  EXPECT_EQ(formatAxisNumber(-5, -2, false), "-0.05");
  EXPECT_EQ(formatAxisNumber(2, 5, false), "200000");
  EXPECT_EQ(formatAxisNumber(2, 5, true), "200k");
  EXPECT_EQ(formatAxisNumber(15, 5, true), "1.5M");
  EXPECT_EQ(formatAxisNumber(1000, 0, true), "1k");
  EXPECT_EQ(formatAxisNumber(105, 4, true), "1.05M");
  EXPECT_EQ(formatAxisNumber(2, 9, true), "2G");
  EXPECT_EQ(formatAxisNumber(25, 15, true), "2.5e16");
  EXPECT_EQ(formatAxisNumber(1, -6, false), "1e-6");
  EXPECT_EQ(formatAxisNumber(INT64_MIN, 0, false).substr(0, 3), "-9.");
}

// ---- line charts ----

TEST(LineChart, DrawingTheSameChartTwiceGivesTheSameBytes) {
  const RgbaCanvas a = drawLineChart(exampleChart()), b = drawLineChart(exampleChart());
  ASSERT_EQ(a.width(), 900);
  ASSERT_EQ(a.height(), 320);
  ASSERT_EQ(b.width(), 900);
  ASSERT_EQ(b.height(), 320);
  EXPECT_TRUE(std::equal(a.data(), a.data() + 900 * 320 * 4, b.data()));
}

TEST(LineChart, ARampPassesThroughItsValuesPixels) {
  std::vector<double> ramp(101);
  for (int i = 0; i <= 100; ++i) ramp[size_t(i)] = double(i);
  LineChart c{"ramp", "frame", "value", {{"ramp", ramp, kRed}}};
  c.yMin = 0.0, c.yMax = 100.0;
  const LineChartLayout l = lineChartLayout(c);
  EXPECT_EQ(l.xEnd, 100);
  const RgbaCanvas cv = drawLineChart(c);
  for (int i : {0, 10, 50, 90, 100}) {
    EXPECT_EQ(pixel(cv, l.xPixel(i), l.yPixel(double(i))), kRed) << "frame " << i;
    EXPECT_NE(pixel(cv, l.xPixel(i), l.yPixel(double(i)) - 20), kRed) << "frame " << i;
  }
  // Frame 0 at the axis, frame 100 at the right end, 0 on the x axis and 100 at the top.
  EXPECT_EQ(l.xPixel(0), l.left);
  EXPECT_EQ(l.xPixel(100), l.right);
  EXPECT_EQ(l.yPixel(0.0), l.bottom);
  EXPECT_EQ(l.yPixel(100.0), l.top);
}

TEST(LineChart, AConstantSeriesIsOneHorizontalRow) {
  const LineChart c{"constant", "frame", "", {{"three", std::vector<double>(50, 3.0), kBlue}}};
  const LineChartLayout l = lineChartLayout(c);
  const RgbaCanvas cv = drawLineChart(c);
  const int y = l.yPixel(3.0);
  for (int x = l.xPixel(0); x <= l.xPixel(49); ++x) {
    ASSERT_EQ(pixel(cv, x, y), kBlue) << x;
    ASSERT_NE(pixel(cv, x, y - 1), kBlue) << x;
    ASSERT_NE(pixel(cv, x, y + 1), kBlue) << x;
  }
}

TEST(LineChart, AThickSeriesCoversThatManyRows) {
  const LineChart c{"thick", "frame", "", {{"three", std::vector<double>(50, 3.0), kBlue, false, 3}}};
  const LineChartLayout l = lineChartLayout(c);
  const RgbaCanvas cv = drawLineChart(c);
  const int x = l.xPixel(25), y = l.yPixel(3.0);
  EXPECT_EQ(pixel(cv, x, y - 1), kBlue);
  EXPECT_EQ(pixel(cv, x, y), kBlue);
  EXPECT_EQ(pixel(cv, x, y + 1), kBlue);
  EXPECT_NE(pixel(cv, x, y - 2), kBlue);
  EXPECT_NE(pixel(cv, x, y + 2), kBlue);
}

TEST(LineChart, ADashedSeriesLeavesGapsInItsRow) {
  const LineChart c{"dashed", "frame", "", {{"three", std::vector<double>(300, 3.0), kBlue, true}}};
  const LineChartLayout l = lineChartLayout(c);
  const RgbaCanvas cv = drawLineChart(c);
  int drawn = 0, total = 0;
  for (int x = l.xPixel(0); x <= l.xPixel(299); ++x, ++total) drawn += pixel(cv, x, l.yPixel(3.0)) == kBlue ? 1 : 0;
  EXPECT_GT(drawn, total / 2);
  EXPECT_LT(drawn, total * 3 / 4);
}

TEST(LineChart, ANanIsAGapAndAnIsolatedValueIsADot) {
  const LineChart c{"gaps", "frame", "", {{"s", {1.0, 1.0, NAN, NAN, 1.0, NAN, 1.0, 1.0}, kBlue}}};
  const LineChartLayout l = lineChartLayout(c);
  EXPECT_EQ(l.xEnd, 7);
  const RgbaCanvas cv = drawLineChart(c);
  const int y = l.yPixel(1.0);
  EXPECT_EQ(pixel(cv, (l.xPixel(0) + l.xPixel(1)) / 2, y), kBlue);
  EXPECT_NE(pixel(cv, (l.xPixel(1) + l.xPixel(2)) / 2, y), kBlue);
  EXPECT_NE(pixel(cv, (l.xPixel(3) + l.xPixel(4)) / 2, y), kBlue);
  EXPECT_EQ(pixel(cv, l.xPixel(4), y), kBlue);
  EXPECT_NE(pixel(cv, l.xPixel(4) + 1, y), kBlue);
  EXPECT_NE(pixel(cv, l.xPixel(4) - 1, y), kBlue);
  EXPECT_EQ(pixel(cv, (l.xPixel(6) + l.xPixel(7)) / 2, y), kBlue);
}

TEST(LineChart, AllNanSeriesDrawsAxesOnly) {
  const LineChart c{"nothing", "frame", "count", {{"nan", std::vector<double>(300, NAN), kRed}}};
  const LineChartLayout l = lineChartLayout(c);
  EXPECT_EQ(l.yMin, 0.0);
  EXPECT_EQ(l.yMax, 1.0);
  EXPECT_EQ(l.xEnd, 300);
  const RgbaCanvas cv = drawLineChart(c);
  EXPECT_EQ(count(cv, kRed), 24);  // the legend's swatch only
  EXPECT_EQ(pixel(cv, l.left, l.top), kBlack);
  EXPECT_EQ(pixel(cv, l.left, l.bottom), kBlack);
  EXPECT_EQ(pixel(cv, l.right, l.bottom), kBlack);
}

TEST(LineChart, EmptyChartsSeriesAndSinglePointsAreFine) {
  EXPECT_EQ(drawLineChart(LineChart{}).width(), 900);
  const RgbaCanvas empty = drawLineChart({"empty", "frame", "", {{"none", {}, kRed}}});
  EXPECT_EQ(count(empty, kRed), 24);  // the legend's swatch only

  const LineChart one{"one", "frame", "", {{"seven", {7.0}, kRed, false, 3}}};
  const LineChartLayout l = lineChartLayout(one);
  EXPECT_EQ(l.yMax, 10.0);
  EXPECT_EQ(pixel(drawLineChart(one), l.xPixel(0), l.yPixel(7.0)), kRed);

  // Tiny canvases are enlarged; infinities are gaps; huge and negative values pick their own range.
  const RgbaCanvas tiny = drawLineChart({"", "", "", {{"x", {1.0, 2.0}, kRed}}, 1, 1});
  EXPECT_GE(tiny.width(), 100);
  const LineChart odd{"odd", "", "", {{"x", {INFINITY, -3.0, 2.5e9, -INFINITY, 1e-300}, kRed}}};
  const LineChartLayout lo = lineChartLayout(odd);
  EXPECT_EQ(lo.yMin, -5.0);
  EXPECT_EQ(lo.yMax, 5e9);
  drawLineChart(odd);
  LineChart inverted{"inverted", "", "", {{"x", {1.0, 2.0}, kRed}}};
  inverted.yMin = 5.0, inverted.yMax = 2.0;
  EXPECT_EQ(lineChartLayout(inverted).yMax, 6.0);
  drawLineChart(inverted);
  LineChart vast{"vast", "", "", {{"x", {-1e308, 1e308}, kRed}}};
  vast.yMin = -1.7e308, vast.yMax = 1.7e308;  // the span overflows to infinity
  drawLineChart(vast);
}

TEST(LineChart, AutomaticRangesEndAtNiceNumbers) {
  auto top = [](std::vector<double> v, std::vector<double> hLines = {}) {
    LineChart c{"", "", "", {{"s", std::move(v), kRed}}};
    c.hLines = std::move(hLines);
    return lineChartLayout(c).yMax;
  };
  EXPECT_EQ(top({1.0, 37.0}), 50.0);
  EXPECT_EQ(top({100.0}), 100.0);
  EXPECT_EQ(top({101.0}), 200.0);
  EXPECT_EQ(top({0.3}), 0.5);
  EXPECT_EQ(top({1.2e6}), 2e6);
  EXPECT_EQ(top({50.0}, {120.0}), 200.0);  // a reference line stays in view
  EXPECT_EQ(top({0.0}), 1.0);
}

TEST(LineChart, ThreeHundredFramesGetAnAxisToThreeHundred) {
  const LineChart c{"", "frame", "", {{"s", std::vector<double>(300, 1.0), kRed}}};
  EXPECT_EQ(lineChartLayout(c).xEnd, 300);
}

TEST(LineChart, ValuesBeyondAGivenRangeAreClippedAtThePlotEdge) {
  LineChart c{"clipped", "frame", "", {{"s", {1.0, 1000.0, 1.0, -1000.0, 1.0}, kRed, false, 1}}};
  c.yMin = 0.0, c.yMax = 10.0;
  const LineChartLayout l = lineChartLayout(c);
  const RgbaCanvas cv = drawLineChart(c);
  for (int y = 0; y < cv.height(); ++y)
    for (int x = l.left; x <= l.right; ++x) {
      if (y >= l.top && y <= l.bottom) continue;
      ASSERT_NE(pixel(cv, x, y), kRed) << x << "," << y;
    }
  EXPECT_EQ(pixel(cv, l.xPixel(0), l.yPixel(1.0)), kRed);
}

TEST(LineChart, TheLegendAvoidsTheCornerTheDataOccupies) {
  // A rising ramp fills the top-right corner, so the legend goes top left and leaves the ramp whole.
  std::vector<double> ramp(101);
  for (int i = 0; i <= 100; ++i) ramp[size_t(i)] = double(i);
  const LineChart c{"ramp", "frame", "value", {{"a rising ramp", ramp, kRed, false, 2}}};
  const LineChartLayout l = lineChartLayout(c);
  const RgbaCanvas cv = drawLineChart(c);
  for (int i = 0; i <= 100; ++i) EXPECT_EQ(pixel(cv, l.xPixel(i), l.yPixel(double(i))), kRed) << i;
  EXPECT_EQ(pixel(cv, l.left + 6 + 1, l.top + 6), (Rgba{160, 160, 160, 255}));  // the legend's border
}

TEST(LineChart, StackingSumsHeightsAndKeepsEachPanel) {
  const RgbaCanvas a = drawLineChart(exampleChart());
  LineChart small = exampleChart();
  small.width = 600, small.height = 200;
  const RgbaCanvas b = drawLineChart(small);
  const RgbaCanvas s = stackCharts({a, b, a});
  EXPECT_EQ(s.width(), 900);
  EXPECT_EQ(s.height(), 320 + 200 + 320);
  for (int y = 0; y < b.height(); ++y)
    for (int x = 0; x < 900; ++x) ASSERT_EQ(pixel(s, x, 320 + y), x < 600 ? pixel(b, x, y) : kWhite) << x << "," << y;
  for (int x = 0; x < 900; ++x) ASSERT_EQ(pixel(s, x, 520 + 100), pixel(a, x, 100));
  const RgbaCanvas none = stackCharts({});
  EXPECT_EQ(none.width(), 0);
  EXPECT_EQ(none.height(), 0);
}

}  // namespace tessera::verify::chart_test
