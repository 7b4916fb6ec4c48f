// The table of built-in programs, looked up by stable name (the GL backend's GLSL twins use the
// same names). Each program lives in its own file; this file only lists them.
#include <array>

#include "raster/program.h"

namespace tessera {
namespace programs {
const Program& flatColor();
const Program& vertexColor();
const Program& textured();
const Program& texarrayBatch();
const Program& atlasDisplace();
const Program& objectId();
const Program& atlasCapture();
const Program& atlasSprite();
const Program& atlasCaptureTab();
const Program& atlasSpriteAo();
const Program& texturedLayers();
}  // namespace programs

static const std::array<const Program*, 11>& table() {
  static const std::array<const Program*, 11> t = {&programs::flatColor(),     &programs::vertexColor(),
                                                  &programs::textured(),      &programs::texarrayBatch(),
                                                  &programs::atlasDisplace(), &programs::objectId(),
                                                  &programs::atlasCapture(),  &programs::atlasSprite(),
                                                  &programs::atlasCaptureTab(), &programs::atlasSpriteAo(),
                                                  &programs::texturedLayers()};
  return t;
}

const Program* findProgram(std::string_view name) {
  for (const Program* p : table())
    if (p->name() == name) return p;
  return nullptr;
}

std::vector<std::string_view> programNames() {
  std::vector<std::string_view> names;
  for (const Program* p : table()) names.push_back(p->name());
  return names;
}

}  // namespace tessera
