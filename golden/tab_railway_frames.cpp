#include "golden/tab_railway_frames.h"

#include <fmt/format.h>

#include <filesystem>
#include <set>

#include "base/error.h"
#include "batching/batcher.h"
#include "batching/input_batches.h"
#include "batching/tab_record.h"
#include "model/model.h"
#include "mta/camera.h"
#include "mta/camera_path.h"
#include "raster/cpu_backend.h"

namespace tessera::golden {

std::vector<RailwayFrame> tabRailwayFrames(const std::string& railwayPath) {
  constexpr uint32_t kFrames = 24, kWidth = 256, kHeight = 192;
  if (!std::filesystem::exists(railwayPath))
    throw Error(railwayPath + ": not found; the texture-array batching goldens render railway.glb (pass --railway PATH)");
  batching::TabScene s = batching::prepareInput(model::loadModel(railwayPath));
  batching::runAlgorithm1(s, batching::TabParams{});
  const mta::CameraPath path = mta::builtinPath("orbit", s.bounds, kFrames);
  const std::set<size_t> keep = {0, 8, 16, 23};
  CpuBackend backend;
  std::vector<RailwayFrame> out;
  for (size_t i : keep) {
    batching::TabView view;
    view.mvp = mta::viewProjection(path.frames[i], kWidth, kHeight);
    view.eye = path.frames[i].eye;
    view.width = kWidth, view.height = kHeight;
    backend.execute(batching::recordTabFrame(s, batching::Variant::Batched, view), "tab_railway");
    const PresentedImage p = backend.presented().at(0);
    auto tex = std::make_shared<TextureData>(*backend.texture(p.texture));
    out.push_back({fmt::format("{}.f{:03}", kTabRailwayScene, i), tex,
                   "tessera tab build railway.glb -o railway.tab && tessera tab render railway.tab --path orbit --frames 24 "
                   "--size 256x192 --save-every 8"});
  }
  return out;
}

}  // namespace tessera::golden
