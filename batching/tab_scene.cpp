#include "batching/tab_scene.h"

namespace tessera::batching {

uint64_t TabTexture::bytes() const {
  uint64_t n = 0;
  for (const auto& l : levels) n += l.size();
  return n;
}

}  // namespace tessera::batching
