#include "tools/scenes/builder.h"

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "raster/texture.h"

namespace tessera::scenes {

namespace {

// v / |v|: GLM's normalize multiplies by an inverse square root and gives other bits. sqrt is
// correctly rounded (IEEE 754), so this is as deterministic as + - * /.
glm::dvec3 normalized(const glm::dvec3& v) { return v / glm::length(v); }

}  // namespace

glm::mat4 mul(const glm::mat4& a, const glm::mat4& b) {
  // dmat4 * dmat4 sums each entry as ((p0 + p1) + p2) + p3; the scenes' sum started from +0.0, which
  // differs only in the sign of a zero result: adding +0.0 turns -0 into +0 and changes nothing else.
  const glm::dmat4 p = glm::dmat4(a) * glm::dmat4(b);
  glm::mat4 r;
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) r[c][row] = float(p[c][row] + 0.0);
  return r;
}

glm::mat4 perspective(double fovyDegrees, double aspect, double zNear, double zFar) {
  const double half = fovyDegrees * kPi / 360.0;
  const double f = detCos(half) / detSin(half);
  glm::mat4 r(0.0f);
  r[0][0] = float(f / aspect);
  r[1][1] = float(f);
  r[2][2] = float((zFar + zNear) / (zNear - zFar));
  r[2][3] = -1.0f;
  r[3][2] = float(2.0 * zFar * zNear / (zNear - zFar));
  return r;
}

glm::mat4 ortho(double l, double r, double b, double t, double n, double f) {
  glm::mat4 m(1.0f);
  m[0][0] = float(2.0 / (r - l));
  m[1][1] = float(2.0 / (t - b));
  m[2][2] = float(-2.0 / (f - n));
  m[3][0] = float(-(r + l) / (r - l));
  m[3][1] = float(-(t + b) / (t - b));
  m[3][2] = float(-(f + n) / (f - n));
  return m;
}

glm::mat4 lookAt(glm::vec3 eye, glm::vec3 center, glm::vec3 up) {
  // In double: glm::cross and glm::dot evaluate in the order this function always used.
  const glm::dvec3 e(eye);
  const glm::dvec3 f = normalized(glm::dvec3(center) - e);
  const glm::dvec3 s = normalized(glm::cross(f, glm::dvec3(up)));
  const glm::dvec3 v = glm::cross(s, f);
  glm::mat4 m(1.0f);
  for (int i = 0; i < 3; ++i) {
    m[i][0] = float(s[i]);
    m[i][1] = float(v[i]);
    m[i][2] = float(-f[i]);
  }
  m[3][0] = float(-glm::dot(s, e));
  m[3][1] = float(-glm::dot(v, e));
  m[3][2] = float(glm::dot(f, e));
  return m;
}

// The vertex buffers of recorded frames are these bytes: no padding, glm::vec3 / vec4 are plain floats.
static_assert(sizeof(Vertex) == 32 && offsetof(Vertex, attr) == 12 && offsetof(Vertex, id) == 28);

VertexLayout standardLayout() {
  VertexLayout l;
  l.stride = sizeof(Vertex);
  l.attribs[0] = {0, 3, AttribType::F32, offsetof(Vertex, pos)};
  l.attribs[1] = {1, 4, AttribType::F32, offsetof(Vertex, attr)};
  l.attribs[2] = {2, 1, AttribType::U32, offsetof(Vertex, id)};
  return l;
}

void Mesh::quad(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3, glm::vec4 a0, glm::vec4 a1, glm::vec4 a2,
                glm::vec4 a3, uint32_t id) {
  const uint32_t base = uint32_t(vertices.size());
  const glm::vec3 p[4] = {p0, p1, p2, p3};
  const glm::vec4 a[4] = {a0, a1, a2, a3};
  for (int i = 0; i < 4; ++i) vertices.push_back({p[i], a[i], id});
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(base + i);
}

void Mesh::triangle(Vertex a, Vertex b, Vertex c) {
  const uint32_t base = uint32_t(vertices.size());
  vertices.push_back(a);
  vertices.push_back(b);
  vertices.push_back(c);
  for (uint32_t i = 0; i < 3; ++i) indices.push_back(base + i);
}

uint32_t bindMesh(CommandList& cl, const Mesh& mesh) {
  std::span<const uint8_t> vb(reinterpret_cast<const uint8_t*>(mesh.vertices.data()),
                              mesh.vertices.size() * sizeof(Vertex));
  std::span<const uint8_t> ib(reinterpret_cast<const uint8_t*>(mesh.indices.data()),
                              mesh.indices.size() * sizeof(uint32_t));
  cl.bindVertexBuffer(cl.createBuffer(BufferKind::Vertex, vb));
  cl.bindIndexBuffer(cl.createBuffer(BufferKind::Index, ib), IndexType::U32);
  cl.setVertexLayout(standardLayout());
  return uint32_t(mesh.indices.size());
}

// glm::mat4 stores its four columns contiguously: the same 16 floats, in the same order, as m[c * 4 + r].
void setMatrix(CommandList& cl, uint32_t slot, const glm::mat4& m) {
  cl.setUniforms(slot, std::span<const float>(glm::value_ptr(m), 16));
}

void setVec4(CommandList& cl, uint32_t slot, glm::vec4 v) {
  cl.setUniforms(slot, std::span<const float>(glm::value_ptr(v), 4));
}

void setTexturedDefaults(CommandList& cl) {
  const float v[20] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 1, 1, 1, 0, 0, 0, 0};
  cl.setUniforms(4, v);
}

RgbaImage checker(uint32_t w, uint32_t h, uint32_t cell, std::array<uint8_t, 4> a, std::array<uint8_t, 4> b) {
  RgbaImage img{w, h, std::vector<uint8_t>(size_t(w) * h * 4)};
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) img.set(x, y, ((x / cell + y / cell) & 1) ? b : a);
  return img;
}

ResourceId uploadTexture(CommandList& cl, const RgbaImage& img, bool mipmaps) {
  TextureDesc d;
  d.kind = TextureKind::Tex2D;
  d.format = Format::RGBA8;
  d.width = img.width;
  d.height = img.height;
  d.levels = mipmaps ? fullMipCount(img.width, img.height) : 1;
  const ResourceId id = cl.createTexture(d);
  if (!mipmaps) {
    cl.uploadTexture(id, 0, 0, img.rgba);
    return id;
  }
  const auto chain = buildMipChainRGBA8(img.width, img.height, img.rgba);
  for (uint32_t l = 0; l < chain.size(); ++l) cl.uploadTexture(id, l, 0, chain[l]);
  return id;
}

ResourceId createTarget(CommandList& cl, Format f, int w, int h, uint32_t layers) {
  TextureDesc d;
  d.kind = layers > 1 ? TextureKind::Tex2DArray : TextureKind::Tex2D;
  d.format = f;
  d.width = uint32_t(w);
  d.height = uint32_t(h);
  d.layers = layers;
  d.levels = 1;
  return cl.createTexture(d);
}

uint64_t Rng::next() {
  uint64_t z = (state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

}  // namespace tessera::scenes
