#include "model/gltf_version.h"

namespace tessera::model::detail::gltf {

Generation generationOf(const nlohmann::json& root) {
  const nlohmann::json::json_pointer vp("/asset/version");
  if (root.contains(vp)) {
    const nlohmann::json& v = root.at(vp);
    if (v.is_string()) return v.get<std::string>().starts_with("1") ? Generation::One : Generation::Two;
    // A number: some early COLLADA converters wrote "version": 1. Only [1, 2) is glTF 1.0; any other
    // number is left to the 2.0 rules, which ask for a string.
    if (v.is_number() && v.get<double>() >= 1.0 && v.get<double>() < 2.0) return Generation::OneWithoutStringVersion;
    return Generation::Two;
  }
  // No version: the keys only glTF 1.0 has decide. Without them the file gets the 2.0 error
  // ("/asset/version: missing"), which is what a 2.0 writer that forgot the asset needs to hear.
  for (const char* key : {"techniques", "programs", "shaders"})
    if (root.contains(key)) return Generation::OneWithoutStringVersion;
  if (root.contains("meshes") && root["meshes"].is_object()) return Generation::OneWithoutStringVersion;
  return Generation::Two;
}

std::string gltf1WithStringVersion(const nlohmann::json& root) {
  nlohmann::json copy = root;
  if (!copy.contains("asset") || !copy["asset"].is_object()) copy["asset"] = nlohmann::json::object();
  copy["asset"]["version"] = "1.0";
  return copy.dump();
}

}  // namespace tessera::model::detail::gltf
