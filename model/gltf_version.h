// Internal to tessera_model: which glTF generation a parsed .gltf JSON document is (load_gltf.cpp).
//
// Implements: the decision between glTF 1.0 (read by Assimp) and glTF 2.0 (read by tinygltf) from the
// JSON root, including the 1.0 files that early converters wrote with a numeric `asset.version`
// ("asset": {"version": 1}) or without `asset.version` at all, which Assimp's glTF 1.0 importer refuses
// as they are (it wants a string starting with "1"): for those, gltf1WithStringVersion() gives the
// document with `asset.version` set to "1.0", which load_gltf.cpp hands to Assimp in place of the file.
// Does not implement: reading either generation, or the binary .glb header (its version word decides
// there, load_gltf.cpp).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace tessera::model::detail::gltf {

enum class Generation {
  One,                      // glTF 1.0 with a string version "1...": Assimp reads the file as it is
  OneWithoutStringVersion,  // glTF 1.0 whose asset.version is a number in [1, 2) or missing
  Two,                      // everything else: glTF 2.0 rules apply (and report a missing or bad version)
};

// glTF 1.0 when asset.version is a string starting with "1" or a number in [1, 2); when asset.version
// is missing, when the root has a 1.0-only key (`techniques`, `programs`, `shaders`: glTF 2.0 dropped
// them) or keeps its meshes in an object keyed by id (1.0) instead of an array (2.0). Otherwise Two.
Generation generationOf(const nlohmann::json& root);

// The document's text with asset.version set to the string "1.0" (the rest re-serialized unchanged).
std::string gltf1WithStringVersion(const nlohmann::json& root);

}  // namespace tessera::model::detail::gltf
