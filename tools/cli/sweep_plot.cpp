#include "tools/cli/sweep_plot.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "verify/line_chart.h"

namespace tessera::cli {

namespace {

using verify::Rgba;
using verify::RgbaCanvas;

constexpr int kPanelW = 660, kPanelH = 440, kScale = 2;
constexpr int kLeft = 70, kRight = 20, kTop = 40, kBottom = 50;
const Rgba kInk{0, 0, 0, 255}, kGrid{225, 225, 225, 255}, kMajor{190, 190, 190, 255};

struct Axis {
  int lo = 0, hi = 1;                         // decades: 10^lo .. 10^hi
  double pos(double v, int a, int b) const {  // pixel between a (10^lo) and b (10^hi)
    const double t = (std::log10(v) - lo) / double(hi - lo);
    return a + t * (b - a);
  }
};

Axis decades(double mn, double mx) {
  if (!(mn > 0) || !(mx > 0)) return {0, 1};
  Axis a{int(std::floor(std::log10(mn))), int(std::ceil(std::log10(mx)))};
  if (a.hi <= a.lo) a.hi = a.lo + 1;
  return a;
}

void drawPanel(RgbaCanvas& c, int ox, int oy, const PlotPanel& p) {
  double xmin = std::numeric_limits<double>::infinity(), xmax = 0, ymin = xmin, ymax = 0;
  for (const PlotLine& l : p.lines)
    for (size_t i = 0; i < l.x.size() && i < l.ms.size(); ++i) {
      if (!(l.x[i] > 0) || !(l.ms[i] > 0)) continue;
      xmin = std::min(xmin, l.x[i]), xmax = std::max(xmax, l.x[i]);
      ymin = std::min(ymin, l.ms[i]), ymax = std::max(ymax, l.ms[i]);
    }
  const Axis ax = decades(xmin, xmax), ay = decades(ymin, ymax);
  const int left = ox + kLeft, right = ox + kPanelW - kRight, top = oy + kTop, bottom = oy + kPanelH - kBottom;
  c.text(ox + kLeft, oy + 10, p.title, kInk, kScale);
  // Grid: 1..9 x 10^k, the decades darker and labelled.
  for (int k = ax.lo; k <= ax.hi; ++k)
    for (int m = 1; m <= (k == ax.hi ? 1 : 9); ++m) {
      const int x = int(std::lround(ax.pos(m * std::pow(10.0, k), left, right)));
      c.line(x, top, x, bottom, m == 1 ? kMajor : kGrid);
      if (m == 1) {
        const std::string s = verify::formatAxisNumber(1, k, true);
        c.text(x - RgbaCanvas::textWidth(s, kScale) / 2, bottom + 6, s, kInk, kScale);
      }
    }
  for (int k = ay.lo; k <= ay.hi; ++k)
    for (int m = 1; m <= (k == ay.hi ? 1 : 9); ++m) {
      const int y = int(std::lround(ay.pos(m * std::pow(10.0, k), bottom, top)));
      c.line(left, y, right, y, m == 1 ? kMajor : kGrid);
      if (m == 1) {
        const std::string s = verify::formatAxisNumber(1, k, true);
        c.text(left - 6 - RgbaCanvas::textWidth(s, kScale), y - kScale * 2, s, kInk, kScale);
      }
    }
  c.line(left, bottom, right, bottom, kInk);
  c.line(left, top, left, bottom, kInk);
  c.text((left + right - RgbaCanvas::textWidth(p.xLabel, kScale)) / 2, bottom + 26, p.xLabel, kInk, kScale);
  c.textUp(ox + 6, (top + bottom - RgbaCanvas::textWidth("ms", kScale)) / 2, "ms", kInk, kScale);
  // Lines and markers first, then the notes on white boxes: at each point, a note goes above its marker
  // when no other noted line is higher there, else below, so two renderers' notes at one x part.
  const auto px = [&](double v) { return int(std::lround(ax.pos(v, left, right))); };
  const auto py = [&](double v) { return int(std::lround(ay.pos(v, bottom, top))); };
  const auto valid = [](const PlotLine& l, size_t i) {
    return i < l.x.size() && i < l.ms.size() && l.x[i] > 0 && l.ms[i] > 0;
  };
  for (const PlotLine& l : p.lines) {
    bool have = false;
    int lx = 0, ly = 0;
    for (size_t i = 0; i < l.x.size(); ++i) {
      if (!valid(l, i)) continue;
      const int x = px(l.x[i]), y = py(l.ms[i]);
      if (have) c.line(lx, ly, x, y, l.color, 2);
      c.fillRect(x - 3, y - 3, 7, 7, l.color);
      lx = x, ly = y, have = true;
    }
  }
  for (size_t li = 0; li < p.lines.size(); ++li) {
    const PlotLine& l = p.lines[li];
    for (size_t i = 0; i < l.notes.size(); ++i) {
      if (l.notes[i].empty() || !valid(l, i)) continue;
      bool highest = true;
      for (size_t o = 0; o < p.lines.size(); ++o)
        if (o != li && i < p.lines[o].notes.size() && !p.lines[o].notes[i].empty() && valid(p.lines[o], i) &&
            (p.lines[o].ms[i] > l.ms[i] || (p.lines[o].ms[i] == l.ms[i] && o < li)))
          highest = false;
      const int x = px(l.x[i]), y = py(l.ms[i]);
      const int w = RgbaCanvas::textWidth(l.notes[i], kScale), th = RgbaCanvas::kGlyphHeight * kScale;
      const int nx = std::clamp(x - w / 2, left + 2, right - w - 2);
      const int ny = highest ? y - 8 - th : y + 8;
      c.fillRect(nx - 2, ny - 2, w + 3, th + 4, Rgba{255, 255, 255, 255});
      c.text(nx, ny, l.notes[i], l.color, kScale);
    }
  }
  int legendY = top + 6;
  for (const PlotLine& l : p.lines) {
    c.fillRect(left + 10, legendY + 2, 14, 6, l.color);
    c.text(left + 30, legendY, l.label, kInk, kScale);
    legendY += 16;
  }
  c.text(left + 10, legendY + 2, "numbers: llvmpipe ms / oracle ms", kInk, kScale);
}

}  // namespace

verify::RgbaCanvas drawSweepPlot(const std::vector<PlotPanel>& panels) {
  const int cols = panels.size() > 1 ? 2 : 1, rows = int((panels.size() + size_t(cols) - 1) / size_t(cols));
  RgbaCanvas c(cols * kPanelW, std::max(1, rows) * kPanelH, Rgba{255, 255, 255, 255});
  for (size_t i = 0; i < panels.size(); ++i)
    drawPanel(c, int(i % size_t(cols)) * kPanelW, int(i / size_t(cols)) * kPanelH, panels[i]);
  return c;
}

}  // namespace tessera::cli
