// Packing of rectangles into one fixed A x A atlas (thesis §2.1, Igarashi & Cosgrove 2001).
//
// Implements: the Igarashi–Cosgrove heuristic without rotation: rectangles sorted by decreasing
// height (then decreasing width, then index), laid out in rows from left to right, each pushed up as
// far as the rectangles below it allow (a per-column skyline). Rotation is not used so that atlas
// texcoords stay an axis-aligned scale + offset of the original ones.
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
};
struct PackResult {
  bool ok = false;
  std::vector<Placement> placements;  // one per input rectangle, in input order (valid when ok)
  uint64_t usedTexels = 0;            // sum of w·h
  double coverage() const;            // usedTexels / A², set by packAtlas
  uint32_t atlasSize = 0;
};

// Deterministic: the result depends only on the inputs. Placements never overlap and lie inside
// [0, A)². Fails (ok = false) when a rectangle would cross the atlas' last row or is wider than A.
PackResult packAtlas(std::span<const PackRect> rects, uint32_t atlasSize);

}  // namespace tessera::mta
