#include "tools/scenes/city_model.h"

namespace tessera::scenes {

namespace {

RgbaImage facadeTexture(Rng& rng) {
  const std::array<uint8_t, 4> wall = {uint8_t(120 + rng.below(100)), uint8_t(100 + rng.below(90)),
                                       uint8_t(80 + rng.below(80)), 255};
  RgbaImage img{64, 64, std::vector<uint8_t>(64 * 64 * 4)};
  for (uint32_t y = 0; y < 64; ++y)
    for (uint32_t x = 0; x < 64; ++x) {
      // 4 x 4 windows per texture repeat; a window is lit with a per-window random shade.
      const bool window = (x % 16) >= 4 && (x % 16) < 12 && (y % 16) >= 5 && (y % 16) < 13;
      if (!window) {
        img.set(x, y, wall);
        continue;
      }
      const uint32_t shade = uint32_t((x / 16) * 7 + (y / 16) * 13) % 5;
      img.set(x, y, {uint8_t(30 + shade * 40), uint8_t(40 + shade * 35), uint8_t(60 + shade * 30), 255});
    }
  return img;
}

}  // namespace

CityModel makeCity(int grid, int width, int height, uint64_t seed) {
  CityModel c;
  Rng rng{seed};
  c.road = checker(64, 64, 8, {90, 90, 95, 255}, {70, 70, 75, 255});
  for (uint32_t y = 0; y < 64; ++y)
    for (uint32_t x = 28; x < 36; ++x) c.road.set(x, y, {200, 200, 180, 255});  // a lane marking
  const float extent = float(grid) * 2.0f;
  c.mesh.quad({-1, -1, 0}, {extent + 1, -1, 0}, {extent + 1, extent + 1, 0}, {-1, extent + 1, 0}, {0, 0, 0, 0},
              {64, 0, 0, 0}, {64, 64, 0, 0}, {0, 64, 0, 0}, 0);
  c.groundIndexCount = uint32_t(c.mesh.indices.size());

  for (int by = 0; by < grid; ++by)
    for (int bx = 0; bx < grid; ++bx) {
      const uint32_t id = uint32_t(c.buildings.size()) + 1;
      const uint32_t first = uint32_t(c.mesh.indices.size());
      const float x0 = float(bx) * 2.0f + 0.3f, y0 = float(by) * 2.0f + 0.3f;
      const float sx = 1.0f + 0.4f * rng.unit(), sy = 1.0f + 0.4f * rng.unit();
      const int floors = 2 + int(rng.below(7));
      const float fh = 0.35f, top = fh * float(floors);
      const int cols = 4;
      // Four facades, each floors x cols quads; texcoords: one texture repeat per 4 x 4 cells.
      const glm::vec3 corners[5] = {
          {x0, y0, 0}, {x0 + sx, y0, 0}, {x0 + sx, y0 + sy, 0}, {x0, y0 + sy, 0}, {x0, y0, 0}};
      for (int f = 0; f < 4; ++f) {
        const glm::vec3 a = corners[f], b = corners[f + 1];
        for (int j = 0; j < floors; ++j)
          for (int i = 0; i < cols; ++i) {
            const float u0 = float(i) / cols, u1 = float(i + 1) / cols;
            const glm::vec3 p0{a.x + (b.x - a.x) * u0, a.y + (b.y - a.y) * u0, fh * float(j)};
            const glm::vec3 p1{a.x + (b.x - a.x) * u1, a.y + (b.y - a.y) * u1, fh * float(j)};
            const float s0 = float(i) * 0.25f, s1 = float(i + 1) * 0.25f, t0 = float(j) * 0.25f, t1 = float(j + 1) * 0.25f;
            c.mesh.quad(p0, p1, {p1.x, p1.y, p1.z + fh}, {p0.x, p0.y, p0.z + fh}, {s0, t0, 0, 0}, {s1, t0, 0, 0},
                        {s1, t1, 0, 0}, {s0, t1, 0, 0}, id);
          }
      }
      // Roof: a wall-coloured corner of the texture.
      c.mesh.quad({x0, y0, top}, {x0 + sx, y0, top}, {x0 + sx, y0 + sy, top}, {x0, y0 + sy, top}, {0, 0, 0, 0},
                  {0.05f, 0, 0, 0}, {0.05f, 0.05f, 0, 0}, {0, 0.05f, 0, 0}, id);
      c.buildings.push_back({first, uint32_t(c.mesh.indices.size()) - first});
      c.facades.push_back(facadeTexture(rng));
    }
  const glm::vec3 eye{-0.08f * extent, -0.12f * extent, 0.16f * extent};
  const glm::vec3 at{0.5f * extent, 0.55f * extent, 0.0f};
  c.viewProj = mul(perspective(55.0, double(width) / height, 0.5, 4.0 * extent), lookAt(eye, at, {0, 0, 1}));
  return c;
}

}  // namespace tessera::scenes
