#include "tools/scenes/scene_goldens.h"

#include <fmt/format.h>

#include "raster/cpu_backend.h"

namespace tessera::scenes {

void renderSceneImages(const SceneInfo& s, const golden::ImageVisitor& visit) {
  const std::string scene(s.name);
  const CommandList list = build(s.name, s.width, s.height);
  CpuBackend backend;
  backend.execute(list, scene);
  const std::string command = fmt::format("tessera render {} --size {}x{}", scene, s.width, s.height);
  for (const PresentedImage& p : backend.presented()) {
    golden::RenderedImage img;
    img.texture = backend.texture(p.texture);
    img.name = golden::testName(scene, p.attachment, p.layer, img.texture->desc.layers);
    img.scene = scene;
    img.attachment = p.attachment;
    img.layer = p.layer;
    img.level = p.level;
    img.command = command;
    visit(img);
  }
}

golden::ImageSource allSceneImages() {
  return [](const golden::ImageVisitor& visit) {
    for (const SceneInfo& s : all()) renderSceneImages(s, visit);
  };
}

}  // namespace tessera::scenes
