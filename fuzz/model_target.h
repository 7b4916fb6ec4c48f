// What the three model targets (gltf, obj, ac3d) share: loading a model file from the scratch directory
// through model::loadModel, then measuring every texture it names and decoding the small ones.
//
// Implements: writeTexturePng() (a valid 2 x 2 RGBA PNG, "tex.png" in the scratch directory, so that a
// seed or a mutation that names it reaches the texture decoder through a real file) and loadWithTextures().
// Work per input is capped: at most kMaxTextures textures are probed (probeTexture reads the header only),
// and only those of at most 256 x 256 texels are decoded (loadTexture), so that an input describing a huge
// image measures the loader, not the machine.
// Does not implement: the per-format splitting of the input into files (each target does that).
#pragma once

#include <cstdint>
#include <string>

#include "base/error.h"
#include "fuzz/fuzz_support.h"
#include "model/model.h"

namespace tessera::fuzz {

constexpr size_t kMaxTextures = 16;
constexpr uint32_t kMaxDecodedSide = 256;

// A 2 x 2 RGBA PNG (red, half-transparent green / blue, transparent white).
inline void writeTexturePng() {
  static const uint8_t kPng[] = {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49,
                                 0x48, 0x44, 0x52, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x02, 0x08, 0x06,
                                 0x00, 0x00, 0x00, 0x72, 0xb6, 0x0d, 0x24, 0x00, 0x00, 0x00, 0x15, 0x49, 0x44,
                                 0x41, 0x54, 0x78, 0xda, 0x63, 0xf8, 0xcf, 0xc0, 0xf0, 0x1f, 0x08, 0x1b, 0x18,
                                 0x80, 0x34, 0x08, 0x30, 0x00, 0x00, 0x43, 0xd3, 0x08, 0x79, 0x78, 0xce, 0x21,
                                 0xcc, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
  static const bool written = (writeScratch("tex.png", std::span<const uint8_t>(kPng, sizeof kPng)), true);
  (void)written;
}

// The work of loadWithTextures(), without the descriptor check.
inline void loadAndProbe(const std::string& path) {
  model::Model m;
  try {
    m = model::loadModel(path);
  } catch (const Error& e) {
    note("model", e.what());
    return;
  }
  if (verbose())
    note("model", "loaded by " + m.loader + ": " + std::to_string(m.meshes.size()) + " mesh(es), " +
                      std::to_string(m.triangleCount()) + " triangle(s), " + std::to_string(m.textures.size()) +
                      " texture(s), " + std::to_string(m.notes.size()) + " note(s)");
  for (size_t i = 0; i < m.textures.size() && i < kMaxTextures; ++i) {
    try {
      const model::TextureInfo info = model::probeTexture(m, i);
      if (info.width > 0 && info.height > 0 && info.width <= kMaxDecodedSide && info.height <= kMaxDecodedSide) {
        const model::Image img = model::loadTexture(m, i);
        if (verbose())
          note("model", "texture decoded: " + std::to_string(img.width) + "x" + std::to_string(img.height));
      }
    } catch (const Error& e) {
      note("model", e.what());
    }
  }
}

// Loads `path`; if that succeeds, probes up to kMaxTextures textures and decodes the small ones.
// Errors are the expected outcome for hostile input and are swallowed; anything else escapes. Checks that
// no file descriptor is left open (DescriptorCheck), naming `target` if one is.
inline void loadWithTextures(const std::string& path, std::string_view target) {
  writeTexturePng();
  const DescriptorCheck descriptors;
  loadAndProbe(path);
  descriptors.expectNoLeak(target);
}

}  // namespace tessera::fuzz
