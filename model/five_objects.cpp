// fiveObjectModel(): the built-in brake assembly (five_objects.h).
#include "model/five_objects.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>

#include "base/det_math.h"

namespace tessera::model {

namespace {

// Appends vertices and triangles to one mesh.
struct Builder {
  Mesh& m;
  uint32_t vertex(glm::vec3 p, glm::vec2 uv, glm::vec3 n) {
    m.positions.push_back(p), m.texcoords.push_back(uv), m.normals.push_back(n);
    return uint32_t(m.positions.size() - 1);
  }
  void tri(uint32_t a, uint32_t b, uint32_t c) { m.indices.insert(m.indices.end(), {a, b, c}); }
  // Corners p0..p3 counter-clockwise seen from the side `n` points to; two triangles (p0 p1 p2), (p0 p2 p3).
  void quad(const std::array<glm::vec3, 4>& p, const std::array<glm::vec2, 4>& uv, glm::vec3 n) {
    const uint32_t a = vertex(p[0], uv[0], n), b = vertex(p[1], uv[1], n), c = vertex(p[2], uv[2], n),
                   d = vertex(p[3], uv[3], n);
    tri(a, b, c), tri(a, c, d);
  }
  // An axis-aligned box [lo, hi]: 6 faces of 4 vertices, each face's texcoords the whole unit square.
  void box(glm::vec3 lo, glm::vec3 hi) {
    const glm::vec3 c = (lo + hi) * 0.5f, h = (hi - lo) * 0.5f;
    // Per face: the normal axis, its sign and the (u, v) axes with u x v = the outward normal.
    struct Face {
      int axis, sign, u, v;
    };
    constexpr Face kFaces[6] = {{0, 1, 1, 2}, {0, -1, 2, 1}, {1, 1, 2, 0}, {1, -1, 0, 2}, {2, 1, 0, 1}, {2, -1, 1, 0}};
    for (const Face& f : kFaces) {
      glm::vec3 n(0.0f);
      n[f.axis] = float(f.sign);
      std::array<glm::vec3, 4> p;
      constexpr float su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
      for (int k = 0; k < 4; ++k) {
        p[size_t(k)] = c;
        p[size_t(k)][f.axis] += float(f.sign) * h[f.axis];
        p[size_t(k)][f.u] += su[k] * h[f.u];
        p[size_t(k)][f.v] += sv[k] * h[f.v];
      }
      quad(p, {glm::vec2{0, 1}, {1, 1}, {1, 0}, {0, 0}}, n);
    }
  }
};

// A texcoord clamped to [0, 1]: detCos(π) is a little below -1, so 0.5 + 0.5 cos would leave the square.
float unit(double t) { return float(std::clamp(t, 0.0, 1.0)); }

// The brake disc: front and back ring faces (planar texcoords over the disc's square), outer and
// inner walls (u around, v across the thickness; the seam vertex is repeated at u = 1).
void disc(Mesh& m) {
  constexpr uint32_t S = kDiscSegments;
  constexpr double R = 1.0, r = 0.35, t = 0.06;
  Builder b{m};
  std::array<double, S + 1> c{}, s{};
  for (uint32_t i = 0; i <= S; ++i) {
    const double a = 2.0 * kPi * double(i % S) / S;
    c[i] = detCos(a), s[i] = detSin(a);
  }
  auto planar = [&](double x, double y) { return glm::vec2(unit(0.5 + 0.5 * x / R), unit(0.5 - 0.5 * y / R)); };
  for (const int side : {1, -1}) {  // front (+z), back (-z)
    const float z = float(side * t);
    const glm::vec3 n(0, 0, float(side));
    const uint32_t first = uint32_t(m.positions.size());
    for (uint32_t i = 0; i < S; ++i) {
      b.vertex({float(R * c[i]), float(R * s[i]), z}, planar(R * c[i], R * s[i]), n);
      b.vertex({float(r * c[i]), float(r * s[i]), z}, planar(r * c[i], r * s[i]), n);
    }
    for (uint32_t i = 0; i < S; ++i) {
      const uint32_t o0 = first + 2 * i, i0 = o0 + 1, o1 = first + 2 * ((i + 1) % S), i1 = o1 + 1;
      if (side > 0)
        b.tri(o0, o1, i1), b.tri(o0, i1, i0);
      else
        b.tri(o0, i1, o1), b.tri(o0, i0, i1);
    }
  }
  for (const double radius : {R, r}) {  // outer wall (normal outward), inner wall (normal towards the axis)
    const float sign = radius == R ? 1.0f : -1.0f;
    const uint32_t first = uint32_t(m.positions.size());
    for (uint32_t i = 0; i <= S; ++i) {
      const glm::vec3 n(sign * float(c[i]), sign * float(s[i]), 0.0f);
      const float u = float(double(i) / S);
      b.vertex({float(radius * c[i]), float(radius * s[i]), float(t)}, {u, 0.0f}, n);   // front
      b.vertex({float(radius * c[i]), float(radius * s[i]), float(-t)}, {u, 1.0f}, n);  // back
    }
    for (uint32_t i = 0; i < S; ++i) {
      const uint32_t f0 = first + 2 * i, b0 = f0 + 1, f1 = f0 + 2, b1 = f0 + 3;
      if (sign > 0)
        b.tri(b0, b1, f1), b.tri(b0, f1, f0);
      else
        b.tri(f0, f1, b1), b.tri(f0, b1, b0);
    }
  }
}

// A hexagonal screw along +z: front and back caps (fans around a centre vertex) and six flat sides.
void screw(Mesh& m, double cx, double cy, double z0, double z1, double rho) {
  Builder b{m};
  std::array<glm::vec3, 7> rim;  // rim[6] = rim[0]
  std::array<double, 7> ca{}, sa{};
  for (int k = 0; k <= 6; ++k) {
    const double a = kPi / 6.0 + kPi / 3.0 * double(k % 6);
    ca[size_t(k)] = detCos(a), sa[size_t(k)] = detSin(a);
    rim[size_t(k)] = {float(cx + rho * ca[size_t(k)]), float(cy + rho * sa[size_t(k)]), 0.0f};
  }
  for (const int side : {1, -1}) {
    const float z = float(side > 0 ? z1 : z0);
    const glm::vec3 n(0, 0, float(side));
    const uint32_t centre = b.vertex({float(cx), float(cy), z}, {0.5f, 0.5f}, n);
    for (int k = 0; k < 6; ++k)
      b.vertex({rim[size_t(k)].x, rim[size_t(k)].y, z},
               {unit(0.5 + 0.5 * ca[size_t(k)]), unit(0.5 - 0.5 * sa[size_t(k)])}, n);
    for (uint32_t k = 0; k < 6; ++k) {
      const uint32_t a = centre + 1 + k, c = centre + 1 + (k + 1) % 6;
      if (side > 0)
        b.tri(centre, a, c);
      else
        b.tri(centre, c, a);
    }
  }
  for (int k = 0; k < 6; ++k) {
    const double mid = kPi / 3.0 * double(k + 1);  // between corners k and k + 1
    const glm::vec3 n(float(detCos(mid)), float(detSin(mid)), 0.0f);
    const glm::vec3 &p = rim[size_t(k)], &q = rim[size_t(k) + 1];
    const float u0 = float(k) / 6.0f, u1 = float(k + 1) / 6.0f;
    b.quad({glm::vec3{p.x, p.y, float(z0)}, {q.x, q.y, float(z0)}, {q.x, q.y, float(z1)}, {p.x, p.y, float(z1)}},
           {glm::vec2{u0, 1}, {u1, 1}, {u1, 0}, {u0, 0}}, n);
  }
}

// ---- Textures: integer arithmetic on texel coordinates only.

using Texels = std::vector<uint8_t>;

uint32_t hash32(uint32_t x, uint32_t y, uint32_t salt) {
  uint32_t h = x * 0x9e3779b1u ^ (y + 0x7f4a7c15u) * 0x85ebca6bu ^ salt * 0xc2b2ae35u;
  h ^= h >> 15, h *= 0x2c1b3c6du, h ^= h >> 12, h *= 0x297a2d39u, h ^= h >> 15;
  return h;
}

void put(Texels& px, uint32_t w, uint32_t x, uint32_t y, int r, int g, int b) {
  auto c8 = [](int v) { return uint8_t(v < 0 ? 0 : v > 255 ? 255 : v); };
  uint8_t* p = &px[(size_t(y) * w + x) * 4];
  p[0] = c8(r), p[1] = c8(g), p[2] = c8(b), p[3] = 255;
}

// Disc: brushed grey with concentric turning grooves and six darker drilled holes on the braking ring.
Texels discTexture(uint32_t n) {
  Texels px(size_t(n) * n * 4);
  const int64_t h = n / 2;
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < n; ++x) {
      const int64_t dx = int64_t(x) * 2 + 1 - 2 * h, dy = int64_t(y) * 2 + 1 - 2 * h;  // doubled, centred
      const int64_t d2 = dx * dx + dy * dy;
      int v = 150 + int(hash32(x, y, 1) % 24) + ((d2 / 1536) % 3 == 0 ? -28 : 0);
      for (int k = 0; k < 6; ++k) {  // hole centres at radius 0.7 (in texture units: 0.35 n)
        static constexpr int kHoleX[6] = {70, 35, -35, -70, -35, 35}, kHoleY[6] = {0, 61, 61, 0, -61, -61};
        const int64_t hx = dx - kHoleX[k] * int64_t(n) / 100, hy = dy - kHoleY[k] * int64_t(n) / 100;
        if (hx * hx + hy * hy < int64_t(n) * n / 256) v = 40;
      }
      put(px, n, x, y, v, v, v + 6);
    }
  return px;
}

// Pad: dark friction material with speckles on a steel backing strip along the top.
Texels padTexture(uint32_t w, uint32_t hgt) {
  Texels px(size_t(w) * hgt * 4);
  for (uint32_t y = 0; y < hgt; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      if (y < hgt / 4) {
        put(px, w, x, y, 120, 125, 135);
        continue;
      }
      const uint32_t r = hash32(x / 2, y / 2, 2) % 16;
      const int v = r == 0 ? 140 : 55 + int(r);
      put(px, w, x, y, v + 12, v, v - 8);
    }
  return px;
}

// Caliper: red paint with a white band of three letter-like blocks and a darker bevel along the edges.
Texels caliperTexture(uint32_t w, uint32_t hgt) {
  Texels px(size_t(w) * hgt * 4);
  for (uint32_t y = 0; y < hgt; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const bool edge = x < w / 32 || x >= w - w / 32 || y < hgt / 16 || y >= hgt - hgt / 16;
      const bool band = y >= hgt * 3 / 8 && y < hgt * 5 / 8 && x >= w / 8 && x < w * 7 / 8;
      const bool block = band && (x * 8 / w) % 2 == 1 && y >= hgt * 13 / 32 && y < hgt * 19 / 32;
      const int g = int(hash32(x, y, 3) % 12);
      if (block)
        put(px, w, x, y, 245, 245, 240);
      else if (edge)
        put(px, w, x, y, 120 + g, 10, 12);
      else
        put(px, w, x, y, 200 + g, 24 + g, 28);
    }
  return px;
}

// Screws: metal of the given tint with a cross slot in the middle.
Texels screwTexture(uint32_t n, int r, int g, int b) {
  Texels px(size_t(n) * n * 4);
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < n; ++x) {
      const bool slot = (x >= n * 7 / 16 && x < n * 9 / 16 && y >= n / 4 && y < n * 3 / 4) ||
                        (y >= n * 7 / 16 && y < n * 9 / 16 && x >= n / 4 && x < n * 3 / 4);
      const int d = int(hash32(x, y, 4) % 16) - 8 + int(x + y) / int(n / 8);
      if (slot)
        put(px, n, x, y, r / 4, g / 4, b / 4);
      else
        put(px, n, x, y, r + d, g + d, b + d);
    }
  return px;
}

