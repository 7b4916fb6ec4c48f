// The input of render-to-texture-atlas frames: a model's meshes as TAB's input batches (textures
// decoded once with their mip chains, meshes sorted by texture so one texture is one draw), each
// mesh assigned to an object, and every vertex carrying its object id (Trapp & Döllner 2010 §2.1: "This
// identifier must be encoded as a per-vertex attribute to allow geometry batching").
// Objects are what the caller says: one per model::Mesh (`--objects mesh`) or one per scene-graph node
// instance (`--objects node`); the object list and its names come with the mapping.
// Every material is captured opaque: the atlas holds one surface per object (the paper's "single
// layer of an object"), so MASK cutoffs and BLEND are not applied in any mode, and STD, RTT and RTTA
// draw the same colours (texel x base-colour factor, alpha 1; untextured meshes: a white texel).
// Does not implement: loading models (model/), Algorithm 1 of TAB (batching/batcher.h, run by the
// caller for `--texturing tab`), recording (rtta_record.h).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "batching/tab_scene.h"
#include "rtta/record.h"

namespace tessera::rtta {

// Non-indexed; 28 bytes: position, texcoord (s, t, i_TAM), object id (a U32 attribute, < 2^24).
struct RttaVertex {
  float x, y, z;
  float s, t, tam;
  uint32_t object;
};
static_assert(sizeof(RttaVertex) == 28);

struct RttaScene {
  batching::TabScene tab;               // textures, meshes, vertices (and arrays / batches after Algorithm 1)
  std::vector<RttaVertex> vertices;     // tab.vertices with the object id, same order
  std::vector<uint32_t> meshObject;     // per tab.meshes entry: its object id
  std::vector<std::string> objectNames;
  std::vector<Box3> objectBounds;       // B_world per object
  uint64_t triangles() const { return vertices.size() / 3; }
};

// `objectOfModelMesh[m]` = the object id of model mesh m (dense ids 0..names.size()-1). Throws Error
// on an id out of range, a mapping of the wrong size, or 2^24 objects or more.
RttaScene makeRttaScene(batching::TabScene tab, std::span<const uint32_t> objectOfModelMesh,
                        std::vector<std::string> objectNames);

// After Algorithm 1 has rewritten tab.vertices' i_TAM: copies them into `vertices`.
void refreshTamIndices(RttaScene& scene);

}  // namespace tessera::rtta
