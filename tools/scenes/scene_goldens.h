// The built-in scenes as a source of golden images (golden/golden_images.h).
//
// Implements: rendering one scene (or all, in scenes::all() order) at its default size on the oracle
// and visiting every presented image under its test name, with the CLI command that reproduces it.
// It sits here, above the golden module, because the golden module must not depend on a tool.
// Does not implement: comparing or rewriting (golden/golden_run.h).
#pragma once

#include "golden/golden_images.h"
#include "tools/scenes/scenes.h"

namespace tessera::scenes {

void renderSceneImages(const SceneInfo& scene, const golden::ImageVisitor& visit);
// Every built-in scene, for golden::GoldenOptions::sceneImages.
golden::ImageSource allSceneImages();

}  // namespace tessera::scenes
