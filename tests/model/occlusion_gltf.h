// A glTF 2.0 file with a second texture layer (occlusionTexture) for the loader and atlas tree tests.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/model/model_test_util.h"

namespace tessera::model::testing {

// Two quads beside each other: material 0 ("lit") has a base colour texture on TEXCOORD_0 and an
// occlusionTexture on TEXCOORD_1 (clamped sampler, strength `strength`); material 1 ("plain") has the
// base colour texture only. `edit` may change the JSON before it is written.
inline std::string writeOcclusionGltf(const ScratchDir& dir, double strength = 0.5,
                                      const std::function<void(nlohmann::json&)>& edit = {}) {
  writeChecker(dir / "base.png", 4, 4);
  writeChecker(dir / "occlusion.png", 2, 2);
  std::string bin;
  appendBytes(bin, std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});  // 0: 48 bytes
  appendBytes(bin, std::vector<float>{0, 0, 3, 0, 3, 3, 0, 3});              // 48: TEXCOORD_0, 32 bytes
  appendBytes(bin, std::vector<float>{0.25f, 0.25f, 0.75f, 0.25f, 0.75f, 0.75f, 0.25f, 0.75f});  // 80: TEXCOORD_1
  appendBytes(bin, std::vector<uint8_t>{0, 1, 2, 0, 2, 3});                  // 112: 6 bytes
  nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"buffers", {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 32}},
        {{"buffer", 0}, {"byteOffset", 80}, {"byteLength", 32}},
        {{"buffer", 0}, {"byteOffset", 112}, {"byteLength", 6}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 3}, {"componentType", 5121}, {"count", 6}, {"type", "SCALAR"}}}},
      {"images", {{{"uri", "base.png"}}, {{"uri", "occlusion.png"}}}},
      {"samplers", {{{"wrapS", 33071}, {"wrapT", 33071}}}},
      {"textures", {{{"source", 0}}, {{"source", 1}, {"sampler", 0}}}},
      {"materials",
       {{{"name", "lit"},
         {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
         {"occlusionTexture", {{"index", 1}, {"texCoord", 1}, {"strength", strength}}}},
        {{"name", "plain"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}, {"TEXCOORD_1", 2}}}, {"indices", 3}, {"material", 0}}}}},
        {{"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 3}, {"material", 1}}}}}}},
      {"nodes", {{{"mesh", 0}}, {{"mesh", 1}, {"translation", {2.0, 0.0, 0.0}}}}},
      {"scenes", {{{"nodes", {0, 1}}}}},
      {"scene", 0}};
  if (edit) edit(j);
  const std::string path = dir / "occlusion.gltf";
  writeFile(path, j.dump(1));
  return path;
}

}  // namespace tessera::model::testing
