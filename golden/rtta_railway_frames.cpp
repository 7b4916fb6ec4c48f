#include "golden/rtta_railway_frames.h"

#include <fmt/format.h>

#include <filesystem>
#include <set>

#include "base/error.h"
#include "batching/input_batches.h"
#include "model/model.h"
#include "mta/camera.h"
#include "mta/camera_path.h"
#include "raster/cpu_backend.h"
#include "rtta/rtta_record.h"

namespace tessera::golden {

std::vector<RailwayFrame> rttaRailwayFrames(const std::string& railwayPath) {
  constexpr uint32_t kFrames = 24, kWidth = 256, kHeight = 192;
  if (!std::filesystem::exists(railwayPath))
    throw Error(railwayPath + ": not found; the render-to-texture-atlas goldens render railway.glb (pass --railway PATH)");
  const model::Model m = model::loadModel(railwayPath);
  std::vector<uint32_t> objectOf(m.meshes.size());
  std::vector<std::string> names;
  for (size_t i = 0; i < m.meshes.size(); ++i) objectOf[i] = uint32_t(i), names.push_back(m.meshes[i].name);
  const rtta::RttaScene s = rtta::makeRttaScene(batching::prepareInput(m), objectOf, names);
  const mta::CameraPath path = mta::builtinPath("orbit", s.tab.bounds, kFrames);
  const std::set<size_t> keep = {0, 8, 16, 23};
  CpuBackend backend;
  std::vector<RailwayFrame> out;
  for (size_t i : keep) {
    rtta::RttaView view;
    view.mvp = mta::viewProjection(path.frames[i], kWidth, kHeight);
    view.eye = path.frames[i].eye;
    view.width = kWidth, view.height = kHeight;
    rtta::RttaOptions o;
    o.mode = rtta::Mode::Rtta;
    const rtta::RttaFrame f = rtta::recordRttaFrame(s, view, o);
    backend.execute(f.list, "rtta_railway");
    auto tex = std::make_shared<TextureData>(*backend.texture(f.screen));
    out.push_back({fmt::format("{}.f{:03}", kRttaRailwayScene, i), tex,
                   "tessera rtta render railway.glb --mode rtta --path orbit --frames 24 --size 256x192 --save-every 8"});
  }
  return out;
}

}  // namespace tessera::golden
