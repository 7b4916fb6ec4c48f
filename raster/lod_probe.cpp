// lodMap(): a probed replay of a CommandList (raster/lod_probe.h). The records themselves are written
// by the sampler (sample.cpp) and the rasterizer (rast.cpp).
#include "raster/lod_probe.h"

#include <string>

#include "base/error.h"
#include "raster/cpu_backend.h"

namespace tessera {

LodMap lodMap(const CommandList& list, int threads, std::string_view frameName) {
  RenderOptions o;
  o.threads = threads;
  o.lodProbe = true;
  CpuBackend backend(o);
  backend.execute(list, frameName);
  const std::vector<PresentedImage> shown = backend.presented();
  if (shown.empty()) throw Error(std::string(frameName) + ": the frame presents no image (no render target bound)");
  if (const LodMap* m = backend.lodMap(shown[0])) return *m;
  // Nothing was drawn into it (e.g. only uploads): every pixel without a lookup.
  const TextureDesc& d = backend.texture(shown[0].texture)->desc;
  const int32_t w = int32_t(levelWidth(d, shown[0].level)), h = int32_t(levelHeight(d, shown[0].level));
  return LodMap{w, h, std::vector<LodPixel>(size_t(w) * size_t(h))};
}

}  // namespace tessera
