// Internal to tessera_model: the city generator's scene description, between the geometry
// (city_gen.cpp), the procedural textures (city_textures.cpp) and the glTF writer (city_gltf.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "model/city_gen.h"
#include "model/model.h"

namespace tessera::model::city {

enum class TexKind : uint8_t { BerlinFacade, Facade, Roof, Detail, Pavement, Fence, Tree, Glass };

struct TexSpec {
  TexKind kind = TexKind::Facade;
  uint32_t width = 0, height = 0;
  uint64_t seed = 0;   // everything about the pixels follows from it
  uint32_t label = 0;  // the number drawn on Berlin facades
  bool rgba() const { return kind == TexKind::Fence || kind == TexKind::Tree || kind == TexKind::Glass; }
};

// Pixels of one texture: rows top first (file order), 3 or 4 channels. Pure function of the spec.
std::vector<uint8_t> renderTexture(const TexSpec& spec);

// An untextured material: a base colour factor only (no texture, no texcoords). The atlas tree
// places such triangles without atlas area (mta::sceneFromModel maps them to texture -1).
struct ColourMaterial {
  std::string name;
  std::array<double, 3> rgb{1, 1, 1};  // linear baseColorFactor, alpha 1
};

struct Primitive {
  // < Scene::textures.size(): that texture's material (one material per texture);
  // else Scene::colours[material - textures.size()].
  uint32_t material = 0;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> texcoords;  // one per position, or empty (untextured: no TEXCOORD_0 is written)
  std::vector<uint32_t> indices;
  // Appends the quad p0 p1 p2 p3 (counter-clockwise seen from the front) with its corner texcoords.
  void quad(const glm::vec3 (&p)[4], const glm::vec2 (&t)[4]);
  // The same without texcoords, for untextured primitives only.
  void quad(const glm::vec3 (&p)[4]);
  void triangle(const glm::vec3 (&p)[3], const glm::vec2 (&t)[3]);
};

struct Node {
  std::string name;
  std::array<double, 3> translation{0, 0, 0};
  double yaw = 0.0;                   // rotation about +Y in radians, written as a quaternion (detSin / detCos)
  std::vector<Primitive> primitives;  // the node's mesh (empty = no mesh)
  std::vector<uint32_t> children;
};

struct Scene {
  std::string name;  // "berlin" / "chemnitz": the file stem
  std::vector<TexSpec> textures;
  std::vector<ColourMaterial> colours;  // materials textures.size() .. textures.size() + colours.size() - 1
  std::vector<Node> nodes;
  std::vector<uint32_t> roots;
  uint32_t buildings = 0;
};

Scene buildBerlin(uint32_t buildings, uint64_t seed, uint32_t textureSize);
Scene buildChemnitz(uint32_t buildings, uint64_t seed, uint32_t textureSize);

// Writes the textures (in parallel) and the .gltf + .bin; fills the file and size fields of `s`.
void writeScene(const Scene& scene, const CityOptions& options, CitySummary& s);
// The same textures, and one glTF file per node with a mesh (every building, the ground) under DIR/parts/,
// in the node's own frame, plus the scene manifest DIR/<name>.json that places each with its world
// matrix (docs/model-import.md): loadModel() of it gives the one-file city's positions bit for bit.
void writeSplitScene(const Scene& scene, const CityOptions& options, CitySummary& s);

// splitmix64: the generator's only source of randomness.
inline uint64_t mix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

}  // namespace tessera::model::city
