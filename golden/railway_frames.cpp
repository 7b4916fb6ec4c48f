#include "golden/railway_frames.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <set>

#include "base/error.h"
#include "model/model.h"
#include "mta/build.h"
#include "mta/camera_path.h"
#include "mta/paging_file.h"
#include "mta/scene.h"
#include "mta/tree_renderer.h"

namespace tessera::golden {

namespace {

constexpr uint32_t kFrames = 60, kWidth = 256, kHeight = 192;
constexpr double kCapacityMiB = 48.0;
constexpr const char* kBudget = "4MiB";
constexpr uint32_t kQueue = 32;

// `--size 256x192 --capacity 48 --budget 4MiB` with every other option at its default.
mta::RendererOptions rendererOptions() {
  mta::RendererOptions o;
  o.mode = mta::RenderMode::AtlasTree;
  o.width = kWidth;
  o.height = kHeight;
  o.tau = 0.0;
  o.bound = mta::DistanceBound::PerNode;
  o.groupBinds = true;
  o.threads = 0;
  o.residency.capacityBytes = uint64_t(kCapacityMiB * 1048576.0);
  o.residency.budget = mta::LoadBudget::parse(kBudget, "--budget");
  o.residency.maxQueue = kQueue;
  return o;
}

}  // namespace

std::vector<RailwayFrame> railwayFrames(const std::string& railwayPath) {
  namespace fs = std::filesystem;
  if (!fs::exists(railwayPath))
    throw Error(railwayPath + ": not found; the atlas tree goldens render railway.glb (pass --railway PATH)");
  const fs::path dir = fs::temp_directory_path() / ("tessera-golden-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  struct Cleanup {
    fs::path d;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(d, ec);
    }
  } cleanup{dir};
  const std::string tree = (dir / "tree.mta").string();
  mta::BuildParams bp;
  bp.dMin = 5.0;
  mta::buildMta(mta::sceneFromModel(std::make_shared<const model::Model>(model::loadModel(railwayPath))), bp, tree);

  mta::PagingFile file(tree);
  const mta::CameraPath path = mta::builtinPathOverTree("thesis", file.meta(), kFrames);
  mta::TreeRenderer renderer(file, rendererOptions());
  const std::set<size_t> keep = {0, 15, 30, 45, 59};
  std::vector<RailwayFrame> out;
  for (size_t i = 0; i < path.frames.size(); ++i) {
    mta::FrameResult r = renderer.renderFrame(path.frames[i]);
    if (!keep.count(i)) continue;
    TextureDesc d;
    d.width = renderer.options().width;
    d.height = renderer.options().height;
    auto tex = std::make_shared<TextureData>(d);
    tex->levels[0] = std::move(r.image);
    out.push_back(
        {fmt::format("{}.f{:03}", kRailwayScene, i), tex,
         "tessera mta build railway.glb --d-min 5 -o tree.mta && tessera mta render tree.mta --path thesis --frames 60 "
         "--size 256x192 --capacity 48 --budget 4MiB --save-every 15"});
  }
  return out;
}

}  // namespace tessera::golden
