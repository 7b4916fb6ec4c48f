#include "model/gltf_graph.h"

#include <algorithm>
#include <optional>

#include "base/error.h"
#include "model/loaders.h"

namespace tessera::model::detail::gltf {

glm::dmat4 nodeTransform(const tinygltf::Node& n) {
  glm::dmat4 t(1.0);
  if (n.matrix.size() == 16) {
    for (int i = 0; i < 16; ++i) t[i / 4][i % 4] = n.matrix[size_t(i)];
    return t;
  }
  double q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1}, tr[3] = {0, 0, 0};
  if (n.rotation.size() == 4)
    for (int i = 0; i < 4; ++i) q[i] = n.rotation[i];
  if (n.scale.size() == 3)
    for (int i = 0; i < 3; ++i) s[i] = n.scale[i];
  if (n.translation.size() == 3)
    for (int i = 0; i < 3; ++i) tr[i] = n.translation[i];
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  const double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                       2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                       2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};  // column-major
  for (int c = 0; c < 3; ++c)
    for (int row = 0; row < 3; ++row) t[c][row] = r[c * 3 + row] * s[c];
  for (int i = 0; i < 3; ++i) t[3][i] = tr[i];
  return t;
}

NodeGraph::NodeGraph(const std::string& path, const tinygltf::Model& m, const ResourceLimits& limits,
                     std::vector<int> roots, std::string rootsPointer)
    : path_(path), m_(m), limits_(limits), roots_(std::move(roots)), rootsPointer_(std::move(rootsPointer)) {}

void NodeGraph::fail(const std::string& pointer, const std::string& why) const {
  throw Error(path_ + ": " + pointer + ": " + why);
}

void NodeGraph::check(const std::function<MeshCost(int mesh)>& meshCost) const {
  // What a node expands to: itself and everything below it, each node counted once per path to it.
  struct Totals {
    uint64_t instances = 0, triangles = 0, vertices = 0;
    uint32_t height = 0;  // levels, the node itself being 1
  };
  const auto add = [](Totals& t, const Totals& u) {
    t.instances = saturatingAdd(t.instances, u.instances);
    t.triangles = saturatingAdd(t.triangles, u.triangles);
    t.vertices = saturatingAdd(t.vertices, u.vertices);
  };
  const auto requireWithinBudgets = [&](const Totals& t) {
    requireWithinBudget(path_, ModelBudget::Instances, t.instances, limits_);
    requireWithinBudget(path_, ModelBudget::Triangles, t.triangles, limits_);
    requireWithinBudget(path_, ModelBudget::Vertices, t.vertices, limits_);
  };
  const auto tooDeep = [&](int node) {
    fail("/nodes/" + std::to_string(node),
         "the node hierarchy nests deeper than the limit of " + std::to_string(limits_.graphDepth) + " levels");
  };

  const size_t n = m_.nodes.size();
  enum : uint8_t { kUnseen, kOnPath, kSummed };
  std::vector<uint8_t> state(n, kUnseen);
  std::vector<Totals> totals(n);
  std::vector<std::optional<MeshCost>> meshes(m_.meshes.size());
  struct Frame {
    int node;
    size_t next;  // the next child to look at
  };
  std::vector<Frame> path;  // the nodes from a root down to the one being looked at
  Totals all;
  for (size_t r = 0; r < roots_.size(); ++r) {
    const int root = roots_[r];
    if (root < 0 || size_t(root) >= n)
      fail(rootsPointer_ + "/" + std::to_string(r), std::to_string(root) + " is not a node index");
    if (state[size_t(root)] == kUnseen) {
      if (limits_.graphDepth < 1) tooDeep(root);
      state[size_t(root)] = kOnPath;
      path.push_back({root, 0});
    }
    while (!path.empty()) {
      Frame& f = path.back();
      const tinygltf::Node& node = m_.nodes[size_t(f.node)];
      if (f.next < node.children.size()) {
        const size_t k = f.next++;
        const int c = node.children[k];
        if (c < 0 || size_t(c) >= n)
          fail("/nodes/" + std::to_string(f.node) + "/children/" + std::to_string(k),
               std::to_string(c) + " is not a node index");
        if (state[size_t(c)] == kOnPath) fail("/nodes/" + std::to_string(c), "the node hierarchy has a cycle");
        if (state[size_t(c)] == kSummed) {  // reached again along another path: its totals count again
          if (path.size() + totals[size_t(c)].height > limits_.graphDepth) tooDeep(c);
          continue;
        }
        if (path.size() + 1 > limits_.graphDepth) tooDeep(c);
        state[size_t(c)] = kOnPath;
        path.push_back({c, 0});  // invalidates f
        continue;
      }
      // Every child is summed: this node's totals (saturated, so any size of graph is summed exactly or
      // as "more than 2^64").
      Totals t;
      t.instances = 1, t.height = 1;
      if (node.mesh >= 0) {
        if (size_t(node.mesh) >= m_.meshes.size())
          fail("/nodes/" + std::to_string(f.node) + "/mesh", std::to_string(node.mesh) + " is not a mesh index");
        std::optional<MeshCost>& cost = meshes[size_t(node.mesh)];
        if (!cost) cost = meshCost(node.mesh);
        t.triangles = cost->triangles, t.vertices = cost->vertices;
      }
      for (int c : node.children) {
        add(t, totals[size_t(c)]);
        t.height = std::max(t.height, totals[size_t(c)].height + 1);
      }
      totals[size_t(f.node)] = t;
      state[size_t(f.node)] = kSummed;
      path.pop_back();
    }
    add(all, totals[size_t(root)]);
  }
  // Once, on the whole graph: the message then says what the file needs, not what a part of it needs.
  requireWithinBudgets(all);
}

void NodeGraph::forEachInstance(const std::function<void(int node, const glm::dmat4& world)>& visit) const {
  struct Frame {
    int node;
    size_t next;  // the next child to visit
    glm::dmat4 world;
  };
  std::vector<Frame> path;  // at most graphDepth frames (check())
  for (int root : roots_) {
    const glm::dmat4 world = compose(glm::dmat4(1.0), nodeTransform(m_.nodes[size_t(root)]));
    visit(root, world);
    path.push_back({root, 0, world});
    while (!path.empty()) {
      Frame& f = path.back();
      const std::vector<int>& children = m_.nodes[size_t(f.node)].children;
      if (f.next == children.size()) {
        path.pop_back();
        continue;
      }
      const int c = children[f.next++];
      const glm::dmat4 w = compose(f.world, nodeTransform(m_.nodes[size_t(c)]));
      visit(c, w);
      path.push_back({c, 0, w});  // invalidates f
    }
  }
}

}  // namespace tessera::model::detail::gltf
