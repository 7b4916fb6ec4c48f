#include "verify/rgba_canvas.h"

#include <algorithm>
#include <cstddef>

namespace tessera::verify {

namespace {

// 3x5 glyphs, one row per entry, bit 2 = left column.
struct Glyph {
  char c;
  uint8_t rows[5];
};
constexpr Glyph kFont[] = {
    {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}}, {'2', {7, 1, 7, 4, 7}}, {'3', {7, 1, 7, 1, 7}},
    {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}}, {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 1, 1}},
    {'8', {7, 5, 7, 5, 7}}, {'9', {7, 5, 7, 1, 7}}, {'-', {0, 0, 7, 0, 0}}, {'+', {0, 2, 7, 2, 0}},
    {'.', {0, 0, 0, 0, 2}}, {'%', {5, 1, 2, 4, 5}}, {'>', {4, 2, 1, 2, 4}}, {' ', {0, 0, 0, 0, 0}},
    {'N', {5, 7, 7, 7, 5}}, {'a', {0, 6, 3, 5, 7}}, {'L', {4, 4, 4, 4, 7}}, {'S', {7, 4, 7, 1, 7}},
    {'B', {6, 5, 6, 5, 6}}, {'i', {2, 0, 2, 2, 2}}, {'n', {0, 6, 5, 5, 5}}, {'f', {3, 4, 6, 4, 4}},
};

const uint8_t* glyphRows(char c) {
  static constexpr uint8_t box[5] = {7, 5, 5, 5, 7};
  for (const Glyph& g : kFont)
    if (g.c == c) return g.rows;
  return box;
}

}  // namespace

RgbaCanvas::RgbaCanvas(int width, int height, Rgba background)
    : w_(width), h_(height), px_(size_t(width) * size_t(height) * 4) {
  fillRect(0, 0, width, height, background);
}

void RgbaCanvas::set(int x, int y, Rgba c) {
  if (x < 0 || y < 0 || x >= w_ || y >= h_) return;
  std::copy(c.begin(), c.end(), px_.begin() + (std::ptrdiff_t(y) * w_ + x) * 4);
}

void RgbaCanvas::fillRect(int x, int y, int w, int h, Rgba c) {
  const int x0 = std::max(x, 0), y0 = std::max(y, 0), x1 = std::min(x + w, w_), y1 = std::min(y + h, h_);
  for (int yy = y0; yy < y1; ++yy)
    for (int xx = x0; xx < x1; ++xx) std::copy(c.begin(), c.end(), px_.begin() + (std::ptrdiff_t(yy) * w_ + xx) * 4);
}

void RgbaCanvas::text(int x, int y, std::string_view s, Rgba c, int scale) {
  for (char ch : s) {
    const uint8_t* rows = glyphRows(ch);
    for (int r = 0; r < 5; ++r)
      for (int col = 0; col < 3; ++col)
        if (rows[r] >> (2 - col) & 1) fillRect(x + col * scale, y + r * scale, scale, scale, c);
    x += 4 * scale;
  }
}

int RgbaCanvas::textWidth(std::string_view s, int scale) { return s.empty() ? 0 : int(s.size()) * 4 * scale - scale; }

}  // namespace tessera::verify
