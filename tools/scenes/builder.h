// Helpers for writing scenes: matrices (from base/det_math.h, no libm), meshes, procedural
// textures and the small recording idioms every scene repeats.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "base/det_math.h"
#include "base/rgba_image.h"
#include "raster/command_list.h"

namespace tessera::scenes {

struct Vec3 { float x, y, z; };
// Column-major 4x4 (m[c * 4 + r]), as GL and the programs' uniform slots expect.
struct Mat4 {
  std::array<float, 16> m{};
  static Mat4 identity();
};
Mat4 operator*(const Mat4& a, const Mat4& b);
Mat4 perspective(double fovyDegrees, double aspect, double zNear, double zFar);
Mat4 ortho(double l, double r, double b, double t, double n, double f);
Mat4 lookAt(Vec3 eye, Vec3 center, Vec3 up);

// The vertex format every scene uses: location 0 = position (3 floats), 1 = texcoord / colour
// (4 floats), 2 = object id (U32).
struct Vertex {
  float pos[3];
  float attr[4];
  uint32_t id;
};
VertexLayout standardLayout();

struct Mesh {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  // Appends a quad p0..p3 (counter-clockwise) with per-corner attributes a0..a3.
  void quad(Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3, std::array<float, 4> a0, std::array<float, 4> a1,
            std::array<float, 4> a2, std::array<float, 4> a3, uint32_t id = 0);
  void triangle(Vertex a, Vertex b, Vertex c);
};

// Uploads the mesh as a vertex + index buffer (U32 indices), binds them and the standard layout.
// Returns the index count.
uint32_t bindMesh(CommandList& cl, const Mesh& mesh);

void setMatrix(CommandList& cl, uint32_t slot, const Mat4& m);
void setVec4(CommandList& cl, uint32_t slot, std::array<float, 4> v);
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
