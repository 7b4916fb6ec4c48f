// Line 10 of Algorithm 1 of Trapp & Döllner 2010 (§2.2): atlasPackaging(R, Tw_max, Th_max), the
// rectangle packing the paper takes from [IC01] (Igarashi & Cosgrove 2001: sort the rectangles by
// height, then fill rows left to right), O(n log n) for the sort and O(n) for the placement.
//
// The packer is a deterministic shelf packer:
// - regions (B_viewport with its border) are sorted by height descending, then width descending,
//   then object id, so the same records always give the same atlas;
// - each region goes to the right of the previous one on the current shelf; when it does not fit the
//   row it opens a new shelf on top of the previous one (shelf height = its first, tallest region); when
//   the shelf does not fit the layer it opens a new layer. Placement never looks back at earlier
//   shelves or layers, which keeps it O(n) and the result independent of anything but the sort order.
// - Tw = Tw_max and Th = Th_max: every layer of a 2D texture array has the same size, and an atlas
//   smaller than the viewport plus its border could not hold a full-screen object (validateAtlas).
// Td = the number of layers used; more than kMaxArrayLayers (2048, §4.2's hardware limit) is an
// Error naming the count, never a silent truncation.
// Does not implement: shrinking the atlas per frame, rotating regions (the transform would no longer be
// a shift), or packing into holes left by earlier shelves (the paper's reference does neither).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "raster/types.h"
#include "rtta/record.h"

namespace tessera::rtta {

struct AtlasSize {
  int32_t width = 0, height = 0;  // Tw, Th
  int32_t layers = 0;             // Td (0 when nothing is visible)
};

// Throws Error unless Tw x Th holds borderedRegion(viewport, border) (a region of a full-screen object
// must fit one layer), both are even and <= kMaxTextureSize. Regions have even sizes and positions
// (parameterize.h), so shelves and offsets stay even and every shift is even.
void validateAtlas(int32_t tw, int32_t th, const Rect& vp, int32_t border);

// Places every visible record's region (Record::viewport): sets Record::atlas and Record::layer;
// culled records keep layer -1. Returns (Tw, Th, Td).
AtlasSize atlasPackaging(std::span<Record> records, int32_t twMax, int32_t thMax);

}  // namespace tessera::rtta
