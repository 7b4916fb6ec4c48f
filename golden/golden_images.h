// The images that the golden set covers, rendered now: the images of the caller's frames (the
// built-in scenes: tools/scenes/scene_goldens.h), then the atlas tree frames of railway.glb
// (railway_frames.h).
//
// Implements: the record of one rendered image and its test name (manifest.h), and visiting them in a
// fixed order: the caller's source first, then the frames.
// Dependency: the golden module does not know the built-in scenes (they live in tools/, above every
// library); the CLI and the tests pass them in as an ImageSource.
// Does not implement: comparing (golden_diff.h) or the check / update runs (golden_run.h).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include "raster/texture.h"

namespace tessera::golden {

struct RenderedImage {
  std::string name;   // test name: "<scene>", "<scene>.a<N>", "<scene>.l<N>", "mta_railway.fNNN"
  std::string scene;  // the built-in scene, or "mta_railway"
  uint32_t attachment = 0, layer = 0;
  std::string command;  // the CLI command that reproduces the image
  // The image is (level, layer) of this texture; valid only while the visitor runs.
  const TextureData* texture = nullptr;
  uint32_t level = 0;
};

using ImageVisitor = std::function<void(const RenderedImage&)>;

// "<scene>" for attachment 0, layer 0; ".a<N>" for attachment N > 0; ".l<N>" for layer N > 0 of a
// texture with more than one layer.
std::string testName(std::string_view scene, uint32_t attachment, uint32_t layer, uint32_t layers);

// Renders a set of images and visits each one (in a fixed order).
using ImageSource = std::function<void(const ImageVisitor&)>;

// `source` (if any), then (unless railwayPath is empty) the atlas tree frames of railwayPath.
// Throws Error naming railwayPath when it is given but missing.
void renderGoldenImages(const ImageSource& source, const std::string& railwayPath, const ImageVisitor& visit);

}  // namespace tessera::golden
