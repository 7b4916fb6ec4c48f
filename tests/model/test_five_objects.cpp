// The built-in five-object model (model/five_objects.h): its objects, counts worked out from the
// construction, deterministic textures, and what the default camera sees.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "model/five_objects.h"
#include "model/object_groups.h"

namespace tessera::model {
namespace {

const Model& five() {
  static const Model m = fiveObjectModel();
  return m;
}

TEST(FiveObjectModel, IsFiveObjectsByMeshAndByNodeEachWithItsOwnMaterialAndTexture) {
  const Model& m = five();
  const std::vector<std::string> names = {"disc", "pad", "caliper", "screw_a", "screw_b"};
  ASSERT_EQ(m.meshes.size(), 5u);
  ASSERT_EQ(m.objects.size(), 5u);
  ASSERT_EQ(m.materials.size(), 5u);
  ASSERT_EQ(m.textures.size(), 5u);
  for (const ObjectGrouping g : {ObjectGrouping::Mesh, ObjectGrouping::Node}) {
    const std::vector<ObjectGroup> groups = groupObjects(m, g);
    ASSERT_EQ(groups.size(), 5u);
    for (uint32_t i = 0; i < 5; ++i) {
      EXPECT_EQ(groups[i].name, names[i]);
      EXPECT_EQ(groups[i].meshes, std::vector<uint32_t>{i});
    }
  }
  for (uint32_t i = 0; i < 5; ++i) {
    EXPECT_EQ(m.meshes[i].object, i);
    EXPECT_EQ(m.objects[i].node, int32_t(i));
    EXPECT_EQ(m.meshes[i].material, i);
    EXPECT_EQ(m.materials[i].baseColorTexture, int32_t(i));
    EXPECT_EQ(m.materials[i].alphaMode, AlphaMode::Opaque);
  }
}

TEST(FiveObjectModel, VertexAndTriangleCountsFollowFromTheConstruction) {
  const Model& m = five();
  const size_t S = kDiscSegments;
  // Disc: two ring faces of S outer + S inner vertices and 2 triangles per segment; two walls of
  // S + 1 vertex pairs (the seam repeated) and 2 triangles per segment.
  EXPECT_EQ(m.meshes[0].positions.size(), 2 * (2 * S) + 2 * (2 * (S + 1)));
  EXPECT_EQ(m.meshes[0].triangleCount(), 4 * (2 * S));
  EXPECT_EQ(m.meshes[1].positions.size(), 6u * 4);  // a box: 6 faces of 4 vertices, 2 triangles each
  EXPECT_EQ(m.meshes[1].triangleCount(), 6u * 2);
  EXPECT_EQ(m.meshes[2].positions.size(), 3u * 24);  // three boxes
  EXPECT_EQ(m.meshes[2].triangleCount(), 3u * 12);
  for (size_t i : {3, 4}) {  // two hexagonal caps (centre + 6, 6 triangles), six side quads
    EXPECT_EQ(m.meshes[i].positions.size(), 2u * 7 + 6u * 4);
    EXPECT_EQ(m.meshes[i].triangleCount(), 2u * 6 + 6u * 2);
  }
  EXPECT_EQ(m.triangleCount(), 384u + 12 + 36 + 24 + 24);
}

TEST(FiveObjectModel, TexcoordsAreInTheUnitSquareAndFacesWindOutward) {
  for (const Mesh& mesh : five().meshes) {
    ASSERT_EQ(mesh.texcoords.size(), mesh.positions.size());
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    for (const glm::vec2& t : mesh.texcoords) {
      EXPECT_GE(t.x, 0.0f);
      EXPECT_LE(t.x, 1.0f);
      EXPECT_GE(t.y, 0.0f);
      EXPECT_LE(t.y, 1.0f);
    }
    // Counter-clockwise seen from outside: the winding's normal agrees with every corner's normal.
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      const uint32_t a = mesh.indices[3 * t], b = mesh.indices[3 * t + 1], c = mesh.indices[3 * t + 2];
      const glm::vec3 n = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
      for (uint32_t k : {a, b, c}) EXPECT_GT(glm::dot(n, mesh.normals[k]), 0.0f) << mesh.name << " triangle " << t;
    }
  }
}

TEST(FiveObjectModel, TexturesArePowerOfTwoRgbaAndTheSameBytesOnEveryCall) {
  const Model& a = five();
  const Model b = fiveObjectModel();
  const uint32_t sizes[5][2] = {{256, 256}, {128, 64}, {256, 128}, {64, 64}, {64, 64}};
  for (size_t i = 0; i < 5; ++i) {
    const Image img = loadTexture(a, i);
    EXPECT_EQ(img.width, sizes[i][0]);
    EXPECT_EQ(img.height, sizes[i][1]);
    EXPECT_FALSE(img.usesAlpha);
    EXPECT_EQ(img.rgba, loadTexture(b, i).rgba);
    EXPECT_EQ(probeTexture(a, i).width, sizes[i][0]);
    for (size_t j = 0; j < i; ++j) {
      if (sizes[j][0] == sizes[i][0] && sizes[j][1] == sizes[i][1]) {
        EXPECT_NE(img.rgba, loadTexture(a, j).rgba) << "textures " << j << " and " << i;
      }
    }
  }
  for (size_t i = 0; i < 5; ++i) EXPECT_EQ(a.meshes[i].positions, b.meshes[i].positions);
}

// The default camera's view space (gluLookAt) and frustum for a square viewport.
struct View {
  glm::dvec3 s, u, f;
  glm::dvec3 at(const glm::vec3& p) const {  // (right, up, depth in front of the eye)
    const glm::dvec3 v = glm::dvec3(p) - kFiveObjectEye;
    return {glm::dot(v, s), glm::dot(v, u), glm::dot(v, f)};
  }
  bool inside(const glm::vec3& p) const {
    const glm::dvec3 q = at(p);
    const double lim = q.z * kFiveObjectTanHalfFovY;
    return q.z > kFiveObjectNear && q.z < kFiveObjectFar && std::abs(q.x) < lim && std::abs(q.y) < lim;
  }
  // Normalized screen position in [-1, 1]² (for points in front of the eye).
  glm::dvec2 screen(const glm::vec3& p) const {
    const glm::dvec3 q = at(p);
    return {q.x / (q.z * kFiveObjectTanHalfFovY), q.y / (q.z * kFiveObjectTanHalfFovY)};
  }
};

View defaultView() {
  View v;
  v.f = glm::normalize(kFiveObjectTarget - kFiveObjectEye);
  v.s = glm::normalize(glm::cross(v.f, kFiveObjectUp));
  v.u = glm::cross(v.s, v.f);
  return v;
}

TEST(FiveObjectModel, TheDefaultCameraSeesEveryObjectAndTheDiscLeavesTheBottomOfTheScreen) {
  EXPECT_NEAR(kFiveObjectTanHalfFovY, std::tan(kFiveObjectFovyDegrees / 2 * M_PI / 180), 1e-15);
  const View v = defaultView();
  std::vector<glm::dvec4> rect;  // screen rectangle of each object's vertices, clipped to the screen
  for (const Mesh& mesh : five().meshes) {
    // Some vertex strictly inside the frustum, so the object's AABB overlaps it.
    EXPECT_TRUE(std::any_of(mesh.positions.begin(), mesh.positions.end(), [&](auto& p) { return v.inside(p); }))
        << mesh.name;
    glm::dvec4 r{1e9, 1e9, -1e9, -1e9};
    for (const glm::vec3& p : mesh.positions) {
      ASSERT_GT(v.at(p).z, kFiveObjectNear) << mesh.name;
      const glm::dvec2 q = glm::clamp(v.screen(p), -1.0, 1.0);
      r = {std::min(r.x, q.x), std::min(r.y, q.y), std::max(r.z, q.x), std::max(r.w, q.y)};
    }
    rect.push_back(r);
  }
  const Mesh& disc = five().meshes[0];
  EXPECT_TRUE(std::any_of(disc.positions.begin(), disc.positions.end(), [&](auto& p) { return v.screen(p).y < -1; }));
  for (size_t i = 1; i < 5; ++i)  // and nothing else leaves the screen
    for (const glm::vec3& p : five().meshes[i].positions) EXPECT_TRUE(v.inside(p)) << five().meshes[i].name;
  // On screen, the pad, the screws and the disc overlap the caliper.
  for (size_t i : {0, 1, 3, 4})
    EXPECT_TRUE(rect[i].x < rect[2].z && rect[2].x < rect[i].z && rect[i].y < rect[2].w && rect[2].y < rect[i].w) << i;
}

// True if the segment from the eye to p passes through the box [lo, hi] before reaching p (slab test).
bool hiddenByBox(const glm::dvec3& p, const glm::dvec3& lo, const glm::dvec3& hi) {
  const glm::dvec3 d = p - kFiveObjectEye;
  double t0 = 0.0, t1 = 1.0 - 1e-9;
  for (int k = 0; k < 3; ++k) {
    double a = (lo[k] - kFiveObjectEye[k]) / d[k], b = (hi[k] - kFiveObjectEye[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a), t1 = std::min(t1, b);
  }
  return t0 <= t1;
}

TEST(FiveObjectModel, TheCaliperPlateHidesTheMiddleOfThePadButNotItsEnds) {
  // The pad's front face is z = 0.13 over x in [-0.6, 0.6], y in [0.62, 0.98]; the caliper's front
  // plate is the box [-0.4, 0.4] x [0.55, 1.16] x [0.15, 0.30].
  Bounds pad;
  for (const glm::vec3& p : five().meshes[1].positions) pad.add(p);
  EXPECT_EQ(pad.max.z, 0.13f);
  const glm::dvec3 lo{-0.4, 0.55, 0.15}, hi{0.4, 1.16, 0.30};
  const double y = (double(pad.min.y) + pad.max.y) / 2, z = pad.max.z;
  EXPECT_TRUE(hiddenByBox({0.0, y, z}, lo, hi));
  EXPECT_FALSE(hiddenByBox({pad.min.x + 0.05, y, z}, lo, hi));
  EXPECT_FALSE(hiddenByBox({pad.max.x - 0.05, y, z}, lo, hi));
}

}  // namespace
}  // namespace tessera::model
