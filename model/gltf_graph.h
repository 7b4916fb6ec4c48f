// Internal to tessera_model: the node graph of a glTF 2.0 scene, expanded without recursion
// (load_gltf.cpp).
//
// Implements: the local transform of a node (matrix, or T * R * S), and the expansion of the graph
// below a scene's root nodes in two passes, both with explicit stacks whatever the depth of the file:
// - check(): every node and mesh reference is in range, there is no cycle, no path is longer than
//   ResourceLimits::graphDepth, and the instances (every node reached, k times when k paths reach it),
//   the triangles and the vertices they expand to are within the model budgets. Each node is looked at
//   once and its totals are summed from its children's (saturating), so a 3 KB file that describes 2^40
//   instances is refused after looking at its 80 nodes, before any geometry is read or transformed;
// - forEachInstance(): calls a function for every node instance in depth-first pre-order (a node before
//   its children, children in the order the file lists them, roots in scene order) with its world
//   transform, composed in double from the root down (compose() in loaders.h).
// A node reached along two paths is expanded twice (glTF 2.0 forbids it; files that do it get instancing).
// Does not implement: reading meshes (the caller's meshCost and visit functions), skins, cameras.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <functional>
#include <glm/mat4x4.hpp>
#include <string>
#include <vector>

#include "base/resource_limits.h"

namespace tessera::model::detail::gltf {

// What one instance of a mesh adds to the model: its triangles and its vertices.
struct MeshCost {
  uint64_t triangles = 0, vertices = 0;
};

// The local transform of node `n`: its matrix when it has one (16 numbers, gltf_checks.h), else
// T * R * S (glTF 2.0 §3.5.3) with the quaternion used as stored (no trigonometry).
glm::dmat4 nodeTransform(const tinygltf::Node& n);

class NodeGraph {
 public:
  // `roots` come from the JSON array named by `rootsPointer` ("/scenes/0/nodes", or "/nodes" for the
  // nodes nobody lists as a child when the file has no scene).
  NodeGraph(const std::string& path, const tinygltf::Model& m, const ResourceLimits& limits, std::vector<int> roots,
            std::string rootsPointer);

  // Throws Error naming the JSON pointer (a bad reference, a cycle, too deep) or overLimitMessage() (a
  // budget), before anything is read. meshCost(mesh) is called once per mesh that some reached node
  // uses, after that index was checked; it may throw Error too.
  void check(const std::function<MeshCost(int mesh)>& meshCost) const;

  // After check(): visit(node, world) for every node instance, in depth-first pre-order.
  void forEachInstance(const std::function<void(int node, const glm::dmat4& world)>& visit) const;

 private:
  [[noreturn]] void fail(const std::string& pointer, const std::string& why) const;

  const std::string& path_;
  const tinygltf::Model& m_;
  const ResourceLimits& limits_;
  std::vector<int> roots_;
  std::string rootsPointer_;
};

}  // namespace tessera::model::detail::gltf
