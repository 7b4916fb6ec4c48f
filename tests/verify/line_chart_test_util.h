// Helpers shared by the line chart tests (test_line_chart.cpp, test_line_chart_example.cpp): the
// colours they use, pixel access, glyph dumps and the 300-frame example chart.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "verify/line_chart.h"
#include "verify/rgba_canvas.h"

namespace tessera::verify::chart_test {

constexpr Rgba kWhite{255, 255, 255, 255};
constexpr Rgba kBlack{0, 0, 0, 255};
constexpr Rgba kRed{220, 30, 30, 255};
constexpr Rgba kBlue{30, 90, 200, 255};
constexpr Rgba kGreen{20, 150, 60, 255};

inline Rgba pixel(const RgbaCanvas& c, int x, int y) {
  const uint8_t* p = c.data() + (size_t(y) * size_t(c.width()) + size_t(x)) * 4;
  return {p[0], p[1], p[2], p[3]};
}

inline int count(const RgbaCanvas& c, Rgba color) {
  int n = 0;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x) n += pixel(c, x, y) == color ? 1 : 0;
  return n;
}

// One glyph as '#' / '.' rows.
inline std::vector<std::string> glyphPixels(char ch) {
  RgbaCanvas c(3, 5, kWhite);
  c.text(0, 0, std::string_view(&ch, 1), kBlack);
  std::vector<std::string> rows(5);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 3; ++x) rows[size_t(y)] += pixel(c, x, y) == kBlack ? '#' : '.';
  return rows;
}

// A 300-frame chart in the style of the thesis figures, with every feature switched on.
inline LineChart exampleChart() {
  std::vector<double> binds(300), draws(300), bytes(300);
  for (int i = 0; i < 300; ++i) {
    binds[size_t(i)] = 40.0 + double((i * 37) % 23) + (i > 150 ? 30.0 : 0.0);
    draws[size_t(i)] = 90.0 - double(i) / 5.0;
    bytes[size_t(i)] = i >= 100 && i < 120 ? NAN : double(i % 60) * 2.0;
  }
  LineChart c{"Texture binds per frame",
              "frame",
              "count",
              {{"texture_binds", binds, kBlue, false, 2},
               {"draw_calls", draws, kRed, true, 1},
               {"bytes resident (MiB)", bytes, kGreen, false, 1}}};
  c.hLines = {110.0};
  return c;
}

}  // namespace tessera::verify::chart_test
