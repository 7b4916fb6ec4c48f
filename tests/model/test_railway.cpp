// railway.glb (data/, see data/README.md): a real CityGML-derived glTF 2.0 scene with 28 embedded JPEG textures and
// texcoords that repeat far outside [0, 1].
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "base/sha256.h"
#include "model/model.h"
#include "model_test_util.h"

namespace tessera::model {
namespace {

using testing::kRailway;

// Fails (never skips) when the file is missing: these tests are the loader's contact with real data.
const Model& railway() {
  static const Model m = [] {
    if (!std::filesystem::exists(kRailway)) {
      ADD_FAILURE() << kRailway << " is missing: it ships in data/ (data/README.md)";
      return Model{};
    }
    return loadModel(kRailway);
  }();
  return m;
}

// The JSON chunk of the .glb, read independently of the loader.
nlohmann::json railwayJson() {
  std::ifstream f(kRailway, std::ios::binary);
  std::vector<char> head(20);
  f.read(head.data(), 20);
  uint32_t len = 0;
  std::memcpy(&len, head.data() + 12, 4);
  std::string json(len, '\0');
  f.read(json.data(), len);
  return nlohmann::json::parse(json);
}

TEST(Railway, LoadsWith28TexturesAndTexturedTriangles) {
  ASSERT_TRUE(std::filesystem::exists(kRailway)) << kRailway << " is missing";
  const Model& m = railway();
  EXPECT_EQ(m.loader, "gltf");
  EXPECT_EQ(m.textures.size(), 28u);
  EXPECT_EQ(m.materials.size(), 28u);
  EXPECT_GT(m.triangleCount(), 0u);
  EXPECT_FALSE(m.bounds.empty());
  for (const Mesh& mesh : m.meshes) {
    EXPECT_EQ(mesh.texcoords.size(), mesh.positions.size()) << mesh.name;
    EXPECT_GE(m.materials[mesh.material].baseColorTexture, 0) << mesh.name;
  }
  for (const TextureRef& t : m.textures) EXPECT_EQ(t.source, TextureRef::Source::FileRange);  // not copied
  std::printf("railway.glb: %zu meshes, %zu triangles, %zu textures, bounds (%g %g %g)..(%g %g %g)\n", m.meshes.size(),
              m.triangleCount(), m.textures.size(), m.bounds.min.x, m.bounds.min.y, m.bounds.min.z, m.bounds.max.x,
              m.bounds.max.y, m.bounds.max.z);
}

TEST(Railway, TexcoordsOutsideTheUnitSquareSurviveExactlyAsTheAccessorsSay) {
  ASSERT_TRUE(std::filesystem::exists(kRailway)) << kRailway << " is missing";
  const Model& m = railway();
  const nlohmann::json j = railwayJson();
  // The single node has a matrix but texcoords are not transformed: each primitive's TEXCOORD_0
  // min/max (written by the exporter) must be exactly the loaded extremes.
  const auto& prims = j["meshes"][0]["primitives"];
  ASSERT_EQ(m.meshes.size(), prims.size());
  float maxAbs = 0.0f;
  for (size_t p = 0; p < prims.size(); ++p) {
    const auto& acc = j["accessors"][prims[p]["attributes"]["TEXCOORD_0"].get<size_t>()];
    float lo[2] = {1e30f, 1e30f}, hi[2] = {-1e30f, -1e30f};
    for (const glm::vec2& t : m.meshes[p].texcoords) {
      lo[0] = std::min(lo[0], t.x), lo[1] = std::min(lo[1], t.y), hi[0] = std::max(hi[0], t.x),
      hi[1] = std::max(hi[1], t.y);
      maxAbs = std::max({maxAbs, std::fabs(t.x), std::fabs(t.y)});
    }
    for (int k = 0; k < 2; ++k) {
      EXPECT_EQ(lo[k], acc["min"][k].get<float>()) << "primitive " << p << " component " << k;
      EXPECT_EQ(hi[k], acc["max"][k].get<float>()) << "primitive " << p << " component " << k;
    }
  }
  EXPECT_GT(maxAbs, 1.0f);
  std::printf("railway.glb: max |uv| = %g\n", maxAbs);
}

TEST(Railway, TheNodeMatrixIsAppliedToPositions) {
  ASSERT_TRUE(std::filesystem::exists(kRailway)) << kRailway << " is missing";
  // The node matrix swaps y and z (y' = z, z' = -y): the first primitive's POSITION accessor has
  // y in [3.942, 7.434] and z in [8.359, 8.638].
  const Mesh& mesh = railway().meshes.at(0);
  Bounds b;
  for (const glm::vec3& p : mesh.positions) b.add(p);
  EXPECT_FLOAT_EQ(b.min.y, 8.359000205993652f);
  EXPECT_FLOAT_EQ(b.max.y, 8.63800048828125f);
  EXPECT_FLOAT_EQ(b.min.z, -7.434000015258789f);
  EXPECT_FLOAT_EQ(b.max.z, -3.941999912261963f);
}

TEST(Railway, EveryTextureDecodesAndItsHeaderProbeAgrees) {
  ASSERT_TRUE(std::filesystem::exists(kRailway)) << kRailway << " is missing";
  const Model& m = railway();
  for (size_t i = 0; i < m.textures.size(); ++i) {
    const TextureInfo info = probeTexture(m, i);
    const Image img = loadTexture(m, i);
    EXPECT_GT(img.width, 0u);
    EXPECT_EQ(img.width, info.width) << i;
    EXPECT_EQ(img.height, info.height) << i;
    EXPECT_EQ(img.rgba.size(), size_t(img.width) * img.height * 4) << i;
    // 27 JPEGs and one PNG (texture 5), each as its mimeType says.
    EXPECT_EQ(info.format, m.textures[i].mimeType == "image/png" ? "png" : "jpeg") << i;
    EXPECT_FALSE(img.usesAlpha) << i;  // every railway texture is RGB
    std::printf("railway.glb texture %2zu: %ux%u, %d channels, %llu bytes\n", i, img.width, img.height,
                img.fileChannels, (unsigned long long)m.textures[i].size);
  }
}

// data/README.md records the file's digest; the goldens and every figure in docs/model-import.md were
// measured on exactly these bytes, so an edited copy must fail here first.
TEST(Railway, TheRepositoryCopyHasTheDigestThatDataReadmeRecords) {
  std::ifstream f(kRailway, std::ios::binary);
  ASSERT_TRUE(f) << kRailway;
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  EXPECT_EQ(bytes.size(), 1341900u);
  EXPECT_EQ(sha256Hex(bytes), "32642154dc0a1206686e11e5e0d1d785bb7ea68da669d2e3a7ec290167478a72");
}

}  // namespace
}  // namespace tessera::model
