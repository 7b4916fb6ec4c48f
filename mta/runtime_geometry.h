// The atlas tree's geometry as the renderer draws it: one interleaved vertex array for every tree of a
// paging file, and per leaf the runs of triangles that share an original texture.
//
// Implements: per tree two regions in leaf (depth-first) order, the textured triangles of every leaf,
// then the untextured ones of every leaf, each leaf's textured triangles sorted by original texture.
// So a node drawn with its atlas is one draw over its leaves' textured triangles (thesis §4.8.1: every
// node stays one contiguous range, now in each region), its untextured triangles are one more draw,
// and a leaf drawn with its original textures needs one draw per texture; the vertex records.
// Does not implement: deciding what to draw (traversal.h), recording (frame_recorder.h).
//
// Only layer 0 is drawn (the base colour); further layers (§5.1.3) share the parameterization and
// would be bound to further texture units by a program that reads them.
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

// A run of triangles [first, first + count) in global triangle order using one original texture.
struct TextureRun {
  int32_t texture = -1;  // scene texture; -1 = untextured
  uint32_t first = 0, count = 0;
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
