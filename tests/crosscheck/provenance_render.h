// Shared by the candidate-set tests (test_candidates.cpp, test_depth_candidates.cpp): one frame
// rendered by the oracle in provenance mode, as the cross-check renders it for llvmpipe, with the
// presented image's pixels. Does not judge anything: each test edits `pixels` and calls verify::judge.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "raster/provenance.h"

namespace tessera {

struct ProvenanceRender {
  std::unique_ptr<CpuBackend> b;
  TextureData* tex = nullptr;
  PresentedImage img;
  std::vector<uint8_t> pixels;  // top row first, as GL reads back
  size_t w = 0, h = 0;
};

// Renders `list` with provenance for an implementation with 8 sub-pixel bits (llvmpipe's) and takes
// presented image `image`.
inline ProvenanceRender renderWithProvenance(const CommandList& list, uint32_t image = 0) {
  ProvenanceRender r;
  RenderOptions o;
  o.provenance = true;
  o.otherSubpixelBits = 8;
  r.b = std::make_unique<CpuBackend>(o);
  r.b->execute(list, "test");
  r.img = r.b->presented().at(image);
  r.tex = const_cast<TextureData*>(r.b->texture(r.img.texture));
  r.pixels = imagePixels(*r.tex, r.img.level, r.img.layer);
  r.w = r.tex->desc.width, r.h = r.tex->desc.height;
  return r;
}

}  // namespace tessera
