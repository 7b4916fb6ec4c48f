// Test helpers: render a command list on the oracle and read back its presented images.
#pragma once

#include <string>
#include <vector>

#include "raster/cpu_backend.h"
#include "raster/image_io.h"

namespace tessera::testing {

struct Rendered {
  std::vector<std::vector<uint8_t>> images;  // top-down pixels of each presented image
  std::vector<std::string> hashes;
  detail::PipelineStats stats;
};

inline Rendered renderList(const CommandList& list, int threads) {
  CpuBackend b(RenderOptions{threads});
  b.execute(list, "test");
  Rendered r;
  for (const PresentedImage& p : b.presented()) {
    const TextureData& t = *b.texture(p.texture);
    r.images.push_back(imagePixels(t, p.level, p.layer));
    r.hashes.push_back(imageSha256(t, p.level, p.layer));
  }
  r.stats = b.stats();
  return r;
}

}  // namespace tessera::testing
