// The procedural city block shared by "city_block" and "city_ids": a G x G grid of box buildings,
// each with its own 64x64 facade texture (lit windows on a wall colour), facades subdivided into
// floor x column quads with texcoords that repeat the texture, and a ground plane with a road
// texture repeated 64 times. Deterministic for its seed.
#pragma once

#include "tools/scenes/builder.h"

namespace tessera::scenes {

struct CityModel {
  Mesh mesh;                                   // ground first, then buildings
  uint32_t groundIndexCount = 0;
  std::vector<std::pair<uint32_t, uint32_t>> buildings;  // (first index, index count)
  std::vector<RgbaImage> facades;                        // one per building
  RgbaImage road;
  glm::mat4 viewProj;
};

CityModel makeCity(int gridSize, int width, int height, uint64_t seed);

}  // namespace tessera::scenes
