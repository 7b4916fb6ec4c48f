#include "verify/line_chart.h"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <utility>

namespace tessera::verify {

namespace {

constexpr Rgba kWhite{255, 255, 255, 255};
constexpr Rgba kInk{0, 0, 0, 255};
constexpr Rgba kGrid{232, 232, 232, 255};
constexpr Rgba kReference{128, 128, 128, 255};
constexpr Rgba kLegendBorder{160, 160, 160, 255};

// All text is the 3x5 font at scale 2: 8 px advance, 10 px high. Smaller is unreadable in a
// thesis-sized figure, and one size keeps every margin below a constant.
constexpr int kScale = 2;
constexpr int kTextH = RgbaCanvas::kGlyphHeight * kScale;
constexpr int kPad = 8;      // canvas edge to anything drawn
constexpr int kTick = 5;     // tick mark length, outside the plot
constexpr int kTickGap = 4;  // tick mark to its label
constexpr int kMaxThickness = 16;
constexpr int kDashOn = 6, kDashOff = 4;
constexpr int kMinWidth = 160, kMinHeight = 100;
// Tick density: at most one y tick per 40 rows and one x tick per 80 columns, so labels never touch.
constexpr int kRowsPerYTick = 40, kColumnsPerXTick = 80;
// Past this many steps from zero a tick's digits no longer fit the double that placed it.
constexpr double kMaxTickIndex = 1e15;
constexpr int64_t kMaxTicks = 1000;

// 10^e by repeated exact steps instead of std::pow, whose last bit may differ between libms.
double pow10(int e) {
  double p = 1.0;
  for (int i = 0; i < (e < 0 ? -e : e); ++i) p *= 10.0;
  return e < 0 ? 1.0 / p : p;
}

// m * 10^e with m in {1, 2, 5}: kept as integers so that tick labels are exact decimals.
struct Nice {
  int mantissa = 1, exp10 = 0;
  double value() const { return double(mantissa) * pow10(exp10); }
};

// The smallest 1, 2 or 5 x 10^e that is at least x > 0. The relative slack absorbs the rounding of
// a quotient like 0.5 / 5, so that an exact nice number maps to itself.
Nice niceAtLeast(double x) {
  constexpr double kSlack = 1e-9;
  int e = 0;
  while (e > -307 && pow10(e) > x * (1.0 + kSlack)) --e;
  while (e < 307 && pow10(e + 1) <= x * (1.0 + kSlack)) ++e;
  for (int m : {1, 2, 5})
    if (double(m) * pow10(e) >= x * (1.0 - kSlack)) return {m, e};
  return {1, e + 1};
}

struct Tick {
  double value;
  std::string label;
};

// Multiples of step in [lo, hi], labelled exactly from the step's integer digits.
std::vector<Tick> ticksOf(double lo, double hi, Nice step, bool compactAllowed) {
  const double s = step.value();
  if (!(s > 0.0) || std::max(std::abs(lo), std::abs(hi)) / s > kMaxTickIndex) return {};
  const auto first = int64_t(std::ceil(lo / s - 1e-9)), last = int64_t(std::floor(hi / s + 1e-9));
  if (last - first > kMaxTicks) return {};  // only a range too wide for a double's step gets here
  const double largest = std::max(std::abs(double(first)), std::abs(double(last))) * s;
  const bool compact = compactAllowed && largest >= 1e4;
  std::vector<Tick> ticks;
  for (int64_t n = first; n <= last; ++n)
    ticks.push_back({double(n) * s, formatAxisNumber(n * step.mantissa, step.exp10, compact)});
  return ticks;
}

struct Axes {
  LineChartLayout layout;
  std::vector<Tick> xTicks, yTicks;
};

Axes axesOf(const LineChart& c) {
  const int width = std::max(c.width, kMinWidth), height = std::max(c.height, kMinHeight);
  size_t frames = 0;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Series& s : c.series) {
    frames = std::max(frames, s.values.size());
    for (double v : s.values)
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  }
  for (double v : c.hLines)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  const bool any = lo <= hi;

