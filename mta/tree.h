// The texture atlas tree in memory (thesis §4.3, Figure 25), as built and as read from a paging file.
//
// Implements: the node record, the tree (nodes in depth-first pre-order, root = 0) with one vertex
// array ordered so that every node is one contiguous range (§4.8.1), root-atlas texture coordinates
// and the per-node texture matrix (uniform scale 2^level, used with REPEAT addressing, §4.5.4).
// Does not implement: building (tree_build.h), atlas texels (atlas_image.h), files (paging_file.h).
//
// Atlas texel (x, y) of an A x A atlas is stored at row y, column x, and covers texture coordinates
// [x/A, (x+1)/A] x [y/A, (y+1)/A]: row 0 is t = 0 (GL's bottom row when uploaded as is). Child q of a
// node occupies the quadrant x-half (q & 1), y-half (q >> 1): 0 bottom-left, 1 bottom-right, 2 top-left,
// 3 top-right in GL terms, as in the thesis.
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "mta/scene.h"
#include "mta/size_estimation.h"

namespace tessera::mta {

// One texture's area in a leaf atlas (layer 0 parameterization).
struct AtlasEntry {
  int32_t texture = -1;        // Scene texture
  TexRect source;              // texture-space rectangle mapped onto the area (A_tex scaled for the border)
  uint32_t x = 0, y = 0, w = 0, h = 0;  // texel rectangle in the leaf atlas, as placed
  // Turned by 90° by the packing (packing.h): the source's u runs along the atlas' +y over h texels and
  // its v along the atlas' −x over w texels (source.v1 at the area's left edge); otherwise u along +x over
  // w texels and v along +y over h texels.
  bool rotated = false;
};
// Leaf-local atlas texel position (x, y) of texture coordinate (u, v) (shifted into the entry's repeat,
// tree_build.cpp) through the entry's map, rotation included. A source of zero width or height maps to the
// area's middle along that axis.
std::pair<double, double> entryTexel(const AtlasEntry& e, double u, double v);

struct Node {
  std::array<float, 6> bounds{};  // min x, y, z, max x, y, z of the node's triangles
  float minDistance = 0.0f;       // leaves: d_min used; inner: 2 · max(children), capped leaves counted at d_min · cap factor
  uint32_t level = 0;             // k; texture matrix = diag(2^k, 2^k)
  uint32_t cellX = 0, cellY = 0;  // R(N) = [cellX, cellX + 1] x [cellY, cellY + 1] / 2^k in root-atlas coords
  std::array<int32_t, 4> children{-1, -1, -1, -1};  // by quadrant; -1 = none (only when < 4 triangles split)
  int32_t parent = -1;
  uint32_t firstTriangle = 0, triangleCount = 0;  // contiguous range of Tree triangles
  float coverage = 0.0f;  // atlas texels inside texture areas / A² (inner: mean of the four quadrants)
  uint32_t imageFirst = 0, imageCount = 0;  // leaves: range of Tree::leafImages (original images used)
  std::vector<AtlasEntry> entries;  // leaves only (build side; not stored in the file)
  bool leaf() const { return children[0] < 0 && children[1] < 0 && children[2] < 0 && children[3] < 0; }
  float textureScale() const { return float(uint64_t(1) << level); }
};

struct Tree {
  uint8_t alpha = 0;  // 0: RGB atlases (3 bytes per texel), 1: RGBA (4)
  std::vector<Node> nodes;
  Geometry geometry;            // every triangle once, in range order
  std::vector<glm::vec2> atlasUV;     // 3 per triangle: root-atlas texture coordinates
  std::vector<uint32_t> leafImages;   // per leaf (Node::imageFirst/Count): sorted images of every layer
  std::vector<uint32_t> atlasBlocks;  // node * layerCount + layer -> paging-file block (file side)
  uint32_t channels() const { return alpha ? 4 : 3; }
  uint32_t depth() const;  // max level + 1 (0 for an empty tree)
};

// Root-atlas coordinate of leaf-local atlas coordinate `local` (in [0,1]) of a node at (level, cell).
double toRoot(double local, uint32_t cell, uint32_t level);
// The node-local coordinate: frac(root · 2^level), i.e. what REPEAT addressing computes.
double toLocal(double root, uint32_t level);

}  // namespace tessera::mta
