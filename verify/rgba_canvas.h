// A minimal RGBA8 drawing surface for report images (heat map legend, histogram, line charts):
// filled rectangles, lines and text in a built-in 3x5 pixel font, so no plotting or font library is
// needed.
//
// Implements: fill, rectangle, Bresenham lines (square brush, optional dash pattern), text in the 3x5
// font (every printable ASCII character: digits, both cases of letters, punctuation; other
// characters draw as a box) left to right or rotated to read bottom to top, integer scaling of the
// font.
// Does not implement: anti-aliasing, blending, clipping other than to the canvas, proportional or
// larger fonts, file output (writePngRGBA8 in raster/image_io.h).
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

namespace tessera::verify {

using Rgba = std::array<uint8_t, 4>;

// A dash pattern for RgbaCanvas::line: `on` brush steps drawn, then `off` skipped. `at` is the
// position in the pattern; line() advances it by one per step, so passing the same Dash to the
// segments of a polyline keeps the dashes running across its vertices.
struct Dash {
  int on = 0, off = 0;
  int at = 0;
};

class RgbaCanvas {
 public:
  RgbaCanvas(int width, int height, Rgba background);
  int width() const { return w_; }
  int height() const { return h_; }
  // Top-left origin, rows top-down (as PNG files store them).
  void set(int x, int y, Rgba c);
  void fillRect(int x, int y, int w, int h, Rgba c);  // clipped to the canvas
  // Stamps a thickness x thickness square (thickness < 1 counts as 1; for even sizes the extra pixel
  // goes right / down) at every step of the Bresenham line from (x0, y0) to (x1, y1), both ends
  // included. A null or empty dash draws a solid line. Clipped to the canvas; the cost is the length
  // of the line, so callers clip lines that are far outside.
  void line(int x0, int y0, int x1, int y1, Rgba c, int thickness = 1, Dash* dash = nullptr);
  void text(int x, int y, std::string_view s, Rgba c, int scale = 1);
  // The same glyphs turned 90 degrees counter-clockwise, reading bottom to top (a y-axis label).
  // (x, y) is the top-left of the turned text: it covers kGlyphHeight * scale columns from x and
  // textWidth(s, scale) rows from y.
  void textUp(int x, int y, std::string_view s, Rgba c, int scale = 1);
  static int textWidth(std::string_view s, int scale = 1);  // advance 4 px per glyph at scale 1
  static constexpr int kGlyphHeight = 5;
  const uint8_t* data() const { return px_.data(); }

 private:
  int w_, h_;
  std::vector<uint8_t> px_;
};

}  // namespace tessera::verify