  Axes a;
  LineChartLayout& l = a.layout;
  l.yMin = std::isfinite(c.yMin) ? c.yMin : (any && lo < 0.0 ? -niceAtLeast(-lo).value() : 0.0);
  l.yMax = std::isfinite(c.yMax) ? c.yMax : (any && hi > 0.0 ? niceAtLeast(hi).value() : (l.yMin < 0.0 ? 0.0 : 1.0));
  if (!(l.yMax > l.yMin)) l.yMax = l.yMin + 1.0;
  // A span that overflows would turn every position into NaN; such a range has nothing to show
  // beyond +-1e307 anyway.
  if (!std::isfinite(l.yMax - l.yMin)) l.yMin = std::max(l.yMin, -1e307), l.yMax = std::min(l.yMax, 1e307);

  // Rows: title, plot, x tick labels, x label. Columns: y label, y tick labels, plot, half of the
  // last x tick label.
  l.top = c.title.empty() ? kPad + kTextH : kPad + kTextH + 12;
  l.bottom = height - kPad - (c.xLabel.empty() ? 0 : kTextH + 6) - kTextH - kTickGap - kTick;
  l.bottom = std::max(l.bottom, l.top + 1);
  const double ySpan = l.yMax - l.yMin;
  const int yTicks = std::max(2, (l.bottom - l.top) / kRowsPerYTick);
  a.yTicks = ticksOf(l.yMin, l.yMax, niceAtLeast(ySpan / yTicks), true);
  int labelW = 0;
  for (const Tick& t : a.yTicks) labelW = std::max(labelW, RgbaCanvas::textWidth(t.label, kScale));
  l.left = kPad + (c.yLabel.empty() ? 0 : kTextH + 8) + labelW + kTickGap + kTick;
  l.right = std::max(width - kPad - 16, l.left + 1);

  // Frames are integers, so the x step is at least 1.
  const int64_t lastFrame = std::max<int64_t>(int64_t(frames) - 1, 1);
  const int xTicks = std::max(2, (l.right - l.left) / kColumnsPerXTick);
  Nice xStep = niceAtLeast(double(lastFrame) / xTicks);
  if (xStep.exp10 < 0) xStep = {1, 0};
  const auto step = int64_t(xStep.value());
  l.xEnd = (lastFrame + step - 1) / step * step;
  a.xTicks = ticksOf(0.0, double(l.xEnd), xStep, true);
  return a;
}

// Draws the segment between two exact plot positions, clipped to the plot's rows (columns are
// always inside), so values beyond [yMin, yMax] run off the edge instead of wrapping or overflowing.
void segment(RgbaCanvas& cv, const LineChartLayout& l, double x0, double y0, double x1, double y1, Rgba color,
             int thickness, Dash* dash) {
  const double top = l.top, bottom = l.bottom;
  if (!std::isfinite(y0) || !std::isfinite(y1)) return;
  if ((y0 < top && y1 < top) || (y0 > bottom && y1 > bottom)) return;
  double t0 = 0.0, t1 = 1.0;
  const double dy = y1 - y0;
  if (dy != 0.0) {
    const double ta = (top - y0) / dy, tb = (bottom - y0) / dy;
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
    if (t0 > t1) return;
  }
  const double ax = x0 + (x1 - x0) * t0, ay = y0 + dy * t0, bx = x0 + (x1 - x0) * t1, by = y0 + dy * t1;
  cv.line(int(std::lround(ax)), int(std::lround(ay)), int(std::lround(bx)), int(std::lround(by)), color, thickness,
          dash);
}

void drawSeries(RgbaCanvas& cv, const LineChartLayout& l, const Series& s) {
  const int t = std::clamp(s.thickness, 1, kMaxThickness);
  Dash dash{kDashOn, kDashOff, 0};
  Dash* d = s.dashed ? &dash : nullptr;
  const std::vector<double>& v = s.values;
  for (size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) continue;
    const double x = l.xPixel(int64_t(i)), y = l.yExact(v[i]);
    const bool next = i + 1 < v.size() && std::isfinite(v[i + 1]);
    const bool prev = i > 0 && std::isfinite(v[i - 1]);
    if (next)
      segment(cv, l, x, y, l.xPixel(int64_t(i + 1)), l.yExact(v[i + 1]), s.color, t, d);
    else if (!prev)
      segment(cv, l, x, y, x, y, s.color, t, nullptr);  // an isolated value: a dot
  }
}

