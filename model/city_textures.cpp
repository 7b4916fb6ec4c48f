// The city generator's procedural textures: integer arithmetic only, every texel a pure function of
// the texture's spec, so the bytes are the same on every machine, thread count and build type.
// Patterns are flat colours with blocky variation rather than per-texel noise: real facades are
// like that, and it keeps the PNGs small (10,000 Berlin facades are 7.32 GiB raw).
#include <algorithm>

#include "model/city_scene.h"

namespace tessera::model::city {

namespace {

using Rgba = std::array<uint8_t, 4>;

struct Canvas {
  uint32_t w, h, ch;
  std::vector<uint8_t> px;
  Canvas(uint32_t w_, uint32_t h_, uint32_t ch_) : w(w_), h(h_), ch(ch_), px(size_t(w_) * h_ * ch_, 0) {}
  void set(uint32_t x, uint32_t y, Rgba c) {
    if (x >= w || y >= h) return;
    uint8_t* p = &px[(size_t(y) * w + x) * ch];
    for (uint32_t k = 0; k < ch; ++k) p[k] = c[k];
  }
  void rect(int64_t x0, int64_t y0, int64_t x1, int64_t y1, Rgba c) {  // [x0, x1) x [y0, y1), clipped
    for (int64_t y = std::max<int64_t>(y0, 0); y < std::min<int64_t>(y1, h); ++y)
      for (int64_t x = std::max<int64_t>(x0, 0); x < std::min<int64_t>(x1, w); ++x) set(uint32_t(x), uint32_t(y), c);
  }
};

uint32_t hash(uint64_t seed, uint64_t a, uint64_t b = 0) { return uint32_t(mix(seed ^ mix(a * 0x100000001b3ull + b))); }

uint8_t clamp8(int v) { return uint8_t(std::clamp(v, 0, 255)); }
Rgba shade(Rgba c, int d) { return {clamp8(c[0] + d), clamp8(c[1] + d), clamp8(c[2] + d), c[3]}; }
Rgba pick(const Rgba* palette, size_t n, uint32_t r) { return palette[r % n]; }

// 3x5 digits, one row per 3 bits (MSB = left), rows top to bottom.
constexpr uint8_t kDigits[10][5] = {{7, 5, 5, 5, 7}, {2, 6, 2, 2, 7}, {7, 1, 7, 4, 7}, {7, 1, 7, 1, 7},
                                    {5, 5, 7, 1, 1}, {7, 4, 7, 1, 7}, {7, 4, 7, 5, 7}, {7, 1, 1, 1, 1},
                                    {7, 5, 7, 5, 7}, {7, 5, 7, 1, 7}};

// Draws `number` in digits of cell size `s` with the top-left corner at (x, y).
void drawNumber(Canvas& c, int64_t x, int64_t y, int64_t s, uint32_t number, Rgba ink) {
  std::string digits = std::to_string(number);
  for (size_t i = 0; i < digits.size(); ++i) {
    const uint8_t* g = kDigits[digits[i] - '0'];
    for (int row = 0; row < 5; ++row)
      for (int col = 0; col < 3; ++col)
        if (g[row] >> (2 - col) & 1)
          c.rect(x + (int64_t(i) * 4 + col) * s, y + row * s, x + (int64_t(i) * 4 + col + 1) * s, y + (row + 1) * s,
                 ink);
  }
}

constexpr Rgba kPlaster[] = {{214, 200, 170, 255}, {190, 160, 130, 255}, {170, 175, 180, 255}, {220, 210, 190, 255},
                             {160, 90, 70, 255},   {200, 185, 150, 255}, {150, 150, 140, 255}, {230, 220, 205, 255},
                             {180, 120, 90, 255},  {120, 110, 100, 255}};

// One Berlin facade: 4 floors x 4 window columns (12 m x 12 m), bricks, lit or dark windows, and a
// plaque with the building number on the ground floor.
void berlinFacade(Canvas& c, const TexSpec& t) {
  const int64_t W = c.w, H = c.h, u = std::max<int64_t>(W / 128, 1);  // u: one "texel unit" at 512 = 4
  const Rgba wall = pick(kPlaster, std::size(kPlaster), hash(t.seed, 1));
  const int64_t bw = 8 * u, bh = 4 * u;  // bricks
  for (int64_t y = 0; y < H; ++y) {
    const int64_t row = y / bh, off = (row & 1) * bw / 2;
    for (int64_t x = 0; x < W; ++x) {
      const int64_t col = (x + off) / bw;
      const bool mortar = y % bh == 0 || (x + off) % bw == 0;
      c.set(uint32_t(x), uint32_t(y),
            mortar ? shade(wall, -30) : shade(wall, int(hash(t.seed, 2, uint64_t(row * 4096 + col)) % 13) - 6));
    }
  }
  const int64_t cw = W / 4, chh = H / 4;
  const Rgba frame = hash(t.seed, 3) & 1 ? Rgba{240, 240, 235, 255} : Rgba{60, 50, 45, 255};
  for (int fy = 0; fy < 4; ++fy)
    for (int fx = 0; fx < 4; ++fx) {
      const int64_t x0 = fx * cw + cw / 4, x1 = fx * cw + 3 * cw / 4, y0 = fy * chh + chh / 5,
                    y1 = fy * chh + 3 * chh / 4;
      c.rect(x0 - u, y0 - u, x1 + u, y1 + u, frame);
      const bool lit = hash(t.seed, 4, uint64_t(fy * 4 + fx)) % 3 == 0;
      for (int64_t y = y0; y < y1; ++y) {
        const int g = int((y - y0) * 40 / std::max<int64_t>(y1 - y0, 1));
        c.rect(x0, y, x1, y + 1,
               lit ? Rgba{clamp8(250 - g), clamp8(220 - g), 140, 255} : Rgba{40, clamp8(60 + g), clamp8(90 + g), 255});
      }
      c.rect((x0 + x1) / 2 - u / 2, y0, (x0 + x1) / 2 + (u + 1) / 2, y1, frame);  // mullion
      c.rect(x0 - 2 * u, y1 + u, x1 + 2 * u, y1 + 3 * u, shade(wall, -50));       // sill
    }
  // The plaque: the thesis made 10,000 textures out of 300 photographs by numbering them.
  // It sits in the wall between the third and fourth floor's windows, centred on the second column.
  const int64_t s = u, digits = int64_t(std::to_string(t.label).size());
  const int64_t pw = (digits * 4 - 1) * s, px = cw + cw / 2 - pw / 2, py = 2 * chh + 3 * chh / 4 + 5 * u;
  c.rect(px - s, py - s, px + pw + s, py + 6 * s, Rgba{250, 250, 245, 255});
  drawNumber(c, px, py, s, t.label, Rgba{20, 30, 120, 255});
}

// Chemnitz facade: one floor high, 1..3 windows across, plaster colour and frames per texture.
void facade(Canvas& c, const TexSpec& t) {
  const int64_t W = c.w, H = c.h, u = std::max<int64_t>(std::min(W, H) / 64, 1);
  const Rgba wall = pick(kPlaster, std::size(kPlaster), hash(t.seed, 1));
  const int64_t band = 2 + hash(t.seed, 2) % 6;
  for (int64_t y = 0; y < H; ++y) c.rect(0, y, W, y + 1, shade(wall, (y / (band * u)) % 2 ? -4 : 3));
  const int64_t n = 1 + hash(t.seed, 3) % 3;
  const Rgba frame = pick(kPlaster, std::size(kPlaster), hash(t.seed, 4) + 3);
  for (int64_t k = 0; k < n; ++k) {
    const int64_t cw = W / n, x0 = k * cw + cw / 5, x1 = (k + 1) * cw - cw / 5, y0 = H / 5, y1 = H * 4 / 5;
    c.rect(x0 - u, y0 - u, x1 + u, y1 + u, shade(frame, -60));
    const bool lit = hash(t.seed, 5, uint64_t(k)) % 4 == 0;
    c.rect(x0, y0, x1, y1, lit ? Rgba{240, 210, 130, 255} : Rgba{50, 70, 95, 255});
    c.rect(x0, (y0 + y1) / 2, x1, (y0 + y1) / 2 + u, shade(frame, -60));
  }
}

void roof(Canvas& c, const TexSpec& t) {
  constexpr Rgba kTiles[] = {{150, 60, 40, 255}, {110, 50, 40, 255}, {80, 80, 85, 255}, {120, 90, 60, 255}};
  const Rgba base = pick(kTiles, std::size(kTiles), hash(t.seed, 1));
  const int64_t W = c.w, H = c.h, th = std::max<int64_t>(H / 8, 2), tw = std::max<int64_t>(W / 8, 2);
  for (int64_t y = 0; y < H; ++y)
    for (int64_t x = 0; x < W; ++x) {
      const int64_t row = y / th, off = (row & 1) * tw / 2, col = (x + off) / tw;
      const int edge = (y % th) * 40 / th;  // tiles darken toward their lower edge
      c.set(uint32_t(x), uint32_t(y),
            shade(base, int(hash(t.seed, uint64_t(row), uint64_t(col)) % 21) - 10 - edge / 2));
    }
}

void detail(Canvas& c, const TexSpec& t) {
  const Rgba a = pick(kPlaster, std::size(kPlaster), hash(t.seed, 1)),
             b = pick(kPlaster, std::size(kPlaster), hash(t.seed, 2) + 5);
  const int64_t W = c.w, H = c.h, stripes = 2 + hash(t.seed, 3) % 6, u = std::max<int64_t>(std::min(W, H) / 32, 1);
  for (int64_t x = 0; x < W; ++x) c.rect(x, 0, x + 1, H, (x * stripes / W) % 2 ? a : b);
  c.rect(u, u, W - u, 2 * u, shade(a, -70));
  drawNumber(c, 2 * u, 3 * u, u, uint32_t(t.seed % 1000), shade(b, -90));
}

void pavement(Canvas& c, const TexSpec& t) {
  constexpr Rgba kStone[] = {{160, 155, 150, 255}, {180, 170, 150, 255}, {140, 130, 125, 255}, {190, 120, 100, 255}};
  const Rgba base = pick(kStone, std::size(kStone), hash(t.seed, 1));
  const int64_t W = c.w, H = c.h, n = 2 + hash(t.seed, 2) % 3, tw = std::max<int64_t>(W / n, 1),
                th = std::max<int64_t>(H / n, 1);
  const int64_t g = std::max<int64_t>(std::min(W, H) / 64, 1);
  for (int64_t y = 0; y < H; ++y)
    for (int64_t x = 0; x < W; ++x) {
      const bool grout = x % tw < g || y % th < g;
      c.set(uint32_t(x), uint32_t(y),
            grout ? shade(base, -60) : shade(base, int(hash(t.seed, uint64_t(x / tw), uint64_t(y / th)) % 25) - 12));
    }
}

void fence(Canvas& c, const TexSpec& t) {  // RGBA: bars and rails opaque, gaps transparent
  const Rgba metal = hash(t.seed, 1) & 1 ? Rgba{40, 45, 40, 255} : Rgba{120, 90, 60, 255};
  const int64_t W = c.w, H = c.h, bars = 4 + hash(t.seed, 2) % 8, bw = std::max<int64_t>(W / bars / 3, 1),
                rail = std::max<int64_t>(H / 16, 1);
  for (int64_t k = 0; k < bars; ++k) c.rect(k * W / bars, H / 8, k * W / bars + bw, H, metal);
  c.rect(0, H / 6, W, H / 6 + rail, metal);
  c.rect(0, H * 5 / 6, W, H * 5 / 6 + rail, metal);
}

void tree(Canvas& c, const TexSpec& t) {  // RGBA: a crown with holes and a trunk on transparency
  const int64_t W = c.w, H = c.h, cx = W / 2, cy = H * 2 / 5, rx = W * 9 / 20, ry = H * 7 / 20;
  const Rgba leaf = hash(t.seed, 1) & 1 ? Rgba{60, 110, 40, 255} : Rgba{90, 130, 50, 255};
  c.rect(W / 2 - W / 24, H / 2, W / 2 + W / 24 + 1, H, Rgba{90, 60, 40, 255});
  const int64_t cell = std::max<int64_t>(std::min(W, H) / 32, 1);
  for (int64_t y = 0; y < H; ++y)
    for (int64_t x = 0; x < W; ++x) {
      const int64_t dx = (x - cx) * ry, dy = (y - cy) * rx, r = rx * ry;
      if (dx * dx + dy * dy > r * r) continue;
      const uint32_t hv = hash(t.seed, uint64_t(x / cell), uint64_t(y / cell));
      if (hv % 7 == 0) continue;  // gaps between leaves
      c.set(uint32_t(x), uint32_t(y), shade(leaf, int(hv % 41) - 20));
    }
}

void glass(Canvas& c, const TexSpec& t) {  // RGBA: translucent panes (BLEND) in opaque frames
  const uint8_t alpha = uint8_t(96 + hash(t.seed, 1) % 64);
  const int64_t W = c.w, H = c.h, n = 2 + hash(t.seed, 2) % 3, f = std::max<int64_t>(std::min(W, H) / 32, 1);
  for (int64_t y = 0; y < H; ++y) c.rect(0, y, W, y + 1, Rgba{clamp8(150 + int(y * 40 / H)), 190, 210, alpha});
  for (int64_t k = 0; k <= n; ++k) {
    c.rect(k * W / n - f, 0, k * W / n + f, H, Rgba{70, 75, 80, 255});
    c.rect(0, k * H / n - f, W, k * H / n + f, Rgba{70, 75, 80, 255});
  }
}

}  // namespace

std::vector<uint8_t> renderTexture(const TexSpec& t) {
  Canvas c(t.width, t.height, t.rgba() ? 4 : 3);
  switch (t.kind) {
    case TexKind::BerlinFacade:
      berlinFacade(c, t);
      break;
    case TexKind::Facade:
      facade(c, t);
      break;
    case TexKind::Roof:
      roof(c, t);
      break;
    case TexKind::Detail:
      detail(c, t);
      break;
    case TexKind::Pavement:
      pavement(c, t);
      break;
    case TexKind::Fence:
      fence(c, t);
      break;
    case TexKind::Tree:
      tree(c, t);
      break;
    case TexKind::Glass:
      glass(c, t);
      break;
  }
  return std::move(c.px);
}

}  // namespace tessera::model::city
