// Internal to tessera_model: scenes made of several model files, which loadModel() reads when it is given
// a scene manifest (a .json file) or a directory (docs/model-import.md, "Scenes of several files").
//
// Implements:
// - readSceneManifest(): the manifest's JSON, checked completely before any model is read: schema 1, a
//   non-empty `models` array of entries with `file` and an optional `name`, and either `transform` (16
//   numbers, column-major like glTF's node.matrix, affine) or `translation` / `rotation` (degrees about
//   x, then y, then z) / `scale`. Unknown keys are errors. Relative files resolve against the
//   manifest's directory; an entry naming a directory or another manifest is refused, so a scene never
//   nests and cannot form a cycle;
// - readSceneDirectory(): every model file directly in a directory (by extension), sorted by name
//   (byte order), with identity transforms;
// - trsMatrix(): T * R * S with R built from degrees by detSin / detCos after an exact reduction to a
//   quarter turn, so multiples of 90 degrees give exact 0 and +-1;
// - mergeScene(): the entries' models loaded one after the other and appended into one Model.
// Errors name the manifest (or directory), the JSON pointer of the entry or field and the reason:
// "scene.json: /models/3/transform: expected 16 numbers, got 12"; a failure inside an entry's model is
// "scene.json: /models/3: <the model's own error>".
// Does not implement: reading the models themselves (loadModelFile(), model.cpp), texture headers and
// budgets of the merged model (loadModel() checks them once, after merging), nested scenes.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "base/resource_limits.h"
#include "model/model.h"

namespace tessera::model::detail {

struct SceneEntry {
  std::string file;   // resolved path of a model file
  std::string name;   // the entry's `name`, or empty
  std::string where;  // for messages: "/models/3" (manifest) or the file name (directory)
  glm::dmat4 transform{1.0};
};

struct Scene {
  std::string path;  // the manifest or the directory
  std::string kind;  // "manifest" or "directory": Model::loader becomes "scene:<kind>"
  std::vector<SceneEntry> entries;
};

// True when loadModel() reads `path` as a scene: a directory, or a file whose extension is .json.
bool isScenePath(const std::string& path);

Scene readSceneManifest(const std::string& path);
Scene readSceneDirectory(const std::string& path);

// T * R * S: translation, rotation in degrees (R = Rz * Ry * Rx: x is applied first), scale.
glm::dmat4 trsMatrix(const glm::dvec3& translation, const glm::dvec3& rotationDegrees, const glm::dvec3& scale);

// sin and cos of `degrees`: reduced exactly to [0, 90) plus a quarter-turn count, then detSin / detCos.
void sinCosDegrees(double degrees, double& s, double& c);

// The model files read by loadModelFile() and appended in entry order (docs/model-import.md says how
// textures, materials and objects are shared and named). The triangle and vertex budgets are checked
// on the running totals after each model.
Model mergeScene(const Scene& scene, const ResourceLimits& limits);

// loadModel() without its texture header pass and bounds: one model file, by content and extension.
Model loadModelFile(const std::string& path, const ResourceLimits& limits);

}  // namespace tessera::model::detail
