// Comparison of two LOD maps (raster/lod_probe.h), pixel by pixel: do the fragments stored in the two
// frames make the same lookups at the same level of detail? This is the check that two renderings of one
// scene (e.g. the TAB batched frame and its baseline) sample every texture at an identical lambda.
//
// Implements: per pixel, the first reason two records differ, in this order: a lookup present in only one
// frame, a different lookup count, a texture complete in one and incomplete in the other, a different
// level-0 size, a different lambda with the same size; the lambda difference (B - A, 8.8) of the first
// lookup that differs; totals per reason. The unit and the array layer count are not compared (a batched
// frame samples an array on another unit); differing units are only counted.
// Does not implement: the probe (raster/lod_probe.h) or any drawing (tools/cli/cmd_texel_frame.cpp).
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "raster/lod_probe.h"

namespace tessera::verify {

enum class LodDiff : uint8_t {
  Same = 0,         // equal records (including: no lookup in either)
  OnlyInA = 1,      // lookups in A, none in B
  OnlyInB = 2,      // lookups in B, none in A
  LookupCount = 3,  // both have lookups, but not the same number
  Completeness = 4, // a lookup's texture is complete (has a LOD) in one frame only
  TextureSize = 5,  // a lookup samples textures of different level-0 sizes
  Lambda = 6,       // same sizes, different lambda
};
constexpr int kLodDiffKinds = 7;
std::string_view lodDiffName(LodDiff d);  // "same", "only_in_a", "lookup_count", ... (JSON keys)

struct LodComparison {
  int32_t width = 0, height = 0;
  std::vector<LodDiff> reason;     // per pixel, rows bottom first like LodMap
  std::vector<int32_t> delta8;     // per pixel: lambda B - A of the first differing lookup (0 otherwise)
  uint64_t count[kLodDiffKinds] = {};
  uint64_t pixelsWithLookups = 0;  // in A or in B
  uint64_t differing = 0;          // pixels whose reason is not Same
  uint64_t unitDiffers = 0;        // pixels with equal records except the unit (counted as Same)
  int32_t maxAbsDelta8 = 0;        // over Lambda pixels
};

// Throws Error naming nameA / nameB if the two maps differ in size.
LodComparison compareLodMaps(const LodMap& a, const LodMap& b, std::string_view nameA = "A",
                             std::string_view nameB = "B");

}  // namespace tessera::verify
