#include "golden/golden_images.h"

#include <fmt/format.h>

#include "golden/railway_frames.h"
#include "raster/cpu_backend.h"

namespace tessera::golden {

std::string testName(std::string_view scene, uint32_t attachment, uint32_t layer, uint32_t layers) {
  std::string n(scene);
  if (attachment) n += ".a" + std::to_string(attachment);
  if (layers > 1 && layer) n += ".l" + std::to_string(layer);
  return n;
}

void renderSceneImages(const scenes::SceneInfo& s, const ImageVisitor& visit) {
  const std::string scene(s.name);
  const CommandList list = scenes::build(s.name, s.width, s.height);
  CpuBackend backend;
  backend.execute(list, scene);
  const std::string command = fmt::format("tessera render {} --size {}x{}", scene, s.width, s.height);
  for (const PresentedImage& p : backend.presented()) {
    RenderedImage img;
    img.texture = backend.texture(p.texture);
    img.name = testName(scene, p.attachment, p.layer, img.texture->desc.layers);
    img.scene = scene;
    img.attachment = p.attachment;
    img.layer = p.layer;
    img.level = p.level;
    img.command = command;
    visit(img);
  }
}

void renderGoldenImages(const std::string& railwayPath, const ImageVisitor& visit) {
  for (const scenes::SceneInfo& s : scenes::all()) renderSceneImages(s, visit);
  if (railwayPath.empty()) return;
  for (const RailwayFrame& f : railwayFrames(railwayPath)) {
    RenderedImage img;
    img.name = f.name;
    img.scene = kRailwayScene;
    img.command = f.command;
    img.texture = f.image.get();
    visit(img);
  }
}

}  // namespace tessera::golden
