// Fuzz target `obj`: Wavefront OBJ + MTL through model::loadModel (model/load_obj.cpp and Debian's
// tinyobjloader behind it), then the textures of a model that loaded (fuzz/model_target.h).
//
// The input is an OBJ and an MTL in one file, so that the fuzzer mutates both: everything before the first
// line that is exactly "#MTL" is written as "input.obj", everything after it as "input.mtl" (empty when
// there is no such line), side by side in the scratch directory. The OBJ names its MTL with
// `mtllib input.mtl`; a `map_Kd tex.png` line names a valid 2 x 2 PNG beside them. Both files are written
// for every input, so no input sees the previous one's MTL.
#include <algorithm>
#include <cstdint>
#include <string_view>

#include "fuzz/model_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  constexpr std::string_view kSeparator = "#MTL";
  std::string_view obj = all, mtl;
  for (size_t line = 0; line < all.size();) {
    const size_t end = std::min(all.find('\n', line), all.size());
    std::string_view text = all.substr(line, end - line);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    if (text == kSeparator) {
      obj = all.substr(0, line);
      mtl = end < all.size() ? all.substr(end + 1) : std::string_view();
      break;
    }
    line = end + 1;
  }
  tessera::fuzz::writeScratch("input.mtl", mtl);
  const std::string path = tessera::fuzz::writeScratch("input.obj", obj);
  tessera::fuzz::loadWithTextures(path, "obj");
  return 0;
}
