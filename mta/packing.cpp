#include "mta/packing.h"

#include <algorithm>
#include <numeric>

namespace tessera::mta {

double PackResult::coverage() const {
  return atlasSize == 0 ? 0.0 : double(usedTexels) / (double(atlasSize) * double(atlasSize));
}

PackResult packAtlas(std::span<const PackRect> rects, uint32_t atlasSize) {
  PackResult r;
  r.atlasSize = atlasSize;
  uint64_t area = 0;
  for (const PackRect& p : rects) {
    if (p.w == 0 || p.h == 0 || p.w > atlasSize || p.h > atlasSize) return r;
    area += uint64_t(p.w) * p.h;
  }
  if (area > uint64_t(atlasSize) * atlasSize) return r;  // cannot fit whatever the layout
  std::vector<uint32_t> order(rects.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    if (rects[a].h != rects[b].h) return rects[a].h > rects[b].h;
    if (rects[a].w != rects[b].w) return rects[a].w > rects[b].w;
    return a < b;  // total order: the same input gives the same layout
  });
  std::vector<uint32_t> skyline(atlasSize, 0);  // first free row of each column
  r.placements.resize(rects.size());
  uint32_t x = 0;
  for (uint32_t i : order) {
    const PackRect& p = rects[i];
    if (x + p.w > atlasSize) x = 0;  // next row
    uint32_t y = 0;
    for (uint32_t c = x; c < x + p.w; ++c) y = std::max(y, skyline[c]);  // push up to the row below
    if (uint64_t(y) + p.h > atlasSize) return PackResult{false, {}, 0, atlasSize};
    for (uint32_t c = x; c < x + p.w; ++c) skyline[c] = y + p.h;
    r.placements[i] = Placement{x, y};
    x += p.w;
  }
  r.ok = true;
  r.usedTexels = area;
  return r;
}

}  // namespace tessera::mta
