#include "tools/cli/rtta_scenes.h"

#include <cstdio>

#include "base/det_math.h"
#include "base/error.h"
#include "batching/batcher.h"
#include "batching/input_batches.h"
#include "model/five_objects.h"
#include "model/model.h"
#include "model/object_groups.h"

namespace tessera::cli {

std::vector<std::string> builtinRttaSceneNames() { return {"five"}; }

mta::CameraPath fiveOrbit(uint32_t frames, int width, int height) {
  mta::CameraPath p;
  p.name = "five-orbit";
  const uint32_t n = frames ? frames : 24;
  const glm::dvec3 d = model::kFiveObjectEye - model::kFiveObjectTarget;
  for (uint32_t i = 0; i < n; ++i) {
    const double angle = n > 1 ? (-0.25 + 0.5 * double(i) / double(n - 1)) * kPi : 0.0;  // -45..+45 degrees
    const double c = detCos(angle), s = detSin(angle);
    mta::Camera cam;
    cam.target = model::kFiveObjectTarget;
    cam.eye = cam.target + glm::dvec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
    cam.up = model::kFiveObjectUp;
    cam.tanHalfFovX = model::kFiveObjectTanHalfFovY * double(width) / double(height);
    cam.nearPlane = model::kFiveObjectNear;
    cam.farPlane = model::kFiveObjectFar;
    p.frames.push_back(cam);
  }
  return p;
}

LoadedRttaScene loadRttaScene(const std::string& input, const std::string& objects, const ResourceLimits& limits, bool quiet,
                              bool withTab) {
  const model::ObjectGrouping grouping = model::parseObjectGrouping(objects);
  const model::Model m = input == "five" ? model::fiveObjectModel() : model::loadModel(input, limits);
  batching::InputOptions io;
  if (!quiet)
    io.progress = [](size_t done, size_t total) {
      if (done == total) std::fprintf(stderr, "rtta: %zu textures decoded with mip chains\n", total);
    };
  const std::vector<model::ObjectGroup> groups = model::groupObjects(m, grouping);
  std::vector<uint32_t> objectOf(m.meshes.size());
  std::vector<std::string> names;
  for (uint32_t g = 0; g < groups.size(); ++g) {
    names.push_back(groups[g].name);
    for (uint32_t mesh : groups[g].meshes) objectOf[mesh] = g;
  }
  batching::TabScene tab = batching::prepareInput(m, io);
  if (withTab) batching::runAlgorithm1(tab, batching::TabParams{});
  LoadedRttaScene out{rtta::makeRttaScene(std::move(tab), objectOf, std::move(names))};
  return out;
}

}  // namespace tessera::cli
