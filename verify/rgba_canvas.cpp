#include "verify/rgba_canvas.h"

#include <algorithm>
#include <cstddef>
#include <cstdlib>

namespace tessera::verify {

namespace {

// 3x5 glyphs, one row per entry, bit 2 = left column.
struct Glyph {
  char c;
  uint8_t rows[5];
};
// The first 24 glyphs predate the rest; report images already made with them must not change, so
// they stay as they are even where the newer letters would draw them differently (S is the 5).
// Lower-case letters use rows 1-4 with row 0 for ascenders; there is no room for descenders, so g, p,
// q, y sit on the baseline. O is rounded because the square 0 doubles as the unknown-character box.
constexpr Glyph kFont[] = {
    {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}}, {'2', {7, 1, 7, 4, 7}}, {'3', {7, 1, 7, 1, 7}},
    {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}}, {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 1, 1}},
    {'8', {7, 5, 7, 5, 7}}, {'9', {7, 5, 7, 1, 7}}, {'-', {0, 0, 7, 0, 0}}, {'+', {0, 2, 7, 2, 0}},
    {'.', {0, 0, 0, 0, 2}}, {'%', {5, 1, 2, 4, 5}}, {'>', {4, 2, 1, 2, 4}}, {' ', {0, 0, 0, 0, 0}},
    {'N', {5, 7, 7, 7, 5}}, {'a', {0, 6, 3, 5, 7}}, {'L', {4, 4, 4, 4, 7}}, {'S', {7, 4, 7, 1, 7}},
    {'B', {6, 5, 6, 5, 6}}, {'i', {2, 0, 2, 2, 2}}, {'n', {0, 6, 5, 5, 5}}, {'f', {3, 4, 6, 4, 4}},
    // Upper case.
    {'A', {2, 5, 7, 5, 5}}, {'C', {3, 4, 4, 4, 3}}, {'D', {6, 5, 5, 5, 6}}, {'E', {7, 4, 6, 4, 7}},
    {'F', {7, 4, 6, 4, 4}}, {'G', {3, 4, 5, 5, 3}}, {'H', {5, 5, 7, 5, 5}}, {'I', {7, 2, 2, 2, 7}},
    {'J', {1, 1, 1, 5, 2}}, {'K', {5, 5, 6, 5, 5}}, {'M', {5, 7, 7, 5, 5}}, {'O', {2, 5, 5, 5, 2}},
    {'P', {6, 5, 6, 4, 4}}, {'Q', {2, 5, 5, 2, 1}}, {'R', {6, 5, 6, 5, 5}}, {'T', {7, 2, 2, 2, 2}},
    {'U', {5, 5, 5, 5, 7}}, {'V', {5, 5, 5, 5, 2}}, {'W', {5, 5, 7, 7, 5}}, {'X', {5, 5, 2, 5, 5}},
    {'Y', {5, 5, 2, 2, 2}}, {'Z', {7, 1, 2, 4, 7}},
    // Lower case.
    {'b', {4, 4, 6, 5, 6}}, {'c', {0, 3, 4, 4, 3}}, {'d', {1, 1, 3, 5, 3}}, {'e', {0, 2, 7, 4, 3}},
    {'g', {0, 3, 5, 3, 6}}, {'h', {4, 4, 6, 5, 5}}, {'j', {1, 0, 1, 5, 2}}, {'k', {4, 4, 5, 6, 5}},
    {'l', {6, 2, 2, 2, 3}}, {'m', {0, 7, 7, 5, 5}}, {'o', {0, 2, 5, 5, 2}}, {'p', {0, 6, 5, 6, 4}},
    {'q', {0, 3, 5, 3, 1}}, {'r', {0, 5, 6, 4, 4}}, {'s', {0, 3, 6, 1, 6}}, {'t', {2, 7, 2, 2, 1}},
    {'u', {0, 5, 5, 5, 3}}, {'v', {0, 5, 5, 5, 2}}, {'w', {0, 5, 5, 7, 5}}, {'x', {0, 5, 2, 2, 5}},
    {'y', {0, 5, 5, 2, 4}}, {'z', {0, 7, 1, 2, 7}},
    // Punctuation.
    {'!', {2, 2, 2, 0, 2}}, {'"', {5, 5, 0, 0, 0}}, {'#', {5, 7, 5, 7, 5}}, {'$', {3, 6, 2, 3, 6}},
    {'&', {2, 5, 2, 5, 3}}, {'\'', {2, 2, 0, 0, 0}}, {'(', {1, 2, 2, 2, 1}}, {')', {4, 2, 2, 2, 4}},
    {'*', {0, 5, 2, 5, 0}}, {',', {0, 0, 0, 2, 4}}, {'/', {1, 1, 2, 4, 4}}, {':', {0, 2, 0, 2, 0}},
    {';', {0, 2, 0, 2, 4}}, {'<', {1, 2, 4, 2, 1}}, {'=', {0, 7, 0, 7, 0}}, {'?', {6, 1, 2, 0, 2}},
    {'@', {2, 5, 7, 4, 3}}, {'[', {6, 4, 4, 4, 6}}, {'\\', {4, 4, 2, 1, 1}}, {']', {3, 1, 1, 1, 3}},
    {'^', {2, 5, 0, 0, 0}}, {'_', {0, 0, 0, 0, 7}}, {'`', {4, 2, 0, 0, 0}}, {'{', {3, 2, 6, 2, 3}},
    {'|', {2, 2, 2, 2, 2}}, {'}', {6, 2, 3, 2, 6}}, {'~', {0, 3, 6, 0, 0}},
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

void RgbaCanvas::line(int x0, int y0, int x1, int y1, Rgba c, int thickness, Dash* dash) {
  const int t = std::max(thickness, 1), back = (t - 1) / 2;
  const bool dashed = dash && dash->on > 0 && dash->off > 0;
  // Integer Bresenham (all octants): the pixels do not depend on floating-point rounding.
  const int dx = std::abs(x1 - x0), sx = x0 < x1 ? 1 : -1;
  const int dy = -std::abs(y1 - y0), sy = y0 < y1 ? 1 : -1;
  int err = dx + dy;
  for (;;) {
    if (!dashed || dash->at % (dash->on + dash->off) < dash->on) fillRect(x0 - back, y0 - back, t, t, c);
    if (dashed) dash->at = (dash->at + 1) % (dash->on + dash->off);
    if (x0 == x1 && y0 == y1) break;
    const int e2 = 2 * err;
    if (e2 >= dy) err += dy, x0 += sx;
    if (e2 <= dx) err += dx, y0 += sy;
  }
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

void RgbaCanvas::textUp(int x, int y, std::string_view s, Rgba c, int scale) {
  // Unturned, a cell starts at u along the text and v down; turned, u runs up from the bottom row.
  const int bottom = y + textWidth(s, scale);
  int u = 0;
  for (char ch : s) {
    const uint8_t* rows = glyphRows(ch);
    for (int r = 0; r < 5; ++r)
      for (int col = 0; col < 3; ++col)
        if (rows[r] >> (2 - col) & 1) fillRect(x + r * scale, bottom - (u + col * scale) - scale, scale, scale, c);
    u += 4 * scale;
  }
}

int RgbaCanvas::textWidth(std::string_view s, int scale) { return s.empty() ? 0 : int(s.size()) * 4 * scale - scale; }

}  // namespace tessera::verify
