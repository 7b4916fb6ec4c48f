#include "batching/batcher.h"

#include <algorithm>
#include <map>

#include "base/error.h"
#include "raster/limits.h"

namespace tessera::batching {

void validateParams(const TabParams& p, const std::string& where) {
  // Require d_max > 0 ∧ b_max > 3 ∧ a_max > 0 (Algorithm 1, line 1), plus what the renderer can bind.
  if (p.bMax <= 3) throw Error(where + ": --b-max: " + std::to_string(p.bMax) + " must be above 3 (vertices per geometry batch)");
  if (p.dMax == 0 || p.dMax > uint32_t(kMaxArrayLayers))
    throw Error(where + ": --d-max: " + std::to_string(p.dMax) + " must be in 1.." + std::to_string(kMaxArrayLayers) +
                " (layers per texture array; GL_MAX_ARRAY_TEXTURE_LAYERS of llvmpipe)");
  if (p.aMax == 0 || p.aMax > kMaxTabArrays)
    throw Error(where + ": --a-max: " + std::to_string(p.aMax) + " must be in 1.." + std::to_string(kMaxTabArrays) +
                " (arrays per output batch: the width of texarray_batch's switch over named samplers)");
}

namespace {

ArrayKey keyOf(const TabTexture& t) { return ArrayKey{t.width, t.height, t.format, t.wrapS, t.wrapT}; }

// The open output batch: its arrays, where each of its textures sits, its TAM and geometry.
struct OpenBatch {
  OutputBatch out;
  std::map<uint32_t, std::pair<uint32_t, uint32_t>> placed;  // texture -> (local array, layer)
  GeometryBatch geometry;
  uint64_t b = 0;  // vertices in the open geometry batch
};

}  // namespace

void runAlgorithm1(TabScene& scene, const TabParams& params) {
  validateParams(params, "tab build");
  scene.params = params;
  scene.arrays.clear();
  scene.batches.clear();
  OpenBatch open;
  auto closeGeometry = [&](uint32_t nextMesh, uint32_t nextVertex) {
    if (open.geometry.meshCount > 0) open.out.geometry.push_back(open.geometry);
    open.geometry = GeometryBatch{nextVertex, 0, nextMesh, 0};
    open.b = 0;
  };
  auto emit = [&](uint32_t nextMesh, uint32_t nextVertex) {
    closeGeometry(nextMesh, nextVertex);
    if (!open.out.geometry.empty()) scene.batches.push_back(std::move(open.out));
    open = OpenBatch{};
    open.geometry = GeometryBatch{nextVertex, 0, nextMesh, 0};
  };
  // matchTextureArray: the earliest array of the open batch with the key and room for one more layer.
  // `extra` counts layers this mesh would add before the lookup (so a mesh's own textures are seen).
  auto match = [&](const ArrayKey& k, const std::map<uint32_t, uint32_t>& extra) -> int {
    for (uint32_t a = 0; a < open.out.arrays.size(); ++a) {
      const TextureArray& ta = scene.arrays[open.out.arrays[a]];
      const auto e = extra.find(a);
      const size_t layers = ta.layers.size() + (e == extra.end() ? 0 : e->second);
      if (ta.key == k && layers < params.dMax) return int(a);  // full at d_max (line 6: `>=`, not `>`)
    }
    return -1;
  };

  for (uint32_t mi = 0; mi < scene.meshes.size(); ++mi) {
    TabMesh& mesh = scene.meshes[mi];
    if (mesh.kind != MeshKind::Batched) break;
    // How many new arrays would this mesh open? All of a mesh's entries live in one output batch.
    auto newArraysNeeded = [&] {
      std::map<uint32_t, uint32_t> extra;
      std::vector<ArrayKey> fresh;  // keys of arrays this mesh would create, with their layer counts
      std::vector<uint32_t> freshLayers;
      std::vector<uint32_t> seen;
      for (uint32_t t : mesh.textures) {
        if (open.placed.count(t) || std::find(seen.begin(), seen.end(), t) != seen.end()) continue;
        seen.push_back(t);
        const ArrayKey k = keyOf(scene.textures[t]);
        const int a = match(k, extra);
        if (a >= 0) {
          ++extra[uint32_t(a)];
          continue;
        }
        bool added = false;
        for (size_t f = 0; f < fresh.size() && !added; ++f)
          if (fresh[f] == k && freshLayers[f] < params.dMax) ++freshLayers[f], added = true;
        if (!added) fresh.push_back(k), freshLayers.push_back(1);
      }
      return fresh.size();
    };
    const size_t need = newArraysNeeded();
    if (open.out.arrays.size() + need > params.aMax) {
      if (open.out.arrays.empty())
        throw Error("tab build: mesh " + std::to_string(mesh.modelMesh) + " ('" + mesh.name + "') needs " +
                    std::to_string(need) + " texture arrays on its own, more than --a-max " + std::to_string(params.aMax));
      emit(mi, mesh.firstVertex);  // line 14, fixed: a new array set and TAM for this mesh
    }
    if (open.b > 0 && open.b + mesh.vertexCount > params.bMax) closeGeometry(mi, mesh.firstVertex);  // line 18

    const uint32_t first = uint32_t(open.out.tam.size());
    if (uint64_t(first) + mesh.textures.size() > kMaxTamIndex)
      throw Error("tab build: output batch " + std::to_string(scene.batches.size()) + ": its TAM would exceed " +
                  std::to_string(kMaxTamIndex) + " entries (i_TAM travels as a float texcoord)");
    for (uint32_t t : mesh.textures) {
      auto it = open.placed.find(t);
      if (it == open.placed.end()) {
        const ArrayKey k = keyOf(scene.textures[t]);
        int a = match(k, {});
        if (a < 0) {  // createNewTextureArray, add(TA, TA)
          a = int(open.out.arrays.size());
          open.out.arrays.push_back(uint32_t(scene.arrays.size()));
          scene.arrays.push_back(TextureArray{k, {}});
        }
        TextureArray& ta = scene.arrays[open.out.arrays[size_t(a)]];
        ta.layers.push_back(t);  // addTexture
        it = open.placed.emplace(t, std::make_pair(uint32_t(a), uint32_t(ta.layers.size() - 1))).first;
      }
      TamEntry e;  // TAE = (TA, l), with the mesh's material
      e.array = it->second.first;
      e.layer = it->second.second;
      e.factor = mesh.factor;
      e.alphaCutoff = mesh.alphaMode == AlphaMode::Mask ? mesh.alphaCutoff : 0.0f;
      e.opaque = mesh.alphaMode != AlphaMode::Blend;
      open.out.tam.push_back(e);
    }
    mesh.outputBatch = uint32_t(scene.batches.size());
    mesh.tamIndex = first;
    for (uint32_t v = 0; v < mesh.vertexCount; ++v) scene.vertices[size_t(mesh.firstVertex) + v].index = float(first);  // update
    open.geometry.meshCount += 1;
    open.geometry.vertexCount += mesh.vertexCount;
    open.b += mesh.vertexCount;
  }
  uint32_t end = 0, endVertex = 0;
  for (const TabMesh& m : scene.meshes)
    if (m.kind == MeshKind::Batched) ++end, endVertex = m.firstVertex + m.vertexCount;
  emit(end, endVertex);  // the last batch, which the printed algorithm never emitted
}

}  // namespace tessera::batching
