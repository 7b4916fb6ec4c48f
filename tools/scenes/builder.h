// Helpers for writing scenes: matrices (GLM types, built from base/det_math.h, never from GLM's libm
// trigonometry), meshes, procedural textures and the small recording idioms every scene repeats.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <vector>

#include "base/det_math.h"
#include "base/rgba_image.h"
#include "raster/command_list.h"

namespace tessera::scenes {

// Matrices are glm::mat4: column-major (m[c][r]), as GL and the programs' uniform slots expect.
// The entries are computed in double and rounded to float once.
glm::mat4 perspective(double fovyDegrees, double aspect, double zNear, double zFar);
glm::mat4 ortho(double l, double r, double b, double t, double n, double f);
glm::mat4 lookAt(glm::vec3 eye, glm::vec3 center, glm::vec3 up);
// a * b as every scene's recorded uniforms have it: each entry summed in double from the float entries
// (the products are exact) in the order ((p0 + p1) + p2) + p3 and rounded to float once; a zero entry
// is +0. GLM's float a * b rounds every step to float and gives other bits, so scenes never use it.
glm::mat4 mul(const glm::mat4& a, const glm::mat4& b);

// The vertex format every scene uses: location 0 = position (3 floats), 1 = texcoord / colour
// (4 floats), 2 = object id (U32). 32 bytes, offsets 0 / 12 / 28 (standardLayout).
struct Vertex {
  glm::vec3 pos;
  glm::vec4 attr;
  uint32_t id;
};
VertexLayout standardLayout();

struct Mesh {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  // Appends a quad p0..p3 (counter-clockwise) with per-corner attributes a0..a3.
  void quad(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3, glm::vec4 a0, glm::vec4 a1, glm::vec4 a2,
            glm::vec4 a3, uint32_t id = 0);
  void triangle(Vertex a, Vertex b, Vertex c);
};

// Uploads the mesh as a vertex + index buffer (U32 indices), binds them and the standard layout.
// Returns the index count.
uint32_t bindMesh(CommandList& cl, const Mesh& mesh);

// Writes the 16 floats of m, column by column, into slots [slot, slot + 4).
void setMatrix(CommandList& cl, uint32_t slot, const glm::mat4& m);
void setVec4(CommandList& cl, uint32_t slot, glm::vec4 v);
// Identity 3x3 texture matrix in slots 4-6, white tint in slot 7, zero bias in slot 8 ("textured").
void setTexturedDefaults(CommandList& cl);

// Scene textures are RgbaImages (base/rgba_image.h): y counts rows from row 0, which is t = 0.
RgbaImage checker(uint32_t w, uint32_t h, uint32_t cell, std::array<uint8_t, 4> a, std::array<uint8_t, 4> b);

// Creates a 2D RGBA8 texture with a full mip chain from the documented box filter (or one level).
// The rows are uploaded as they are: image row 0 is GL's first row (t = 0).
ResourceId uploadTexture(CommandList& cl, const RgbaImage& img, bool mipmaps);
// Creates a colour render target texture (one level).
ResourceId createTarget(CommandList& cl, Format f, int w, int h, uint32_t layers = 1);

// A small deterministic PRNG (splitmix64) for procedural content.
struct Rng {
  uint64_t state;
  uint64_t next();
  uint32_t below(uint32_t n) { return uint32_t(next() % n); }
  float unit() { return float(next() >> 40) / float(1 << 24); }  // [0, 1), exact in float
};

}  // namespace tessera::scenes
