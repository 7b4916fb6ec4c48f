#include "golden/golden_images.h"

#include "golden/railway_frames.h"
#include "golden/rtta_railway_frames.h"
#include "golden/tab_railway_frames.h"

namespace tessera::golden {

std::string testName(std::string_view scene, uint32_t attachment, uint32_t layer, uint32_t layers) {
  std::string n(scene);
  if (attachment) n += ".a" + std::to_string(attachment);
  if (layers > 1 && layer) n += ".l" + std::to_string(layer);
  return n;
}

void renderGoldenImages(const ImageSource& source, const std::string& railwayPath, const ImageVisitor& visit) {
  if (source) source(visit);
  if (railwayPath.empty()) return;
  auto visitFrames = [&](const std::vector<RailwayFrame>& frames, const char* scene) {
    for (const RailwayFrame& f : frames) {
      RenderedImage img;
      img.name = f.name;
      img.scene = scene;
      img.command = f.command;
      img.texture = f.image.get();
      visit(img);
    }
  };
  visitFrames(railwayFrames(railwayPath), kRailwayScene);
  visitFrames(tabRailwayFrames(railwayPath), kTabRailwayScene);
  visitFrames(rttaRailwayFrames(railwayPath), kRttaRailwayScene);
}

}  // namespace tessera::golden