// Pixels in the rectangle that carry data: neither the background nor a grid line.
int64_t coveredPixels(const RgbaCanvas& cv, int x, int y, int w, int h) {
  int64_t n = 0;
  for (int yy = std::max(y, 0); yy < std::min(y + h, cv.height()); ++yy)
    for (int xx = std::max(x, 0); xx < std::min(x + w, cv.width()); ++xx) {
      const uint8_t* p = cv.data() + (size_t(yy) * size_t(cv.width()) + size_t(xx)) * 4;
      const Rgba c{p[0], p[1], p[2], p[3]};
      n += c != kWhite && c != kGrid ? 1 : 0;
    }
  return n;
}

void drawLegend(RgbaCanvas& cv, const LineChartLayout& l, const std::vector<Series>& series) {
  if (series.empty()) return;
  constexpr int kInset = 6, kBoxPad = 6, kSwatch = 24, kSwatchGap = 8, kRow = kTextH + 4;
  int labelW = 0;
  for (const Series& s : series) labelW = std::max(labelW, RgbaCanvas::textWidth(s.label, kScale));
  const int w = kBoxPad + kSwatch + kSwatchGap + labelW + kBoxPad;
  const int h = kBoxPad + int(series.size()) * kRow - 4 + kBoxPad;
  // Candidates in order of preference: top right, top left, bottom right, bottom left.
  const int xs[2] = {std::max(l.right - kInset - w, l.left + 1 + kInset), l.left + 1 + kInset};
  const int ys[2] = {l.top + kInset, std::max(l.bottom - kInset - h, l.top + kInset)};
  int bx = xs[0], by = ys[0];
  int64_t best = std::numeric_limits<int64_t>::max();
  for (int yi = 0; yi < 2; ++yi)
    for (int xi = 0; xi < 2; ++xi) {
      const int64_t n = coveredPixels(cv, xs[xi], ys[yi], w, h);
      if (n < best) best = n, bx = xs[xi], by = ys[yi];
    }
  cv.fillRect(bx, by, w, h, kWhite);
  cv.fillRect(bx, by, w, 1, kLegendBorder);
  cv.fillRect(bx, by + h - 1, w, 1, kLegendBorder);
  cv.fillRect(bx, by, 1, h, kLegendBorder);
  cv.fillRect(bx + w - 1, by, 1, h, kLegendBorder);
  for (size_t i = 0; i < series.size(); ++i) {
    const Series& s = series[i];
    const int rowY = by + kBoxPad + int(i) * kRow, mid = rowY + kTextH / 2;
    // The swatch is at most as thick as the text, so a thick series does not swallow its row.
    Dash dash{kDashOn, kDashOff, 0};
    cv.line(bx + kBoxPad, mid, bx + kBoxPad + kSwatch - 1, mid, s.color, std::clamp(s.thickness, 1, kTextH - 2),
            s.dashed ? &dash : nullptr);
    cv.text(bx + kBoxPad + kSwatch + kSwatchGap, rowY, s.label, kInk, kScale);
  }
}

}  // namespace

int LineChartLayout::xPixel(int64_t frame) const {
  const int64_t span = right - left;
  return left + int((2 * frame * span + xEnd) / (2 * xEnd));
}

double LineChartLayout::yExact(double value) const {
  return double(bottom) - (value - yMin) / (yMax - yMin) * double(bottom - top);
}

int LineChartLayout::yPixel(double value) const { return int(std::lround(yExact(value))); }

LineChartLayout lineChartLayout(const LineChart& chart) { return axesOf(chart).layout; }

std::string formatAxisNumber(int64_t digits, int exp10, bool compact) {
  if (digits == 0) return "0";
  const bool negative = digits < 0;
  // Unsigned, so that the magnitude of INT64_MIN is representable.
  uint64_t n = negative ? 0 - uint64_t(digits) : uint64_t(digits);
  while (n % 10 == 0) n /= 10, ++exp10;
  const std::string d = std::to_string(n);     // integer formatting never consults the locale
  const int lead = int(d.size()) - 1 + exp10;  // the power of ten of the leading digit
  std::string out = negative ? "-" : "";
  if (lead >= 15 || lead <= -5) {
    out += d[0];
    if (d.size() > 1) out.append(".").append(d, 1);
    return out.append("e").append(std::to_string(lead));
  }
  const char* suffix = "";
  int top = lead;
  if (compact && lead >= 3) {
    static constexpr const char* kSuffix[] = {"k", "M", "G", "T"};
    const int group = std::min(lead / 3, 4);
    suffix = kSuffix[group - 1];
    top -= 3 * group, exp10 -= 3 * group;
  }
  // One character per power of ten, from the leading digit (or the units) down to the last digit
  // (or the units): zeros pad both ends, and the point goes before the tenths.
  for (int p = std::max(top, 0); p >= std::min(exp10, 0); --p) {
    if (p == -1) out += '.';
    const int k = top - p;
    out += k >= 0 && k < int(d.size()) ? d[size_t(k)] : '0';
  }
  return out.append(suffix);
}

