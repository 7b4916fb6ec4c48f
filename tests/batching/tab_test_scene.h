// Hand-built TabScene inputs for the batching tests: meshes of given sizes naming textures of given
// resolutions and wrap modes, as prepareInput() would hand them to Algorithm 1 (batched meshes first,
// consecutive vertices). Texture texels are one level of zeros: Algorithm 1 only reads their keys.
#pragma once

#include <cstdint>
#include <vector>

#include "batching/tab_scene.h"

namespace tessera::testing {

struct TexSpec {
  uint32_t width = 64, height = 64;
  batching::WrapMode wrap = batching::WrapMode::Repeat;
};
struct MeshSpec {
  uint32_t triangles = 1;
  std::vector<uint32_t> textures;  // per unit
};

inline batching::TabScene tabInput(const std::vector<TexSpec>& textures, const std::vector<MeshSpec>& meshes) {
  batching::TabScene s;
  for (const TexSpec& t : textures) {
    batching::TabTexture tt;
    tt.width = t.width, tt.height = t.height, tt.wrapS = tt.wrapT = t.wrap;
    s.textures.push_back(tt);
  }
  uint32_t v = 0;
  for (uint32_t i = 0; i < meshes.size(); ++i) {
    batching::TabMesh m;
    m.name = std::to_string(i).insert(0, 1, 'm');  // not "m" + ...: GCC 12 warns falsely (-Wrestrict, bug 105329)
    m.modelMesh = i;
    m.textures = meshes[i].textures;
    m.firstVertex = v;
    m.vertexCount = meshes[i].triangles * 3;
    for (uint32_t k = 0; k < m.vertexCount; ++k) {
      const float f = float(v + k);
      s.vertices.push_back({f, f + 0.5f, -f, f * 0.25f, 1.0f - f, 0.0f});
    }
    v += m.vertexCount;
    s.meshes.push_back(m);
  }
  return s;
}

}  // namespace tessera::testing
