#include "tools/cli/mta_golden.h"

#include <unistd.h>

#include <filesystem>
#include <set>

#include "model/model.h"
#include "mta/build.h"
#include "mta/scene.h"
#include "raster/command_list.h"
#include "tools/cli/mta_path_run.h"

namespace tessera::cli {

std::vector<MtaGoldenFrame> mtaGoldenFrames(const std::string& railwayPath) {
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

  PathRunArgs a;
  a.input = tree;
  a.frames = 60;
  a.size = "256x192";
  a.capacityMiB = 48.0;
  a.budget = "4MiB";
  mta::PagingFile file(tree);
  const mta::CameraPath path = loadPath(a, file.meta());
  mta::TreeRenderer renderer(file, rendererOptions(a, mta::RenderMode::AtlasTree));
  const std::set<size_t> keep = {0, 15, 30, 45, 59};
  std::vector<MtaGoldenFrame> out;
  for (size_t i = 0; i < path.frames.size(); ++i) {
    mta::FrameResult r = renderer.renderFrame(path.frames[i]);
    if (!keep.count(i)) continue;
    TextureDesc d;
    d.width = renderer.options().width;
    d.height = renderer.options().height;
    auto tex = std::make_shared<TextureData>(d);
    tex->levels[0] = std::move(r.image);
    char name[32];
    std::snprintf(name, sizeof name, "mta_railway.f%03zu", i);
    out.push_back({name, tex,
                   "tessera mta build railway.glb --d-min 5 -o tree.mta && tessera mta render tree.mta --path thesis --frames 60 "
                   "--size 256x192 --capacity 48 --budget 4MiB --save-every 15"});
  }
  return out;
}

}  // namespace tessera::cli
