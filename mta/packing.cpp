#include "mta/packing.h"

#include <algorithm>
#include <numeric>

namespace tessera::mta {

double PackResult::coverage() const {
  return atlasSize == 0 ? 0.0 : double(usedTexels) / (double(atlasSize) * double(atlasSize));
}

namespace {

// The row-and-skyline layout of `rects` (no rotation here: the caller passes them turned as wanted).
bool skyline(std::span<const PackRect> rects, uint32_t atlasSize, std::vector<Placement>& out) {
  for (const PackRect& p : rects)
    if (p.w == 0 || p.h == 0 || p.w > atlasSize || p.h > atlasSize) return false;
  std::vector<uint32_t> order(rects.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    if (rects[a].h != rects[b].h) return rects[a].h > rects[b].h;
    if (rects[a].w != rects[b].w) return rects[a].w > rects[b].w;
    return a < b;  // total order: the same input gives the same layout
  });
  std::vector<uint32_t> sky(atlasSize, 0);  // first free row of each column
  out.assign(rects.size(), Placement{});
  uint32_t x = 0;
  for (uint32_t i : order) {
    const PackRect& p = rects[i];
    if (x + p.w > atlasSize) x = 0;  // next row
    uint32_t y = 0;
    for (uint32_t c = x; c < x + p.w; ++c) y = std::max(y, sky[c]);  // push up to the row below
    if (uint64_t(y) + p.h > atlasSize) return false;
    for (uint32_t c = x; c < x + p.w; ++c) sky[c] = y + p.h;
    out[i] = Placement{x, y, false};
    x += p.w;
  }
  return true;
}

}  // namespace

PackResult packAtlas(std::span<const PackRect> rects, uint32_t atlasSize, bool allowRotation) {
  PackResult r;
  r.atlasSize = atlasSize;
  uint64_t area = 0;
  for (const PackRect& p : rects) {
    if (p.w == 0 || p.h == 0) return r;
    area += uint64_t(p.w) * p.h;
  }
  if (area > uint64_t(atlasSize) * atlasSize) return r;  // cannot fit whatever the layout
  if (skyline(rects, atlasSize, r.placements)) {
    r.ok = true;
    r.usedTexels = area;
    return r;
  }
  if (!allowRotation) return PackResult{false, {}, 0, atlasSize, false};
  // Igarashi–Cosgrove's first step: every rectangle taller than wide.
  std::vector<PackRect> turned(rects.begin(), rects.end());
  bool any = false;
  for (PackRect& p : turned)
    if (p.h < p.w) std::swap(p.w, p.h), any = true;
  if (!any || !skyline(turned, atlasSize, r.placements)) return PackResult{false, {}, 0, atlasSize, false};
  for (size_t i = 0; i < rects.size(); ++i) r.placements[i].rotated = rects[i].h < rects[i].w;
  r.ok = true;
  r.usedTexels = area;
  r.anyRotated = true;
  return r;
}

}  // namespace tessera::mta
