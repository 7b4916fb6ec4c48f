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
  LodMap m;
  lodMap(backend, list, m, frameName);
  return m;
}

void lodMap(CpuBackend& backend, const CommandList& list, LodMap& out, std::string_view frameName) {
  if (!backend.options().lodProbe) throw Error(std::string(frameName) + ": lodMap needs a backend made with RenderOptions::lodProbe");
  backend.execute(list, frameName);
  const std::vector<PresentedImage> shown = backend.presented();
  if (shown.empty()) throw Error(std::string(frameName) + ": the frame presents no image (no render target bound)");
  if (const LodMap* m = backend.lodMap(shown[0])) {
    out = *m;  // copy-assignment keeps out's storage when it is large enough
    return;
  }
  // Nothing was drawn into it (e.g. only uploads): every pixel without a lookup.
  const TextureDesc& d = backend.texture(shown[0].texture)->desc;
  out.width = int32_t(levelWidth(d, shown[0].level));
  out.height = int32_t(levelHeight(d, shown[0].level));
  out.pixels.assign(size_t(out.width) * size_t(out.height), LodPixel{});
}

}  // namespace tessera
