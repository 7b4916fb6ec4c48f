// The parsed form of an AC3D file (.ac, AC3Db / AC3Dc; TORCS .acc): what model/load_ac3d.cpp turns into a Model.
//
// Implements: parse(), which reads the whole text line by line into materials and a list of objects in
// file order (parents before their kids, each naming its parent), checking as it goes: every count must
// fit in what the rest of the file can hold (each line it announces takes 2 bytes at least) before
// anything is reserved for it; kids nest through an explicit stack, never deeper than
// ResourceLimits::graphDepth; every number is finite; every refs index is below its object's numvert;
// a truncated file or an object without its kids line is an Error naming the file and the line.
// Unknown tokens are skipped and counted (the format is read token by token, as its specification
// says). Does not implement: material index checks and the model's totals (load_ac3d.cpp checks them
// once every MATERIAL is known), meshes, transforms or textures.
#pragma once

#include <cstdint>
#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "base/resource_limits.h"

namespace tessera::model::detail::ac3d {

struct Material {
  std::string name;
  glm::vec3 rgb{0.6f};  // Assimp's default for a file without MATERIAL lines
  float trans = 0.0f;
};

struct Ref {
  uint32_t vertex = 0;
  float u = 0.0f, v = 0.0f;
};

struct Surface {
  uint32_t flags = 0;
  uint64_t mat = 0;
  size_t line = 0, matLine = 0;
  size_t firstRef = 0, refCount = 0;
  uint32_t type() const { return flags & 0xfu; }  // 0 polygon, 1 closed line, 2 line, 4 strip (.acc)
  bool twoSided() const { return (flags & 0x20u) != 0; }
  bool isLine() const { return type() == 1 || type() == 2; }
};

struct Object {
  std::string name;
  size_t line = 0;
  int32_t parent = -1;  // index into the object list; -1 at the top
  uint32_t depth = 1;
  glm::mat3 rot{1.0f};  // rows as the file writes them (Assimp's reading): p' = rot * p + loc
  glm::vec3 loc{0.0f};
  std::string texture;
  size_t textureLine = 0;
  glm::vec2 texRep{1.0f}, texOff{0.0f};
  bool sawNumvert = false, mixedNormals = false;
  std::vector<glm::vec3> vertices, normals;  // normals: TORCS vertex lines of 6 numbers
  std::vector<Surface> surfaces;
  std::vector<Ref> refs;
  uint64_t triangles = 0;  // before degenerate strip triangles are skipped

  // "object 'name' (line N)", for messages.
  std::string label() const;
};

// What was dropped or assumed, counted while reading and building, written as Model::notes at the end.
struct Tally {
  std::map<std::string, std::pair<size_t, size_t>> unknown;  // token -> (lines, first line)
  size_t unknownKinds = 0;                                   // distinct tokens beyond the ones kept
  size_t lines = 0, smallPolygons = 0, unknownTypes = 0, pointLists = 0, lights = 0, subdiv = 0, layers = 0;
  size_t degenerateStrip = 0, notSimple = 0, shortData = 0, mixedNormals = 0, unknownObjectTypes = 0;
  bool defaultMaterial = false;
  int newerVersion = -1;
};

struct File {
  std::vector<Material> materials;
  std::vector<Object> objects;  // parents before their kids
  Tally tally;
};

// Parses `text`, the contents of `path` (named in messages). Throws Error("<path>:<line>: <reason>").
File parse(const std::string& path, std::string_view text, const ResourceLimits& limits);

// A token as it may appear in a message: at most 40 characters, control bytes as '?'.
std::string shown(std::string_view token);

}  // namespace tessera::model::detail::ac3d
