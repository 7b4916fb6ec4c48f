// Fuzz target `scene_manifest`: the scene manifest reader (model/scene_manifest.h, docs/model-import.md
// "Scenes of several files"): the JSON of a manifest into its entries, and nothing more.
//
// The input is one manifest, written to the scratch directory as "input.json". Beside it the target keeps
// a fixed set of entries to refer to: empty model files a.glb, c.obj and parts/b.gltf, a directory sub/ and
// a manifest nested.json, so that the reader's checks of `file` (exists, not a directory, not another
// manifest) all run. Only readSceneManifest is called: it opens the manifest and stats the listed files,
// it never opens them (mergeScene, which loads the models, is not fuzzed here: the model readers have
// targets of their own). A file named by an absolute path is only stat'ed, never read.
// For a manifest it accepts, every entry must name a file, and its transform must be finite and affine
// (last row 0 0 0 1), whatever the translation, rotation and scale; else the target reports a finding.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "base/error.h"
#include "fuzz/fuzz_support.h"
#include "model/scene_manifest.h"

namespace {

using namespace tessera;

void makeFixtures() {
  static const bool done = [] {
    const std::filesystem::path dir = fuzz::scratchDir();
    std::filesystem::create_directories(dir / "parts");
    std::filesystem::create_directories(dir / "sub");
    fuzz::writeScratch("a.glb", std::string_view());
    fuzz::writeScratch("c.obj", std::string_view());
    fuzz::writeScratch("parts/b.gltf", std::string_view());
    fuzz::writeScratch("nested.json", std::string_view(R"({"schema": 1, "models": [{"file": "a.glb"}]})"));
    return true;
  }();
  (void)done;
}

void run(const uint8_t* data, size_t size) {
  makeFixtures();
  const std::string path = fuzz::writeScratch("input.json", std::span<const uint8_t>(data, size));
  model::detail::Scene scene;
  try {
    scene = model::detail::readSceneManifest(path);
  } catch (const Error& e) {
    fuzz::note("scene_manifest", e.what());
    return;
  }
  if (scene.entries.empty()) fuzz::propertyViolated("scene_manifest", "an accepted manifest has no entries");
  for (const model::detail::SceneEntry& e : scene.entries) {
    if (e.file.empty()) fuzz::propertyViolated("scene_manifest", e.where + ": an accepted entry names no file");
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        if (!std::isfinite(e.transform[c][r]))
          fuzz::propertyViolated("scene_manifest", e.where + ": the transform is not finite");
    if (e.transform[0][3] != 0.0 || e.transform[1][3] != 0.0 || e.transform[2][3] != 0.0 || e.transform[3][3] != 1.0)
      fuzz::propertyViolated("scene_manifest", e.where + ": the transform is not affine");
  }
  if (fuzz::verbose()) fuzz::note("scene_manifest", std::to_string(scene.entries.size()) + " entr(y/ies) accepted");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fuzz::DescriptorCheck descriptors;
  run(data, size);
  descriptors.expectNoLeak("scene_manifest");
  return 0;
}
