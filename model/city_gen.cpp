// The two city layouts (geometry, texture specs, node hierarchy) and generateCity().
// Geometry is IEEE arithmetic on values from the seeded splitmix stream plus detSin / detCos, so it
// is bit-identical everywhere; glTF is Y-up, metres.
#include "model/city_gen.h"

#include <chrono>
#include <filesystem>

#include "model/city_scene.h"
#include "raster/command_list.h"
#include "base/det_math.h"

namespace tessera::model {

namespace city {

void Primitive::quad(const glm::vec3 (&p)[4], const glm::vec2 (&t)[4]) {
  const uint32_t b = uint32_t(positions.size());
  for (int k = 0; k < 4; ++k) positions.push_back(p[k]), texcoords.push_back(t[k]);
  indices.insert(indices.end(), {b, b + 1, b + 2, b, b + 2, b + 3});
}

void Primitive::quad(const glm::vec3 (&p)[4]) {
  const uint32_t b = uint32_t(positions.size());
  for (int k = 0; k < 4; ++k) positions.push_back(p[k]);
  indices.insert(indices.end(), {b, b + 1, b + 2, b, b + 2, b + 3});
}

void Primitive::triangle(const glm::vec3 (&p)[3], const glm::vec2 (&t)[3]) {
  const uint32_t b = uint32_t(positions.size());
  for (int k = 0; k < 3; ++k) positions.push_back(p[k]), texcoords.push_back(t[k]);
  indices.insert(indices.end(), {b, b + 1, b + 2});
}

namespace {


struct Rng {
  uint64_t state;
  uint64_t next() { return mix(state++); }
  uint32_t below(uint32_t n) { return uint32_t(next() % n); }
  int range(int lo, int hi) { return lo + int(below(uint32_t(hi - lo + 1))); }  // [lo, hi]
  double unit() { return double(next() >> 11) * (1.0 / 9007199254740992.0); }   // [0, 1), exact
};

float f(double v) { return float(v); }

// The primitive of `node` for `material`, created on first use (primitives stay in first-use order).
Primitive& prim(Node& node, uint32_t material) {
  for (Primitive& p : node.primitives)
    if (p.material == material) return p;
  node.primitives.push_back(Primitive{material, {}, {}, {}});
  return node.primitives.back();
}

// A vertical wall from (x0, z0) to (x1, z1), y in [y0, y1], split into `cols` x `rows` quads with
// texcoords u = u0 + s * du, v = v0 + (y1 - y) * dv (v = 0 at the top, glTF); front faces outward
// for counter-clockwise footprints seen from +Y.
void wall(Primitive& p, double x0, double z0, double x1, double z1, double y0, double y1, int cols, int rows, double u0,
          double du, double dv) {
  const uint32_t base = uint32_t(p.positions.size());
  for (int r = 0; r <= rows; ++r)
    for (int c = 0; c <= cols; ++c) {
      const double s = double(c) / cols, y = y0 + (y1 - y0) * r / rows;
      p.positions.push_back({f(x0 + (x1 - x0) * s), f(y), f(z0 + (z1 - z0) * s)});
      p.texcoords.push_back({f(u0 + du * c), f((y1 - y) * dv)});
    }
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const uint32_t a = base + uint32_t(r * (cols + 1) + c), b = a + 1, d = a + uint32_t(cols + 1), e = d + 1;
      p.indices.insert(p.indices.end(), {a, b, e, a, e, d});
    }
}

// An axis-aligned box without its bottom, texcoords 0..1 per face.
void box(Primitive& p, double cx, double y0, double cz, double hx, double hy, double hz) {
  const double x0 = cx - hx, x1 = cx + hx, z0 = cz - hz, z1 = cz + hz, y1 = y0 + 2 * hy;
  const glm::vec2 t[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  auto q = [&](double ax, double az, double bx, double bz) {
    const glm::vec3 v[4] = {{f(ax), f(y0), f(az)}, {f(bx), f(y0), f(bz)}, {f(bx), f(y1), f(bz)}, {f(ax), f(y1), f(az)}};
    p.quad(v, t);
  };
  q(x0, z1, x1, z1), q(x1, z1, x1, z0), q(x1, z0, x0, z0), q(x0, z0, x0, z1);
  const glm::vec3 top[4] = {{f(x0), f(y1), f(z1)}, {f(x1), f(y1), f(z1)}, {f(x1), f(y1), f(z0)}, {f(x0), f(y1), f(z0)}};
  p.quad(top, t);
}

// A horizontal quad at height y over [x0, x1] x [z0, z1] facing +Y, texcoords scaled by `repeat`.
void ground(Primitive& p, double x0, double z0, double x1, double z1, double y, double repeatU, double repeatV) {
  const glm::vec3 v[4] = {{f(x0), f(y), f(z1)}, {f(x1), f(y), f(z1)}, {f(x1), f(y), f(z0)}, {f(x0), f(y), f(z0)}};
  const glm::vec2 t[4] = {{0, f(repeatV)}, {f(repeatU), f(repeatV)}, {f(repeatU), 0}, {0, 0}};
  p.quad(v, t);
}

// The same without texcoords (an untextured primitive).
void flat(Primitive& p, double x0, double z0, double x1, double z1, double y) {
  const glm::vec3 v[4] = {{f(x0), f(y), f(z1)}, {f(x1), f(y), f(z1)}, {f(x1), f(y), f(z0)}, {f(x0), f(y), f(z0)}};
  p.quad(v);
}

uint32_t gridSide(uint32_t n) {
  uint32_t g = 1;
  while (uint64_t(g) * g < n) ++g;
  return g;
}

}  // namespace

Scene buildBerlin(uint32_t buildings, uint64_t seed, uint32_t textureSize) {
  Scene s;
  s.name = "berlin";
  s.buildings = buildings;
  Rng rng{mix(seed ^ 0xbe71u)};
  const uint32_t g = gridSide(buildings);
  // Lot pitch: the one free ratio of this layout, calibrated to the thesis' atlas tree. §4.7.1 gives
  // the facades (10,000 x 512², matched exactly), d_min = D/72 and the result (1,773 nodes of 512²,
  // i.e. ~46 k atlas texels per building over all levels), but not the extent of "a part of Berlin".
  // At d_min = D/72 the atlas texels a building needs scale as (facade extent / D)², and D grows as
  // pitch * sqrt(N): the tree size depends on facade size / pitch and hardly on N (the 512² facades
  // never limit it: a 12 m repeat needs ~52 atlas texels at N = 10,000). Tree nodes with the builder's
  // defaults (A = 512, 1024 px, 60°, τ = 1, border 8), N = 10,000 / N = 1,000:
  //   pitch  40 m: 47.1 k / 7.9 k (a dense inner-city grid; ~37 GB of atlases at N = 10,000)
  //          60 m:  9.9 k / 5.6 k     80 m: 5.3 k / 3.7 k     100 m: 2.2 k / 2.6 k
  //         105 m:  1.74 k / 1.34 k   110 m: 1.5 k / 1.34 k   120 m: 1.37 k / 1.33 k
  // (N = 1,000 below ~105 m: walls are critical at D/72; they are split, or below ~95 m d_min is raised
  // to ~59 m.) 105 m gives the
  // thesis' tree size, so its model had ~7x the area per building of a dense 40 m grid (sparser
  // buildings, or terrain beyond them widening D; the text does not say). We spread the lots, which
  // keeps every building's surroundings alike.
  const double pitch = 105.0, street = 10.0, lot = pitch - street;
  s.nodes.push_back(Node{.name = "berlin"});
  s.roots.push_back(0);
  // Ground and roofs are untextured (thesis §4.7.1: "roofs and terrain are neither considered" in the
  // atlas-tree workload; they carried an aerial image). A textured ground quad repeating a street
  // texture g x g times was critical and split into ~9,500 atlas-filling triangles (N = 1,000).
  // Colour materials follow the N facade materials: lot, asphalt, then kRoofColours roof colours. Per
  // grid cell one lot quad and two street strips (on the +x and +z sides), so every ground triangle
  // stays as local as a building: a city-sized triangle would give the tree node holding it (and every
  // ancestor) the bounds of the whole city.
  s.colours = {{"lot", {0.16, 0.19, 0.11}},
               {"asphalt", {0.06, 0.06, 0.07}},
               {"roof_tiles", {0.30, 0.07, 0.04}},
               {"roof_slate", {0.10, 0.10, 0.11}},
               {"roof_copper", {0.12, 0.25, 0.18}}};
  constexpr uint32_t kRoofColours = 3;
  const uint32_t roofMaterial = buildings + 2;
  Node groundNode{.name = "ground"};
  groundNode.primitives = {Primitive{.material = buildings}, Primitive{.material = buildings + 1}};
  Primitive &lots = groundNode.primitives[0], &streets = groundNode.primitives[1];
  for (uint32_t j = 0; j < g; ++j)
    for (uint32_t i = 0; i < g; ++i) {
      const double x = i * pitch, z = j * pitch;
      flat(lots, x, z, x + lot, z + lot, 0.0);
      flat(streets, x + lot, z, x + pitch, z + pitch, 0.0);
      flat(streets, x, z + lot, x + lot, z + pitch, 0.0);
    }
  for (uint32_t i = 0; i < buildings; ++i) {
    // Walls are multiples of the 3 m window module, so each facade holds whole window columns.
    const int wx = rng.range(4, 9), wz = rng.range(4, 9), floors = rng.range(2, 12);
    const double hx = wx * 1.5, hz = wz * 1.5, h = floors * 3.0;
    const double jx = (rng.range(0, 8) - 4) * 0.5, jz = (rng.range(0, 8) - 4) * 0.5;
    Node b{.name = "building_" + std::to_string(i)};
    b.translation = {(i % g) * pitch + lot / 2 + jx, 0.0, (i / g) * pitch + lot / 2 + jz};  // mid-lot
    Primitive& p = prim(b, i);
    // Counter-clockwise from +Y: (-x,+z) -> (+x,+z) -> (+x,-z) -> (-x,-z). u continues around the
    // building: one repeat per 12 m; v: one repeat per 4 floors (12 m).
    const double cx[5] = {-hx, hx, hx, -hx, -hx}, cz[5] = {hz, hz, -hz, -hz, hz};
    double u = 0.0;
    for (int k = 0; k < 4; ++k) {
      const double len = k % 2 ? 2 * hz : 2 * hx;
      wall(p, cx[k], cz[k], cx[k + 1], cz[k + 1], 0.0, h, 1, 1, u, len / 12.0, 1.0 / 12.0);
      u += len / 12.0;
    }
    const glm::vec3 roof[4] = {
        {f(-hx), f(h), f(hz)}, {f(hx), f(h), f(hz)}, {f(hx), f(h), f(-hz)}, {f(-hx), f(h), f(-hz)}};
    // Untextured, like the ground (the thesis' roofs carried an aerial image outside the atlas tree).
    // A roof mapping a small region of the facade texture needs far more texels per repeat than the
    // walls (512, the cap, against ~135), and a node stores each texture at one resolution: the whole
    // facade would be stored at the roof's magnification (40 m lots, N = 1000: 15.0 k nodes instead
    // of 7.9 k).
    prim(b, roofMaterial + uint32_t(mix(seed ^ (uint64_t(i) << 20) ^ 0x7f0fu) % kRoofColours)).quad(roof);
    s.nodes[0].children.push_back(uint32_t(s.nodes.size()));
    s.nodes.push_back(std::move(b));
    s.textures.push_back(TexSpec{TexKind::BerlinFacade, textureSize, textureSize, mix(seed * 0x9e37u + i), i + 1});
  }
  s.nodes[0].children.push_back(uint32_t(s.nodes.size()));
  s.nodes.push_back(std::move(groundNode));
  return s;
}

namespace {

// Chemnitz texture pool shares per kind, of 5 textures per building (2,000 at 400 buildings).
struct Pool {
  TexKind kind;
  uint32_t per1000;  // textures per 1000 of the pool
  uint32_t first = 0, count = 0, cursor = 0;
  // Cycles through the kind's textures so every one is used once the kind has enough uses.
  uint32_t take() { return first + (cursor++ % count); }
};

uint32_t scaled(uint32_t size, uint32_t textureSize) {
  return std::max<uint32_t>(4, uint32_t(uint64_t(size) * textureSize / 512));
}

}  // namespace

// Lot pitch of chemnitz, calibrated like berlin's (see there): the thesis gives d_min = D/62 and the
// result (two trees, 223 MB of S3 data with the originals, i.e. ~1,600 atlases of 512²) but not the
// model's extent. Leaves of both trees at D/62 with the builder's defaults, 400 buildings: pitch 36 m
// 19,908; 60 m 7,788; 90 m 3,313; 120 m 1,682.
constexpr double kChemnitzPitch = 120.0;

Scene buildChemnitz(uint32_t buildings, uint64_t seed, uint32_t textureSize) {
  Scene s;
  s.name = "chemnitz";
  s.buildings = buildings;
  Rng rng{mix(seed ^ 0xc4e3u)};
  Pool pools[] = {{TexKind::Facade, 540}, {TexKind::Roof, 150}, {TexKind::Detail, 160}, {TexKind::Pavement, 50},
                  {TexKind::Fence, 40},   {TexKind::Tree, 40},  {TexKind::Glass, 20}};
  // 5 textures per building: every kind but facades gets its share (at least one), facades the rest.
  const uint32_t total = 5 * buildings;
  uint32_t others = 0;
  for (Pool& p : pools)
    if (p.kind != TexKind::Facade)
      p.count = std::max<uint32_t>(1, uint32_t(uint64_t(total) * p.per1000 / 1000)), others += p.count;
  pools[0].count = total > others + 3 ? total - others : 3;
  for (Pool& p : pools) {
    p.first = uint32_t(s.textures.size());
    for (uint32_t k = 0; k < p.count; ++k) {
      TexSpec t{p.kind, 0, 0, mix(seed * 0x2545f491u + s.textures.size()), 0};
      // Mixed sizes, mostly small (the thesis: ~36 M texels in ~2,000 textures): 64..512 per axis,
      // and every 37th texture not a power of two, to exercise odd mip extents.
      static constexpr uint32_t kSizes[] = {64,  64,  64,  64,  64,  64,  64,  64,  64,  128,
                                            128, 128, 128, 128, 128, 128, 256, 256, 256, 512};
      uint32_t w = kSizes[rng.below(std::size(kSizes))], h = kSizes[rng.below(std::size(kSizes))];
      if (s.textures.size() % 37 == 5) {
        static constexpr uint32_t kOdd[] = {96, 100, 160, 200, 300, 384};
        w = kOdd[rng.below(std::size(kOdd))], h = kOdd[rng.below(std::size(kOdd))];
      }
      if (p.kind == TexKind::Fence || p.kind == TexKind::Tree) h = std::max(h, w / 2);  // not too flat to read
      t.width = scaled(w, textureSize), t.height = scaled(h, textureSize);
      s.textures.push_back(t);
    }
  }
  Pool &facades = pools[0], &roofs = pools[1], &details = pools[2], &paves = pools[3], &fences = pools[4],
       &trees = pools[5], &glasses = pools[6];

  const uint32_t g = gridSide(buildings), blockLots = 4;
  const double pitch = kChemnitzPitch;
  s.nodes.push_back(Node{.name = "chemnitz"});
  s.roots.push_back(0);
  // The terrain is untextured, one quad per lot (as for berlin): a textured city-wide ground is the
  // atlas tree's whole workload at D/62 (2,000 repeats of a pavement tile over the city needed ~2 G
  // atlas texels and a 40,000-leaf tree) and a city-sized triangle would give its node the city's
  // bounds. The high repetition counts of §4.7.2 on single triangles are the plazas' pavement below.
  s.colours = {{"ground", {0.20, 0.19, 0.17}}};
  Node groundNode{.name = "ground"};
  groundNode.primitives = {Primitive{.material = uint32_t(s.textures.size())}};
  for (uint32_t j = 0; j < g; ++j)
    for (uint32_t i = 0; i < g; ++i) {
      const double x = i * pitch - pitch / 2, z = j * pitch - pitch / 2;
      flat(groundNode.primitives[0], x, z, x + pitch, z + pitch, 0.0);
    }
  // Blocks of 4 x 4 lots are nodes with their own translation; buildings are rotated children.
  std::vector<uint32_t> blockNode;
  const uint32_t blocks = (g + blockLots - 1) / blockLots;
  for (uint32_t b = 0; b < blocks * blocks; ++b) {
    blockNode.push_back(uint32_t(s.nodes.size()));
    Node n{.name = "block_" + std::to_string(b)};
    n.translation = {(b % blocks) * blockLots * pitch, 0.0, (b / blocks) * blockLots * pitch};
    s.nodes[0].children.push_back(uint32_t(s.nodes.size()));
    s.nodes.push_back(std::move(n));
  }
  for (uint32_t i = 0; i < buildings; ++i) {
    const uint32_t gx = i % g, gz = i / g, block = (gz / blockLots) * blocks + gx / blockLots;
    Node b{.name = "building_" + std::to_string(i)};
    b.translation = {(gx % blockLots) * pitch + (rng.unit() - 0.5) * 3.0, 0.0,
                     (gz % blockLots) * pitch + (rng.unit() - 0.5) * 3.0};
    b.yaw = rng.unit() * 2.0 * kPi;
    // A star-shaped footprint: k corners at jittered angles, radii 6..14 m.
    const int k = rng.range(5, 14), floors = rng.range(2, 8);
    const double floorH = 3.0 + rng.unit() * 0.6, h = floors * floorH;
    std::vector<double> px(size_t(k) + 1), pz(size_t(k) + 1);
    for (int j = 0; j < k; ++j) {
      const double a = 2.0 * kPi * (j + 0.15 + 0.7 * rng.unit()) / k, r = 6.0 + rng.unit() * 8.0;
      px[size_t(j)] = r * detCos(a), pz[size_t(j)] = -r * detSin(a);  // counter-clockwise seen from +Y
    }
    px[size_t(k)] = px[0], pz[size_t(k)] = pz[0];
    const uint32_t wallTex[3] = {facades.take(), facades.take(), facades.take()};
    for (int j = 0; j < k; ++j) {
      const double dx = px[size_t(j) + 1] - px[size_t(j)], dz = pz[size_t(j) + 1] - pz[size_t(j)];
      const double len = std::sqrt(dx * dx + dz * dz);  // correctly rounded
      const int cols = std::max(1, int(len / 1.1));     // ~1.1 m segments: ~300 k triangles at 400 buildings
      // u: one repeat per 4 m of wall, v: one repeat per floor.
      wall(prim(b, wallTex[j % 3]), px[size_t(j)], pz[size_t(j)], px[size_t(j) + 1], pz[size_t(j) + 1], 0.0, h, cols,
           floors, 0.0, len / 4.0 / cols, 1.0 / floorH);
    }
    // Pyramid roof, planar texcoords at 2 m per repeat.
    Primitive& rp = prim(b, roofs.take());
    const double apex = h + 2.0 + rng.unit() * 3.0;
    for (int j = 0; j < k; ++j) {
      const glm::vec3 v[3] = {{f(px[size_t(j)]), f(h), f(pz[size_t(j)])},
                              {f(px[size_t(j) + 1]), f(h), f(pz[size_t(j) + 1])},
                              {0, f(apex), 0}};
      const glm::vec2 t[3] = {
          {f(px[size_t(j)] / 2), f(pz[size_t(j)] / 2)}, {f(px[size_t(j) + 1] / 2), f(pz[size_t(j) + 1] / 2)}, {0, 0}};
      rp.triangle(v, t);
    }
    // Small detail: balconies along the walls, chimneys on the roof.
    const int boxes = rng.range(4, 12);
    for (int j = 0; j < boxes; ++j) {
      const int e = rng.range(0, k - 1);
      const double t = 0.2 + 0.6 * rng.unit(), y = floorH * rng.range(1, std::max(1, floors - 1));
      const double bx = px[size_t(e)] + (px[size_t(e) + 1] - px[size_t(e)]) * t,
                   bz = pz[size_t(e)] + (pz[size_t(e) + 1] - pz[size_t(e)]) * t;
      box(prim(b, details.take()), bx * 1.05, y, bz * 1.05, 0.6 + rng.unit(), 0.15 + 0.2 * rng.unit(),
          0.6 + rng.unit());
    }
    box(prim(b, details.take()), 1.0, h, 1.0, 0.4, 0.5 + rng.unit(), 0.4);
    // Fence around half of the lots (RGBA, alpha MASK): one quad per side, 1 repeat per 2 m.
    if (rng.below(2) == 0) {
      Primitive& fp = prim(b, fences.take());
      const double r = 16.0;
      const double fx[5] = {-r, r, r, -r, -r}, fz[5] = {r, r, -r, -r, r};
      for (int j = 0; j < 4; ++j)
        wall(fp, fx[j], fz[j], fx[j + 1], fz[j + 1], 0.0, 1.5, 4, 1, 0.0, 2 * r / 2.0 / 4, 1.0 / 1.5);
    }
    // Trees: two crossed quads each (RGBA, MASK).
    const int treeCount = rng.range(1, 5);
    for (int j = 0; j < treeCount; ++j) {
      Primitive& tp = prim(b, trees.take());
      const double a = rng.unit() * 2.0 * kPi, d = 15.0 + rng.unit() * 2.0, tx = d * detCos(a), tz = d * detSin(a);
      const double r = 2.0 + rng.unit() * 2.0, th = 4.0 + rng.unit() * 5.0;
      const glm::vec2 t[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
      const glm::vec3 q1[4] = {
          {f(tx - r), 0, f(tz)}, {f(tx + r), 0, f(tz)}, {f(tx + r), f(th), f(tz)}, {f(tx - r), f(th), f(tz)}};
      const glm::vec3 q2[4] = {
          {f(tx), 0, f(tz - r)}, {f(tx), 0, f(tz + r)}, {f(tx), f(th), f(tz + r)}, {f(tx), f(th), f(tz - r)}};
      tp.quad(q1, t), tp.quad(q2, t);
    }
    // A glass canopy on one building in five (RGBA, BLEND).
    if (rng.below(5) == 0) {
      const glm::vec3 v[4] = {{-3, f(floorH), 3}, {3, f(floorH), 3}, {3, f(floorH), -3}, {-3, f(floorH), -3}};
      const glm::vec2 t[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
      prim(b, glasses.take()).quad(v, t);
    }
    // A raised plaza on one lot in three: pavement at 0.3 m per tile repeat.
    if (rng.below(3) == 0) ground(prim(b, paves.take()), -17.0, -17.0, 17.0, 17.0, 0.05, 34.0 / 0.3, 34.0 / 0.3);
    s.nodes[blockNode[block]].children.push_back(uint32_t(s.nodes.size()));
    s.nodes.push_back(std::move(b));
  }
  s.nodes[0].children.push_back(uint32_t(s.nodes.size()));
  s.nodes.push_back(std::move(groundNode));
  return s;
}

}  // namespace city

CityPreset parseCityPreset(const std::string& name) {
  if (name == "berlin") return CityPreset::Berlin;
  if (name == "chemnitz") return CityPreset::Chemnitz;
  throw Error("--preset '" + name + "': expected berlin or chemnitz");
}

const char* cityPresetName(CityPreset p) { return p == CityPreset::Berlin ? "berlin" : "chemnitz"; }

uint32_t defaultCityBuildings(CityPreset p) { return p == CityPreset::Berlin ? 10000 : 400; }

nlohmann::json CitySummary::toJson() const {
  return {{"gltf", gltf},
          {"files", files.size()},
          {"buildings", buildings},
          {"textures", textures},
          {"rgba_textures", rgbaTextures},
          {"texels", texelCount},
          {"triangles", triangles},
          {"vertices", vertices},
          {"primitives", primitives},
          {"texture_bytes_raw", textureBytesRaw},
          {"bytes_on_disk", bytesOnDisk},
          {"time_s", seconds}};
}

CitySummary generateCity(const CityOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  if (o.outDir.empty()) throw Error("city: no output directory (-o DIR)");
  if (o.textureSize < 8 || o.textureSize > 8192)
    throw Error("--texture-size " + std::to_string(o.textureSize) + ": expected 8..8192");
  const uint32_t n = o.buildings ? o.buildings : defaultCityBuildings(o.preset);
  if (n > 1000000) throw Error("--buildings " + std::to_string(n) + ": at most 1,000,000");
  const city::Scene scene = o.preset == CityPreset::Berlin ? city::buildBerlin(n, o.seed, o.textureSize)
                                                           : city::buildChemnitz(n, o.seed, o.textureSize);
  CitySummary s;
  s.buildings = n;
  if (o.splitPerBuilding)
    city::writeSplitScene(scene, o, s);
  else
    city::writeScene(scene, o, s);
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return s;
}

}  // namespace tessera::model
