// Internal to tessera_model: the checks of a glTF 2.0 JSON document that come before tinygltf reads it
// (load_gltf.cpp).
//
// Implements: refusing, with the JSON pointer and the reason, what tinygltf would otherwise accept
// silently or wrongly:
// - nesting deeper than ResourceLimits::graphDepth (tinygltf converts `extras` and `extensions`
//   recursively, so a deeply nested value would overflow the stack there);
// - index and count fields that are not non-negative integers (tinygltf casts an index of 2^32 to int,
//   which wraps to 0, and ignores a negative or fractional optional field);
// - node `matrix`, `translation`, `rotation`, `scale` that are not 16 / 3 / 4 / 3 finite numbers;
// - sampler `wrapS` / `wrapT` / `magFilter` / `minFilter` outside glTF 2.0's enums, primitive `mode`
//   outside 0..6;
// - a base colour `texCoord` (or KHR_texture_transform's) that is not a non-negative integer.
// Does not implement: checks that need more than the JSON (accessor ranges: gltf_accessors.h; the node
// graph: gltf_graph.h; whether a primitive has the texcoord set its material names: load_gltf.cpp).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "base/resource_limits.h"

namespace tessera::model::detail::gltf {

// Throws Error("<path>: <JSON pointer>: <reason>") for the first problem found.
void checkDocument(const std::string& path, const nlohmann::json& root, const ResourceLimits& limits);

}  // namespace tessera::model::detail::gltf
