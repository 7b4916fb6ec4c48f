// Packing of rectangles into one fixed A x A atlas (thesis §2.1, Igarashi & Cosgrove 2001).
//
// Implements: the Igarashi–Cosgrove heuristic: rectangles sorted by decreasing height (then decreasing
// width, then index), laid out in rows from left to right, each pushed up as far as the rectangles below
// it allow (a per-column skyline). The layout is tried first as given; if it does not fit and rotation is
// allowed, again with every rectangle wider than tall turned by 90° (the paper's and the thesis's first
// step: "rotate all source images whose height is smaller than their width"), so that a rectangle is
// rotated only where that lets the set fit one atlas, and a set that fits as given keeps its layout.
// A rotated rectangle occupies h x w texels; the caller maps its texture into the area turned by 90°
// (tree.h AtlasEntry::rotated), so the image is unchanged apart from resampling.
// Does not implement: multiple atlases (a failure makes the caller split the node, §4.5.1).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace tessera::mta {

struct PackRect {
  uint32_t w = 0, h = 0;
};
struct Placement {
  uint32_t x = 0, y = 0;  // texel offset of the rectangle's first row / column
  bool rotated = false;   // occupies h columns and w rows (turned by 90°)
};
struct PackResult {
  bool ok = false;
  std::vector<Placement> placements;  // one per input rectangle, in input order (valid when ok)
  uint64_t usedTexels = 0;            // sum of w·h
  double coverage() const;            // usedTexels / A², set by packAtlas
  uint32_t atlasSize = 0;
  bool anyRotated = false;            // some placement is rotated
};

// Deterministic: the result depends only on the inputs. Placements never overlap and lie inside
// [0, A)² (with their extents swapped when rotated). Fails (ok = false) when neither layout fits: a
// rectangle would cross the atlas' last row, or is wider than A in both layouts.
PackResult packAtlas(std::span<const PackRect> rects, uint32_t atlasSize, bool allowRotation = true);

}  // namespace tessera::mta
