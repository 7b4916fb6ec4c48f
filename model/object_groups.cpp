// groupObjects(): RTTA's objects from a Model (object_groups.h).
#include "model/object_groups.h"

#include "base/error.h"

namespace tessera::model {

ObjectGrouping parseObjectGrouping(const std::string& name) {
  if (name == "mesh") return ObjectGrouping::Mesh;
  if (name == "node") return ObjectGrouping::Node;
  throw Error("--objects '" + name + "': expected mesh or node");
}

const char* objectGroupingName(ObjectGrouping g) { return g == ObjectGrouping::Mesh ? "mesh" : "node"; }

std::vector<ObjectGroup> groupObjects(const Model& model, ObjectGrouping grouping) {
  std::vector<ObjectGroup> groups;
  if (grouping == ObjectGrouping::Mesh) {
    groups.reserve(model.meshes.size());
    for (size_t i = 0; i < model.meshes.size(); ++i) {
      const std::string& name = model.meshes[i].name;
      groups.push_back(ObjectGroup{.name = name.empty() ? "mesh" + std::to_string(i) : name, .meshes = {uint32_t(i)}});
    }
    return groups;
  }
  // Groups are made in the order of each object's first mesh. The loaders keep an object's meshes
  // consecutive, but a model built in code need not: the map from object to group handles both.
  std::vector<int64_t> groupOf(model.objects.empty() ? 1 : model.objects.size(), -1);
  for (size_t i = 0; i < model.meshes.size(); ++i) {
    const uint32_t o = model.meshes[i].object;
    if (o >= groupOf.size())
      throw Error(model.source + ": mesh " + std::to_string(i) + " names object " + std::to_string(o) + " of " +
                  std::to_string(model.objects.size()));
    if (groupOf[o] < 0) {
      groupOf[o] = int64_t(groups.size());
      groups.push_back(
          ObjectGroup{.name = model.objects.empty() ? "object" + std::to_string(o) : model.objects[o].name});
    }
    groups[size_t(groupOf[o])].meshes.push_back(uint32_t(i));
  }
  return groups;
}

}  // namespace tessera::model
