// The input of the atlas tree build: a flat list of textured triangles (thesis §4.2: a set G of
// triangles, a set T of textures and an assignment), with one or more texture layers (§5.1.3).
//
// Implements: the flat scene, its conversion from a model::Model (one layer: the base colour), and
// lazy image access (one image decoded at a time through the callback).
// Does not implement: image decoding (model/), the build (build.h).
//
// Conventions: positions are glm::vec3, texcoords glm::vec2 (x = u, y = v). Texcoords follow
// model/model.h (v = 0 is the first stored image row), are never clamped or wrapped. Layer 0 defines
// the atlas parameterization; layers 1.. share it (§5.1.3).
// A triangle with texture -1 in layer 0 is untextured: it is placed in the tree but gets no atlas area.
#pragma once

#include <cstdint>
#include <functional>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "model/model.h"

namespace tessera::mta {

// An input texture: an image plus its addressing (glTF sampler), because the same image sampled with
// REPEAT and with CLAMP fills the atlas differently.
struct SceneTexture {
  uint32_t image = 0;
  model::Wrap wrapS = model::Wrap::Repeat, wrapT = model::Wrap::Repeat;
};

struct SceneImage {
  uint32_t width = 0, height = 0;  // from the image header; the decoded image must agree
  std::string name;
};

struct SceneLayer {
  std::vector<int32_t> texture;  // per triangle: index into Scene::textures, -1 = none
  std::vector<glm::vec2> uv;     // 3 per triangle (x = u, y = v)
};

// Triangle soup. Everything per triangle is indexed the same way.
struct Geometry {
  std::vector<glm::vec3> positions;  // 3 per triangle, counter-clockwise
  std::vector<uint32_t> source;   // per triangle: the input triangle it came from (critical splits keep it)
  std::vector<uint8_t> alpha;     // per triangle: 1 = RGBA tree (material alpha mode is MASK or BLEND), 0 = RGB
  std::vector<SceneLayer> layers;  // at least one
  size_t triangleCount() const { return positions.size() / 3; }
};

struct Scene {
  Geometry geometry;
  std::vector<SceneTexture> textures;
  std::vector<SceneImage> images;
  // Decodes image i as RGBA8, rows top first. Must be callable from several threads at once.
  std::function<model::Image(uint32_t image)> loadImage;
  std::string name;  // for messages
  // Optional, for messages: names input triangle `source` (Geometry::source), e.g. "mesh 'roof' (3) triangle
  // 7"; without it messages say "input triangle N".
  std::function<std::string(uint32_t source)> describeTriangle;
  // Throws Error naming the triangle / texture that is inconsistent (sizes, indices, non-finite values).
  void validate() const;
};

// One layer (the base colour). Untextured materials give texture -1. Image sizes come from
// model::probeTexture (headers only); nothing is decoded until loadImage is called.
Scene sceneFromModel(std::shared_ptr<const model::Model> m);

}  // namespace tessera::mta
