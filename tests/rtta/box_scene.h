// Test helper: a hand-built RTTA scene of textured boxes, one object per box, so capture and
// composite tests do not depend on a model file. Boxes may share a texture (then one draw covers
// several objects, as batched geometry does).
#pragma once

#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "raster/texture.h"
#include "rtta/rtta_scene.h"
#include "tests/rtta/flat_render.h"

namespace tessera::rtta::testing {

struct BoxSpec {
  glm::vec3 lo, hi;
  uint32_t texture;  // index into the checker textures
};

inline std::vector<uint8_t> checker(uint32_t n, std::array<uint8_t, 4> a, std::array<uint8_t, 4> b) {
  std::vector<uint8_t> t(size_t(n) * n * 4);
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < n; ++x) {
      const auto& c = ((x / 4 + y / 4) & 1) ? a : b;
      std::copy(c.begin(), c.end(), t.begin() + (size_t(y) * n + x) * 4);
    }
  return t;
}

// Boxes in `specs` order are objects 0..n-1; meshes are sorted by texture (the order TAB's input
// batches have), so vertex ranges follow texture order, not object order.
inline RttaScene boxScene(const std::vector<BoxSpec>& specs, uint32_t textureCount) {
  batching::TabScene tab;
  for (uint32_t t = 0; t < textureCount; ++t) {
    batching::TabTexture tex;
    tex.name = "checker" + std::to_string(t);
    tex.width = tex.height = 32;
    const std::array<uint8_t, 4> a{uint8_t(60 + 60 * t), uint8_t(200 - 50 * t), uint8_t(90 + 40 * (t & 1)), 255};
    tex.levels = buildMipChainRGBA8(32, 32, checker(32, a, {30, 30, 40, 255}));
    tab.textures.push_back(std::move(tex));
  }
  std::vector<uint32_t> order(specs.size());
  for (uint32_t i = 0; i < specs.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return specs[a].texture < specs[b].texture; });
  std::vector<uint32_t> objectOf(specs.size());
  std::vector<std::string> names;
  for (uint32_t i = 0; i < specs.size(); ++i) objectOf[i] = i, names.push_back("box" + std::to_string(i));
  for (uint32_t i : order) {
    batching::TabMesh m;
    m.name = names[i];
    m.modelMesh = i;
    m.textures = {specs[i].texture};
    m.firstVertex = uint32_t(tab.vertices.size());
    std::vector<glm::vec3> tris;
    addBox(tris, specs[i].lo, specs[i].hi);
    for (size_t k = 0; k < tris.size(); ++k) {
      // Texcoords from the face-local corner pattern: 0,1,3 / 0,3,2 style triangles get a 2x repeat.
      const float st[6][2] = {{0, 0}, {2, 0}, {2, 2}, {0, 0}, {2, 2}, {0, 2}};
      tab.vertices.push_back({tris[k].x, tris[k].y, tris[k].z, st[k % 6][0], st[k % 6][1], 0.0f});
    }
    m.vertexCount = uint32_t(tab.vertices.size()) - m.firstVertex;
    tab.meshes.push_back(m);
  }
  return makeRttaScene(std::move(tab), objectOf, names);
}

// Five boxes like Fig. 1: overlapping on screen, one partly occluded, one partly off-screen; boxes 1
// and 3 share a texture.
inline std::vector<BoxSpec> fiveBoxes() {
  return {{{-2.5f, -1.0f, -1.0f}, {-0.5f, 1.0f, 1.0f}, 0},  {{0.0f, -0.8f, -0.5f}, {1.5f, 0.6f, 0.8f}, 1},
          {{-1.0f, 0.5f, -3.0f}, {1.0f, 2.0f, -1.5f}, 2},  {{2.0f, -1.5f, -2.0f}, {5.5f, 0.0f, -0.5f}, 1},
          {{-0.7f, -2.0f, 1.2f}, {0.3f, -1.2f, 2.2f}, 3}};
}

}  // namespace tessera::rtta::testing
