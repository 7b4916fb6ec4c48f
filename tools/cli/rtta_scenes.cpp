#include "tools/cli/rtta_scenes.h"

#include <cstdio>

#include "base/error.h"
#include "batching/input_batches.h"
#include "model/model.h"

namespace tessera::cli {

std::vector<std::string> builtinRttaSceneNames() { return {}; }

LoadedRttaScene loadRttaScene(const std::string& input, const std::string& objects, const ResourceLimits& limits, bool quiet) {
  const model::Model m = model::loadModel(input, limits);
  batching::InputOptions io;
  if (!quiet)
    io.progress = [](size_t done, size_t total) {
      if (done == total) std::fprintf(stderr, "rtta: %zu textures decoded with mip chains\n", total);
    };
  std::vector<uint32_t> objectOf(m.meshes.size());
  std::vector<std::string> names;
  if (objects != "mesh") throw Error("--objects " + objects + ": not available yet");
  for (size_t i = 0; i < m.meshes.size(); ++i) {
    objectOf[i] = uint32_t(i);
    names.push_back(m.meshes[i].name.empty() ? "mesh " + std::to_string(i) : m.meshes[i].name);
  }
  return {rtta::makeRttaScene(batching::prepareInput(m, io), objectOf, std::move(names))};
}

}  // namespace tessera::cli
