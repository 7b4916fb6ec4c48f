// compareLodMaps (verify/lod_compare.h).
#include "verify/lod_compare.h"

#include <cstdlib>
#include <string>

#include "base/error.h"

namespace tessera::verify {

std::string_view lodDiffName(LodDiff d) {
  switch (d) {
    case LodDiff::Same: return "same";
    case LodDiff::OnlyInA: return "only_in_a";
    case LodDiff::OnlyInB: return "only_in_b";
    case LodDiff::LookupCount: return "lookup_count";
    case LodDiff::Completeness: return "completeness";
    case LodDiff::TextureSize: return "texture_size";
    case LodDiff::Lambda: return "lambda";
  }
  return "?";
}

namespace {

// The reason two pixels differ, and the lambda difference of the first lookup that does.
LodDiff comparePixel(const LodPixel& a, const LodPixel& b, int32_t& delta8, bool& unitDiffers) {
  delta8 = 0;
  unitDiffers = false;
  if (a.count == 0 && b.count == 0) return LodDiff::Same;
  if (b.count == 0) return LodDiff::OnlyInA;
  if (a.count == 0) return LodDiff::OnlyInB;
  if (a.count != b.count) return LodDiff::LookupCount;
  for (int i = 0; i < a.recorded(); ++i) {
    const LodLookup& x = a.look[size_t(i)];
    const LodLookup& y = b.look[size_t(i)];
    if ((x.levels == 0) != (y.levels == 0)) return LodDiff::Completeness;
    if (x.width != y.width || x.height != y.height) {
      delta8 = y.lambda8 - x.lambda8;
      return LodDiff::TextureSize;
    }
    if (x.levels != 0 && x.lambda8 != y.lambda8) {
      delta8 = y.lambda8 - x.lambda8;
      return LodDiff::Lambda;
    }
    if (x.unit != y.unit) unitDiffers = true;
  }
  return LodDiff::Same;
}

}  // namespace

LodComparison compareLodMaps(const LodMap& a, const LodMap& b, std::string_view nameA, std::string_view nameB) {
  if (a.width != b.width || a.height != b.height)
    throw Error(std::string(nameA) + " is " + std::to_string(a.width) + "x" + std::to_string(a.height) + " but " +
                std::string(nameB) + " is " + std::to_string(b.width) + "x" + std::to_string(b.height) +
                ": LOD maps of different sizes cannot be compared pixel by pixel");
  LodComparison c;
  c.width = a.width, c.height = a.height;
  const size_t n = a.pixels.size();
  c.reason.assign(n, LodDiff::Same);
  c.delta8.assign(n, 0);
  for (size_t i = 0; i < n; ++i) {
    bool unit = false;
    const LodDiff d = comparePixel(a.pixels[i], b.pixels[i], c.delta8[i], unit);
    c.reason[i] = d;
    ++c.count[int(d)];
    if (a.pixels[i].count != 0 || b.pixels[i].count != 0) ++c.pixelsWithLookups;
    if (d != LodDiff::Same) ++c.differing;
    if (d == LodDiff::Same && unit) ++c.unitDiffers;
    if (d == LodDiff::Lambda && std::abs(c.delta8[i]) > c.maxAbsDelta8) c.maxAbsDelta8 = std::abs(c.delta8[i]);
  }
  return c;
}

}  // namespace tessera::verify
