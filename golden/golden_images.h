// The images that the golden set covers, rendered now: every presented image of every built-in scene,
// then the atlas tree frames of railway.glb (railway_frames.h).
//
// Implements: rendering them in a fixed order (scenes in scenes::all() order, each scene's presented
// images in presentation order, then the frames) and naming each with its test name (manifest.h).
// Dependency: the golden set is defined by the built-in scenes, so tessera_golden links tessera_scenes
// (tools/scenes/), a library that lives under tools/ but is a plain library without the CLI.
// Does not implement: comparing (golden_diff.h) or the check / update runs (golden_run.h).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include "raster/texture.h"
#include "tools/scenes/scenes.h"

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

// Renders one built-in scene at its default size on the oracle and visits every presented image.
void renderSceneImages(const scenes::SceneInfo& scene, const ImageVisitor& visit);

// Every built-in scene, then (unless railwayPath is empty) the atlas tree frames of railwayPath.
// Throws Error naming railwayPath when it is given but missing.
void renderGoldenImages(const std::string& railwayPath, const ImageVisitor& visit);

}  // namespace tessera::golden
