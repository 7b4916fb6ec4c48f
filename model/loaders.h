// Internal to tessera_model: the per-format loaders behind loadModel() and what they share (paths,
// URIs, the double-precision node transform). Not a public interface.
#pragma once

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/resource_limits.h"
#include "model/model.h"

namespace tessera::model::detail {

// Each loader checks its model against `limits` before it reads the geometry that would exceed them
// (instances, graph depth, triangles, vertices); loadModel() checks the texture bytes for all of them.
Model loadGltf(const std::string& path, const ResourceLimits& limits);    // load_gltf.cpp; glTF 1.0 -> loadAssimp
Model loadObj(const std::string& path, const ResourceLimits& limits);     // load_obj.cpp
Model loadAssimp(const std::string& path, const ResourceLimits& limits);  // load_assimp.cpp
// The same, with Assimp reading `text` in place of the file `path` itself (files beside it, such as
// buffers and images, are still read from the disk): a glTF 1.0 document whose version was normalized.
Model loadAssimp(const std::string& path, const ResourceLimits& limits, const std::string& text);
// load_ac3d.cpp: AC3D .ac and TORCS .acc, parsed without Assimp. Throws Error("<file>:<line>: <reason>")
// for malformed input and overLimitMessage() when the model exceeds `limits`.
Model loadAc3d(const std::string& path, const ResourceLimits& limits);

// What a model needs of one of its budgets (docs/limits.md).
enum class ModelBudget { Instances, Triangles, Vertices, TextureBytes };
// Throws Error(overLimitMessage(where, ...)) naming the budget's option when `need` exceeds its limit in
// `limits`. A saturated need (UINT64_MAX, see saturatingAdd) reads as "more than 2^64".
void requireWithinBudget(const std::string& where, ModelBudget budget, uint64_t need, const ResourceLimits& limits);
// a + b and a * b saturated at UINT64_MAX: counts that a hostile file can make overflow are summed this
// way and compared against a limit, which is always far below UINT64_MAX.
inline uint64_t saturatingAdd(uint64_t a, uint64_t b) { return checkedAdd(a, b).value_or(UINT64_MAX); }
inline uint64_t saturatingMul(uint64_t a, uint64_t b) { return checkedMul(a, b).value_or(UINT64_MAX); }

// Percent-decoding of a relative URI reference ("a%20b.png" -> "a b.png"); a "file://" prefix is dropped.
std::string uriDecode(std::string_view uri);
// `relative` (already decoded) resolved against the directory of `modelPath`; absolute paths pass.
std::string resolveBeside(const std::string& modelPath, const std::string& relative);
// Throws Error("<model>: <what>: texture file '<resolved>' (written as '<uri>') does not exist")
// unless `resolved` is a regular file.
void requireTextureFile(const std::string& modelPath, const std::string& what, const std::string& uri,
                        const std::string& resolved);

// Appends meshes to a model with their scene-graph object (Model::objects). A loader calls begin() when
// it enters an object (a node instance, an AC3D object, an OBJ shape) and add() for each of its meshes;
// the object is appended with its first mesh, so objects without meshes never appear. `instance` counts
// the objects made earlier from the same node.
class ObjectSink {
 public:
  explicit ObjectSink(Model& out) : out_(out) {}
  void begin(std::string name, int32_t node) { name_ = std::move(name), node_ = node, added_ = false; }
  void add(Mesh&& mesh) {
    if (!added_) {
      uint32_t instance = 0;
      if (node_ >= 0) {
        if (size_t(node_) >= instances_.size()) instances_.resize(size_t(node_) + 1);
        instance = instances_[size_t(node_)]++;
      }
      out_.objects.push_back(SceneObject{.name = name_, .node = node_, .instance = instance});
      added_ = true;
    }
    mesh.object = uint32_t(out_.objects.size() - 1);
    out_.meshes.push_back(std::move(mesh));
  }

 private:
  Model& out_;
  std::string name_;
  int32_t node_ = -1;
  bool added_ = false;
  std::vector<uint32_t> instances_;
};

// Node transforms are glm::dmat4: column-major (m[c][r]) as glTF and Assimp store them, composed in
// double and applied to float positions and normals.

// parent * child as the loaders have always composed it: GLM's order ((p0 + p1) + p2) + p3 per entry,
// with a zero entry always +0 (the sum used to start from +0.0, which differs from GLM's product only in
// the sign of a zero result; adding +0.0 turns -0 into +0 and changes nothing else). A -0 would reach
// the stored positions' bits through transformPoint.
inline glm::dmat4 compose(const glm::dmat4& parent, const glm::dmat4& child) {
  glm::dmat4 r = parent * child;
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) r[c][row] = r[c][row] + 0.0;
  return r;
}

inline bool isIdentity(const glm::dmat4& m) { return m == glm::dmat4(1.0); }

// m * (p, 1) rounded to float once: ((m0·x + m1·y) + m2·z) + m3 per component. (GLM's m * vec4 adds
// (m0·x + m1·y) + (m2·z + m3·w), which gives other bits.)
inline glm::vec3 transformPoint(const glm::dmat4& m, const glm::vec3& p) {
  const glm::dvec3 q(p);
  return glm::vec3(glm::dvec3(m[0]) * q.x + glm::dvec3(m[1]) * q.y + glm::dvec3(m[2]) * q.z + glm::dvec3(m[3]));
}

// The determinant of the upper 3x3 (GLM's cofactor expansion along the first row).
inline double det3(const glm::dmat4& m) { return glm::determinant(glm::dmat3(m)); }

// Transforms a normal by the inverse transpose of the upper 3x3 (the cofactor matrix; the
// determinant's scale is removed by normalizing) and normalizes it (sqrt is correctly rounded).
// A normal that maps to zero length is returned unchanged.
inline glm::vec3 transformNormal(const glm::dmat4& m, const glm::vec3& n) {
  // Row-major names of the upper 3x3: a b c / d e f / g h i.
  const double a = m[0][0], b = m[1][0], c = m[2][0], d = m[0][1], e = m[1][1], f = m[2][1], g = m[0][2], h = m[1][2],
               i = m[2][2];
  const glm::dvec3 cof0(e * i - f * h, -(d * i - f * g), d * h - e * g);  // the cofactor matrix's rows
  const glm::dvec3 cof1(-(b * i - c * h), a * i - c * g, -(a * h - b * g));
  const glm::dvec3 cof2(b * f - c * e, -(a * f - c * d), a * e - b * d);
  const glm::dvec3 dn(n);
  const glm::dvec3 v(glm::dot(cof0, dn), glm::dot(cof1, dn), glm::dot(cof2, dn));
  const double sign = det3(m) < 0.0 ? -1.0 : 1.0, len = glm::length(v);
  if (!(len > 0.0)) return n;
  return glm::vec3(sign * v / len);
}

}  // namespace tessera::model::detail
