// Fuzz target `gltf`: glTF 2.0 through model::loadModel (model/load_gltf.cpp, model/gltf_accessors.h and
// Debian's tinygltf behind them), then the textures of a model that loaded (fuzz/model_target.h).
//
// The input is one file: a .glb when it starts with the "glTF" magic, else a .gltf (JSON), written to the
// scratch directory under that extension. External files it can name: "tex.png" (a valid 2 x 2 PNG beside
// it) and itself ("input.gltf" / "input.glb", e.g. as a buffer uri); embedded images (data: URIs, a .glb's
// BIN chunk) reach the decoders directly. A .glb or JSON declaring glTF 1.0 is handed to Assimp by the loader.
#include <cstdint>
#include <cstring>
#include <span>

#include "fuzz/model_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::string path =
      tessera::fuzz::writeScratch(binary ? "input.glb" : "input.gltf", std::span<const uint8_t>(data, size));
  tessera::fuzz::loadWithTextures(path, "gltf");
  return 0;
}
