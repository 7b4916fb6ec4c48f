#include "tools/scenes/builder.h"

#include <cmath>

#include "raster/texture.h"

namespace tessera::scenes {

Mat4 Mat4::identity() {
  Mat4 r;
  r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.0f;
  return r;
}

Mat4 operator*(const Mat4& a, const Mat4& b) {
  Mat4 r;
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) {
      double s = 0.0;
      for (int k = 0; k < 4; ++k) s = s + double(a.m[k * 4 + row]) * double(b.m[c * 4 + k]);
      r.m[c * 4 + row] = float(s);
    }
  return r;
}

Mat4 perspective(double fovyDegrees, double aspect, double zNear, double zFar) {
  const double half = fovyDegrees * kPi / 360.0;
  const double f = detCos(half) / detSin(half);
  Mat4 r;
  r.m[0] = float(f / aspect);
  r.m[5] = float(f);
  r.m[10] = float((zFar + zNear) / (zNear - zFar));
  r.m[11] = -1.0f;
  r.m[14] = float(2.0 * zFar * zNear / (zNear - zFar));
  return r;
}

Mat4 ortho(double l, double r, double b, double t, double n, double f) {
  Mat4 m = Mat4::identity();
  m.m[0] = float(2.0 / (r - l));
  m.m[5] = float(2.0 / (t - b));
  m.m[10] = float(-2.0 / (f - n));
  m.m[12] = float(-(r + l) / (r - l));
  m.m[13] = float(-(t + b) / (t - b));
  m.m[14] = float(-(f + n) / (f - n));
  return m;
}

Mat4 lookAt(Vec3 eye, Vec3 center, Vec3 up) {
  auto norm = [](double v[3]) {
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);  // sqrt is correctly rounded
    for (int i = 0; i < 3; ++i) v[i] /= l;
  };
  double f[3] = {double(center.x) - eye.x, double(center.y) - eye.y, double(center.z) - eye.z};
  norm(f);
  double u[3] = {up.x, up.y, up.z};
  double s[3] = {f[1] * u[2] - f[2] * u[1], f[2] * u[0] - f[0] * u[2], f[0] * u[1] - f[1] * u[0]};
  norm(s);
  const double v[3] = {s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2], s[0] * f[1] - s[1] * f[0]};
  Mat4 m = Mat4::identity();
  for (int i = 0; i < 3; ++i) {
    m.m[i * 4 + 0] = float(s[i]);
    m.m[i * 4 + 1] = float(v[i]);
    m.m[i * 4 + 2] = float(-f[i]);
  }
  m.m[12] = float(-(s[0] * eye.x + s[1] * eye.y + s[2] * eye.z));
  m.m[13] = float(-(v[0] * eye.x + v[1] * eye.y + v[2] * eye.z));
  m.m[14] = float(f[0] * eye.x + f[1] * eye.y + f[2] * eye.z);
  return m;
}

VertexLayout standardLayout() {
  VertexLayout l;
  l.stride = sizeof(Vertex);
  l.attribs[0] = {0, 3, AttribType::F32, offsetof(Vertex, pos)};
  l.attribs[1] = {1, 4, AttribType::F32, offsetof(Vertex, attr)};
  l.attribs[2] = {2, 1, AttribType::U32, offsetof(Vertex, id)};
  return l;
}

void Mesh::quad(Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3, std::array<float, 4> a0, std::array<float, 4> a1,
                std::array<float, 4> a2, std::array<float, 4> a3, uint32_t id) {
  const uint32_t base = uint32_t(vertices.size());
  const Vec3 p[4] = {p0, p1, p2, p3};
  const std::array<float, 4> a[4] = {a0, a1, a2, a3};
  for (int i = 0; i < 4; ++i)
    vertices.push_back({{p[i].x, p[i].y, p[i].z}, {a[i][0], a[i][1], a[i][2], a[i][3]}, id});
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

void setMatrix(CommandList& cl, uint32_t slot, const Mat4& m) { cl.setUniforms(slot, m.m); }

void setVec4(CommandList& cl, uint32_t slot, std::array<float, 4> v) { cl.setUniforms(slot, v); }

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
