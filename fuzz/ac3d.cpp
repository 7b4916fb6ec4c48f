// Fuzz target `ac3d`: AC3D (.ac) through model::loadModel (the project's AC3D reader, model/ac3d_file.h),
// then the textures of a model that loaded (fuzz/model_target.h).
//
// The input is one .ac file, written to the scratch directory as "input.ac". A `texture "tex.png"` line
// names a valid 2 x 2 PNG beside it.
#include <cstdint>
#include <span>

#include "fuzz/model_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = tessera::fuzz::writeScratch("input.ac", std::span<const uint8_t>(data, size));
  tessera::fuzz::loadWithTextures(path, "ac3d");
  return 0;
}