RgbaCanvas drawLineChart(const LineChart& chart) {
  const Axes a = axesOf(chart);
  const LineChartLayout& l = a.layout;
  RgbaCanvas cv(std::max(chart.width, kMinWidth), std::max(chart.height, kMinHeight), kWhite);

  // Grid first, so that reference lines, series and axes cover it.
  for (const Tick& t : a.yTicks) {
    const int y = l.yPixel(t.value);
    if (y != l.bottom) cv.fillRect(l.left + 1, y, l.right - l.left, 1, kGrid);
  }
  for (const Tick& t : a.xTicks) {
    const int x = l.xPixel(int64_t(std::llround(t.value)));
    if (x != l.left) cv.fillRect(x, l.top, 1, l.bottom - l.top, kGrid);
  }
  for (double h : chart.hLines) {
    if (!std::isfinite(h) || h < l.yMin || h > l.yMax) continue;
    Dash dash{kDashOn, kDashOff, 0};
    const int y = l.yPixel(h);
    cv.line(l.left + 1, y, l.right, y, kReference, 1, &dash);
  }

  // Axes before the series: a run of zeros lies on the x axis and must stay visible.
  cv.fillRect(l.left, l.top, 1, l.bottom - l.top + 1, kInk);
  cv.fillRect(l.left, l.bottom, l.right - l.left + 1, 1, kInk);
  for (const Tick& t : a.yTicks) {
    const int y = l.yPixel(t.value);
    cv.fillRect(l.left - kTick, y, kTick, 1, kInk);
    const int x = l.left - kTick - kTickGap - RgbaCanvas::textWidth(t.label, kScale);
    cv.text(x, y - kTextH / 2, t.label, kInk, kScale);
  }
  for (const Tick& t : a.xTicks) {
    const int x = l.xPixel(int64_t(std::llround(t.value)));
    cv.fillRect(x, l.bottom + 1, 1, kTick, kInk);
    cv.text(x - RgbaCanvas::textWidth(t.label, kScale) / 2, l.bottom + kTick + kTickGap, t.label, kInk, kScale);
  }

  for (const Series& s : chart.series) drawSeries(cv, l, s);
  drawLegend(cv, l, chart.series);

  const int plotMid = (l.left + l.right) / 2;
  if (!chart.title.empty())
    cv.text(std::max(kPad, plotMid - RgbaCanvas::textWidth(chart.title, kScale) / 2), kPad, chart.title, kInk, kScale);
  if (!chart.xLabel.empty())
    cv.text(plotMid - RgbaCanvas::textWidth(chart.xLabel, kScale) / 2, l.bottom + kTick + kTickGap + kTextH + 6,
            chart.xLabel, kInk, kScale);
  if (!chart.yLabel.empty())
    cv.textUp(kPad, (l.top + l.bottom) / 2 - RgbaCanvas::textWidth(chart.yLabel, kScale) / 2, chart.yLabel, kInk,
              kScale);
  return cv;
}

RgbaCanvas stackCharts(const std::vector<RgbaCanvas>& charts) {
  int width = 0, height = 0;
  for (const RgbaCanvas& c : charts) width = std::max(width, c.width()), height += c.height();
  RgbaCanvas out(width, height, kWhite);
  int y0 = 0;
  for (const RgbaCanvas& c : charts) {
    for (int y = 0; y < c.height(); ++y)
      for (int x = 0; x < c.width(); ++x) {
        const uint8_t* p = c.data() + (size_t(y) * size_t(c.width()) + size_t(x)) * 4;
        out.set(x, y0 + y, {p[0], p[1], p[2], p[3]});
      }
    y0 += c.height();
  }
  return out;
}

}  // namespace tessera::verify
