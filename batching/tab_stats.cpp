#include "batching/tab_stats.h"

#include <set>

namespace tessera::batching {

nlohmann::json tableOneJson(const TabScene& s) {
  uint64_t batchedVertices = 0, batchedMeshes = 0, units = 0, untexturedVertices = 0, blendVertices = 0;
  uint64_t untexturedMeshes = 0, blendMeshes = 0;
  std::set<uint32_t> batchedTextures;
  for (const TabMesh& m : s.meshes) {
    if (m.kind == MeshKind::Batched) {
      batchedVertices += m.vertexCount, ++batchedMeshes, units += m.textures.size();
      batchedTextures.insert(m.textures.begin(), m.textures.end());
    } else if (m.kind == MeshKind::Untextured) {
      untexturedVertices += m.vertexCount, ++untexturedMeshes;
    } else {
      blendVertices += m.vertexCount, ++blendMeshes;
    }
  }
  uint64_t geometryBatches = 0, tamEntries = 0;
  for (const OutputBatch& b : s.batches) geometryBatches += b.geometry.size(), tamEntries += b.tam.size();
  uint64_t originalBytes = 0, arrayBytes = 0;
  for (uint32_t t : batchedTextures) originalBytes += s.textures[t].bytes();
  nlohmann::json arrays = nlohmann::json::array();
  for (const OutputBatch& b : s.batches)
    for (uint32_t a : b.arrays) {
      const TextureArray& ta = s.arrays[a];
      uint64_t bytes = 0;
      for (uint32_t t : ta.layers) bytes += s.textures[t].bytes();
      arrayBytes += bytes;
      arrays.push_back({{"width", ta.key.width}, {"height", ta.key.height}, {"layers", ta.layers.size()}, {"bytes", bytes}});
    }
  const double avgIn = batchedMeshes ? double(batchedVertices) / double(batchedMeshes) : 0.0;
  const double avgOut = geometryBatches ? double(batchedVertices) / double(geometryBatches) : 0.0;
  constexpr uint64_t kP = 36;
  return {
      {"source", s.source},
      {"params", {{"b_max", s.params.bMax}, {"d_max", s.params.dMax}, {"a_max", s.params.aMax}}},
      {"vertices", s.vertices.size()},
      {"triangles", s.vertices.size() / 3},
      {"textures", batchedTextures.size()},
      {"input_batches", batchedMeshes},
      {"b_average_input", avgIn},
      {"output_batches", s.batches.size()},
      {"geometry_batches", geometryBatches},
      {"b_average_output", avgOut},
      {"batched_vertices", batchedVertices},
      {"arrays", arrays},
      {"array_count", arrays.size()},
      {"tam_entries", tamEntries},
      {"o_tam_p_bytes", kP},
      {"o_tam_bytes", kP * units},
      {"o_tam_paper_values", 3 * units},
      {"texture_bytes_originals", originalBytes},
      {"texture_bytes_arrays", arrayBytes},
      {"texture_bytes_duplicated", arrayBytes - originalBytes},
      {"untextured", {{"meshes", untexturedMeshes}, {"vertices", untexturedVertices}, {"draws", untexturedMeshes ? 1 : 0}}},
      {"blend", {{"meshes", blendMeshes}, {"vertices", blendVertices}, {"draws", blendMeshes}}},
  };
}

}  // namespace tessera::batching