void addObject(Model& model, const std::string& name, Mesh&& mesh, Texels&& texels, uint32_t w, uint32_t h) {
  const uint32_t index = uint32_t(model.objects.size());
  TextureRef t;
  t.source = TextureRef::Source::Memory;
  t.name = name + ".rgba";
  t.bytes = std::make_shared<const std::vector<uint8_t>>(std::move(texels));
  t.size = t.bytes->size();
  t.rawRGBA = true;
  t.rawWidth = w, t.rawHeight = h;
  t.header = TextureInfo{w, h, 4, "raw"};
  model.textures.push_back(std::move(t));
  Material m;
  m.name = name;
  m.baseColorTexture = int32_t(index);
  m.wrapS = m.wrapT = Wrap::ClampToEdge;  // texcoords stay in [0, 1]: no neighbour bleeds in at the seams
  model.materials.push_back(m);
  mesh.name = name;
  mesh.material = index;
  mesh.object = index;
  for (const glm::vec3& p : mesh.positions) model.bounds.add(p);
  model.meshes.push_back(std::move(mesh));
  model.objects.push_back(SceneObject{.name = name, .node = int32_t(index), .instance = 0});
}

}  // namespace

Model fiveObjectModel() {
  Model model;
  model.source = "builtin:five_objects";
  model.loader = "builtin";
  {
    Mesh m;
    disc(m);
    addObject(model, "disc", std::move(m), discTexture(256), 256, 256);
  }
  {
    Mesh m;
    Builder{m}.box({-0.6f, 0.62f, 0.07f}, {0.6f, 0.98f, 0.13f});
    addObject(model, "pad", std::move(m), padTexture(128, 64), 128, 64);
  }
  {
    Mesh m;
    Builder b{m};
    b.box({-0.4f, 0.55f, 0.15f}, {0.4f, 1.16f, 0.30f});    // front plate, in front of the pad
    b.box({-0.4f, 0.55f, -0.30f}, {0.4f, 1.16f, -0.15f});  // back plate, behind the disc
    // The bridge over the disc's rim reaches into both plates and stays inside their outline, so no
    // visible face of it is coplanar with a plate's.
    b.box({-0.36f, 1.02f, -0.2f}, {0.36f, 1.14f, 0.2f});
    addObject(model, "caliper", std::move(m), caliperTexture(256, 128), 256, 128);
  }
  {
    Mesh m;
    screw(m, -0.22, 0.85, 0.29, 0.40, 0.07);
    addObject(model, "screw_a", std::move(m), screwTexture(64, 200, 200, 205), 64, 64);
  }
  {
    Mesh m;
    screw(m, 0.22, 0.85, 0.29, 0.40, 0.07);
    addObject(model, "screw_b", std::move(m), screwTexture(64, 210, 170, 60), 64, 64);
  }
  return model;
}

}  // namespace tessera::model
