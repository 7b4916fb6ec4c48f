// The atlas tree's geometry as the renderer draws it: one interleaved vertex array for every tree of a
// paging file, and per leaf the runs of triangles that share an original texture.
//
// Implements: per tree two regions in leaf (depth-first) order, the textured triangles of every leaf,
// then the untextured ones of every leaf, each leaf's textured triangles sorted by original texture
// (layer 0's, then layer 1's: a run is one pair of textures, so one pair of binds).
// So a node drawn with its atlas is one draw over its leaves' textured triangles (thesis §4.8.1: every
// node stays one contiguous range, now in each region), its untextured triangles are one more draw,
// and a leaf drawn with its original textures needs one draw per texture; the vertex records.
// Does not implement: deciding what to draw (traversal.h), recording (frame_recorder.h).
//
// Layers: layer 0 (the base colour) always; a file with a layer 1 (§5.1.3: a light map, glTF's
// occlusionTexture) also gets `layered`, the vertex array the recorder draws it from. Layer 1 shares
// layer 0's atlas parameterization: the build fills layer 1's atlas area of a layer-0 entry at the same
// texels (mta/build.cpp renderLeaf), so a node's layer-1 atlas is sampled at the layer-0 atlas
// coordinates. Originals are sampled at each layer's own texcoords. An untextured triangle (layer 0
// texture -1) draws no layer: it has no atlas area to carry one. Layers >= 2 are not drawn.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "mta/paging_file.h"

namespace tessera::mta {

// 36 bytes; the vertex layouts of frame_recorder.cpp depend on these offsets.
struct RuntimeVertex {
  glm::vec3 pos;
  glm::vec2 atlasUV;  // root-atlas coordinates (scaled by 2^level in the program's texture matrix)
  glm::vec2 origUV;   // original texture coordinates, unwrapped
  uint32_t triangle;  // global triangle index (object_id frames; texel analysis)
  uint32_t pad;
};
static_assert(sizeof(RuntimeVertex) == 36 && offsetof(RuntimeVertex, atlasUV) == 12 &&
              offsetof(RuntimeVertex, origUV) == 20 && offsetof(RuntimeVertex, triangle) == 28);

// The layered vertex (files with a layer 1), 44 bytes: each draw reads one vec4 at offset 12 (atlas
// draws: the root-atlas coordinates twice, as both layers' atlases share them) or at offset 28
// (original draws: the layer-0 and the layer-1 texcoords), the layouts of program "textured_layers".
struct LayeredVertex {
  glm::vec3 pos;
  glm::vec2 atlasUV0, atlasUV1;  // equal (see above); stored twice so that one attribute reads both
  glm::vec2 origUV0, origUV1;    // layer-1 texcoords are (0, 0) where the triangle has no layer-1 texture
};
static_assert(sizeof(LayeredVertex) == 44 && offsetof(LayeredVertex, atlasUV0) == 12 &&
              offsetof(LayeredVertex, origUV0) == 28);

// A run of triangles [first, first + count) in global triangle order using one original texture per layer.
struct TextureRun {
  int32_t texture = -1;  // scene texture of layer 0; -1 = untextured
  uint32_t first = 0, count = 0;
  int32_t texture1 = -1;  // scene texture of layer 1; -1 = none (or a file without layer 1)
};

struct LeafRuns {
  uint32_t texturedFirst = 0, texturedCount = 0;      // the leaf's textured triangles, sorted by texture
  uint32_t runFirst = 0, runCount = 0;                // into RuntimeGeometry::runs (textured runs only)
  uint32_t untexturedFirst = 0, untexturedCount = 0;  // in the tree's untextured region
};

struct RuntimeTree {
  uint32_t firstTriangle = 0;  // of this tree in the global order (trees follow each other)
  uint32_t firstUntextured = 0;  // start of the tree's untextured region
  std::vector<LeafRuns> leaf;  // per node (inner nodes: empty record)
};

struct RuntimeGeometry {
  std::vector<RuntimeVertex> vertices;  // 3 per triangle, global order
  std::vector<LayeredVertex> layered;   // the same triangles, when the file has a layer 1; else empty
  std::vector<TextureRun> runs;
  std::vector<RuntimeTree> trees;
  // Per global triangle: tree and node (leaf) it belongs to, and its tree-local index in the file.
  std::vector<uint8_t> triangleTree;
  std::vector<uint32_t> triangleLeaf, triangleSource;
  uint32_t triangleCount() const { return uint32_t(triangleLeaf.size()); }
};

// Precondition: `meta` passed PagingFile's validation (its leaves partition each tree's triangles). A meta
// that does not is an Error ("internal error"), never a write out of bounds.
RuntimeGeometry buildRuntimeGeometry(const MtaMeta& meta);

}  // namespace tessera::mta
