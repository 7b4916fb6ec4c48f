// A minimal RGBA8 drawing surface for report images (heat map legend, histogram): filled
// rectangles and text in a built-in 3x5 pixel font, so no plotting or font library is needed.
//
// Implements: fill, rectangle, text (digits, '+', '-', '.', '%', '>', ' ', and the letters of
// "NaN", "LSB" and "inf"; other characters draw as a box), integer scaling of the font.
// Does not implement: anti-aliasing, blending, file output (writePngRGBA8 in raster/image_io.h).
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

namespace tessera::verify {

using Rgba = std::array<uint8_t, 4>;

class RgbaCanvas {
 public:
  RgbaCanvas(int width, int height, Rgba background);
  int width() const { return w_; }
  int height() const { return h_; }
  // Top-left origin, rows top-down (as PNG files store them).
  void set(int x, int y, Rgba c);
  void fillRect(int x, int y, int w, int h, Rgba c);  // clipped to the canvas
  void text(int x, int y, std::string_view s, Rgba c, int scale = 1);
  static int textWidth(std::string_view s, int scale = 1);  // advance 4 px per glyph at scale 1
  static constexpr int kGlyphHeight = 5;
  const uint8_t* data() const { return px_.data(); }

 private:
  int w_, h_;
  std::vector<uint8_t> px_;
};

}  // namespace tessera::verify
