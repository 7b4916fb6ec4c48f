#include "rtta/packing.h"

#include <algorithm>
#include <fmt/format.h>

#include "base/error.h"
#include "raster/limits.h"
#include "rtta/parameterize.h"

namespace tessera::rtta {

void validateAtlas(int32_t tw, int32_t th, const Rect& vp, int32_t border) {
  if (tw <= 0 || th <= 0 || tw > kMaxTextureSize || th > kMaxTextureSize)
    throw Error(fmt::format("atlas {}x{}: expected 1..{} texels on each side", tw, th, kMaxTextureSize));
  const PixelRect full = borderedRegion({vp.x, vp.y, vp.x + vp.w, vp.y + vp.h}, border);
  if (tw < full.width() || th < full.height())
    throw Error(fmt::format("atlas {}x{}: must hold the viewport {}x{} plus a border of {} on each side, aligned to even "
                            "pixels ({}x{}), so that a full-screen object fits one layer",
                            tw, th, vp.w, vp.h, border, full.width(), full.height()));
  if (tw % 2 || th % 2)
    throw Error(fmt::format("atlas {}x{}: width and height must be even (regions sit at even positions)", tw, th));
}

AtlasSize atlasPackaging(std::span<Record> records, int32_t twMax, int32_t thMax) {
  std::vector<uint32_t> order;
  for (uint32_t i = 0; i < records.size(); ++i) {
    Record& r = records[i];
    r.layer = -1;
    r.atlas = {};
    if (!r.visible()) continue;
    if (r.viewport.width() > twMax || r.viewport.height() > thMax)
      throw Error(fmt::format("object {}: its region {}x{} does not fit the atlas {}x{}", r.id, r.viewport.width(),
                              r.viewport.height(), twMax, thMax));
    order.push_back(i);
  }
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    const PixelRect &ra = records[a].viewport, &rb = records[b].viewport;
    if (ra.height() != rb.height()) return ra.height() > rb.height();
    if (ra.width() != rb.width()) return ra.width() > rb.width();
    return records[a].id < records[b].id;
  });
  AtlasSize size{twMax, thMax, 0};
  int32_t x = 0, shelfY = 0, shelfH = 0;
  for (uint32_t i : order) {
    Record& r = records[i];
    const int32_t w = r.viewport.width(), h = r.viewport.height();
    if (size.layers == 0) {
      size.layers = 1;
      x = shelfY = 0;
      shelfH = h;
    } else if (x + w > twMax) {  // next shelf
      shelfY += shelfH;
      x = 0;
      shelfH = h;
      if (shelfY + h > thMax) {  // next layer
        ++size.layers;
        shelfY = 0;
      }
    }
    if (size.layers > kMaxArrayLayers)
      throw Error(fmt::format("the atlas needs more than {} layers of {}x{} (GL_MAX_ARRAY_TEXTURE_LAYERS of llvmpipe, "
                              "Trapp & Döllner §4.2): use a larger --atlas or fewer objects",
                              kMaxArrayLayers, twMax, thMax));
    r.layer = size.layers - 1;
    r.atlas = {x, shelfY, x + w, shelfY + h};
    x += w;
  }
  return size;
}

}  // namespace tessera::rtta
