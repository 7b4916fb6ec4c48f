#include "rtta/rtta_scene.h"

#include <fmt/format.h>
#include <glm/common.hpp>

#include "base/error.h"

namespace tessera::rtta {

RttaScene makeRttaScene(batching::TabScene tab, std::span<const uint32_t> objectOfModelMesh,
                        std::vector<std::string> objectNames) {
  if (objectNames.size() >= (size_t(1) << 24))
    throw Error(fmt::format("{} objects: object ids are a U32 vertex attribute that must stay below 2^24",
                            objectNames.size()));
  RttaScene s;
  s.objectNames = std::move(objectNames);
  s.objectBounds.assign(s.objectNames.size(), Box3{});
  std::vector<bool> seen(s.objectNames.size(), false);
  s.vertices.resize(tab.vertices.size());
  s.meshObject.resize(tab.meshes.size());
  for (size_t i = 0; i < tab.meshes.size(); ++i) {
    const batching::TabMesh& m = tab.meshes[i];
    if (m.modelMesh >= objectOfModelMesh.size())
      throw Error(fmt::format("mesh '{}' (model mesh {}): the object mapping has only {} entries", m.name, m.modelMesh,
                              objectOfModelMesh.size()));
    const uint32_t obj = objectOfModelMesh[m.modelMesh];
    if (obj >= s.objectNames.size())
      throw Error(fmt::format("mesh '{}': object id {} but there are {} objects", m.name, obj, s.objectNames.size()));
    s.meshObject[i] = obj;
    Box3& b = s.objectBounds[obj];
    for (uint32_t v = m.firstVertex; v < m.firstVertex + m.vertexCount; ++v) {
      const batching::Vertex& tv = tab.vertices[v];
      s.vertices[v] = {tv.x, tv.y, tv.z, tv.s, tv.t, tv.index, obj};
      const glm::dvec3 p(tv.x, tv.y, tv.z);
      if (!seen[obj]) b.lo = b.hi = p, seen[obj] = true;
      b.lo = glm::min(b.lo, p);
      b.hi = glm::max(b.hi, p);
    }
  }
  s.tab = std::move(tab);
  return s;
}

void refreshTamIndices(RttaScene& scene) {
  for (size_t v = 0; v < scene.vertices.size(); ++v) scene.vertices[v].tam = scene.tab.vertices[v].index;
}

}  // namespace tessera::rtta
