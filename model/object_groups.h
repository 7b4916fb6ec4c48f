// The objects of RTTA (render-to-texture-atlas, issue 12): which meshes of a Model are captured as one object.
//
// Implements: groupObjects(), the two groupings of `tessera rtta --objects mesh|node`:
// - Mesh: one object per model::Mesh, in model order (object i = mesh i), named after the mesh;
// - Node: one object per scene-graph object (Model::objects: a glTF / Assimp node instance, an AC3D
//   object, an OBJ shape; docs/model-import.md "Objects"), in the order of their first mesh, each
//   holding its meshes in model order and named after the node. A node instanced twice is two objects.
// Both orders depend only on the model, so the object ids RTTA derives from them are deterministic.
// Does not implement: records, culling or anything else of RTTA (rtta/), nor merging meshes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/model.h"

namespace tessera::model {

enum class ObjectGrouping : uint8_t { Mesh, Node };

struct ObjectGroup {
  std::string name;
  std::vector<uint32_t> meshes;  // indices into Model::meshes, ascending; never empty
};

// Parses "mesh" / "node"; throws Error naming the value otherwise.
ObjectGrouping parseObjectGrouping(const std::string& name);
const char* objectGroupingName(ObjectGrouping g);

// The objects of `model` under `grouping`. Node grouping follows Mesh::object; a model built in code
// whose Model::objects is empty (every Mesh::object 0 by default) is then one object named "object0".
// Throws Error when a Mesh::object is out of range of a non-empty Model::objects.
std::vector<ObjectGroup> groupObjects(const Model& model, ObjectGrouping grouping);

}  // namespace tessera::model
