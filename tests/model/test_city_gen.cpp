// The synthetic city generator: small "berlin" and "chemnitz" cities round-trip through loadModel
// with the expected counts, and the bytes of every file depend only on the options.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>

#include "model/city_gen.h"
#include "model/model.h"
#include "model_test_util.h"

namespace tessera::model {
namespace {

using testing::ScratchDir;

CitySummary generateSmallCity(CityPreset preset, uint32_t buildings, uint64_t seed, const std::string& dir,
                              uint32_t textureSize = 64, CityImageFormat format = CityImageFormat::Png) {
  CityOptions o;
  o.preset = preset;
  o.buildings = buildings;
  o.seed = seed;
  o.textureSize = textureSize;
  o.format = format;
  o.outDir = dir;
  o.progress = false;
  return generateCity(o);
}

bool isPowerOfTwo(uint32_t v) { return v && !(v & (v - 1)); }

TEST(CityGenerator, SmallBerlinRoundTripsWithOneFacadeTexturePerBuildingAndUntexturedRoofsAndGround) {
  ScratchDir dir;
  const CitySummary s = generateSmallCity(CityPreset::Berlin, 6, 7, dir / "out");
  // Facades are the whole textured workload (thesis §4.7.1: roofs and terrain are not in the atlas tree).
  EXPECT_EQ(s.textures, 6u);
  // 4 walls + roof per building; per cell of the 3 x 3 grid a lot and two street strips.
  EXPECT_EQ(s.triangles, 6u * 10 + 9u * 6);
  EXPECT_EQ(s.files.size(), 6u + 2);
  const Model m = loadModel(s.gltf);
  EXPECT_EQ(m.textures.size(), 6u);
  EXPECT_EQ(m.materials.size(), 6u + 5);  // facades, lot, asphalt, 3 roof colours
  EXPECT_EQ(m.triangleCount(), s.triangles);
  EXPECT_EQ(m.meshes.size(), s.primitives);
  std::vector<int> uses(6, 0);
  size_t textured = 0, untexturedTriangles = 0;
  for (const Mesh& mesh : m.meshes) {
    const Material& mat = m.materials[mesh.material];
    if (mat.baseColorTexture < 0) {
      EXPECT_TRUE(mesh.texcoords.empty()) << mesh.name;
      EXPECT_LT(mat.baseColorFactor[0], 1.0f) << mesh.name << ": a base colour, not the default white";
      for (size_t v = 0; v < mesh.positions.size(); ++v) EXPECT_GE(mesh.positions[v].y, 0.0f);
      untexturedTriangles += mesh.triangleCount();
      continue;
    }
    ++textured;
    ++uses[size_t(mat.baseColorTexture)];
    ASSERT_EQ(mesh.texcoords.size(), mesh.positions.size());
    EXPECT_EQ(mesh.triangleCount(), 8u) << mesh.name << ": the four walls";
    float maxU = 0;
    for (const glm::vec2& t : mesh.texcoords) maxU = std::max(maxU, t.x);
    EXPECT_GT(maxU, 1.0f) << mesh.name << ": the facade texture repeats around the building";
  }
  EXPECT_EQ(textured, 6u);
  EXPECT_EQ(untexturedTriangles, 6u * 2 + 9u * 6);
  for (int u : uses) EXPECT_EQ(u, 1);
  // Buildings stand on a grid of 105 m lots: node translations are applied.
  EXPECT_GT(m.bounds.max.x - m.bounds.min.x, 105.0f);
  EXPECT_EQ(m.bounds.min.y, 0.0f);
  for (size_t i = 0; i < m.textures.size(); ++i) {
    const Image img = loadTexture(m, i);
    EXPECT_EQ(img.width, 64u);
    EXPECT_EQ(img.fileChannels, 3);
  }
}

TEST(CityGenerator, SmallChemnitzRoundTripsWithRgbaPartsOddSizesAndOverAHundredRepeatsOnOneTriangle) {
  ScratchDir dir;
  const CitySummary s = generateSmallCity(CityPreset::Chemnitz, 8, 3, dir / "out");
  EXPECT_EQ(s.textures, 5u * 8);
  EXPECT_GT(s.rgbaTextures, 0u);
  const Model m = loadModel(s.gltf);
  EXPECT_EQ(m.textures.size(), s.textures);
  EXPECT_EQ(m.triangleCount(), s.triangles);
  EXPECT_EQ(m.meshes.size(), s.primitives);
  size_t mask = 0, blend = 0;
  for (const Material& mat : m.materials)
    mask += mat.alphaMode == AlphaMode::Mask, blend += mat.alphaMode == AlphaMode::Blend;
  EXPECT_GT(mask, 0u);
  EXPECT_GT(blend, 0u);
  // Some single triangle (a plaza's pavement) spans 34 / 0.3 = 113 texture repeats; the terrain is
  // untextured.
  float maxSpan = 0;
  size_t untextured = 0;
  for (const Mesh& mesh : m.meshes) {
    if (mesh.texcoords.empty()) {
      ++untextured;
      continue;
    }
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
      float lo = 1e30f, hi = -1e30f;
      for (int k = 0; k < 3; ++k)
        lo = std::min(lo, mesh.texcoords[mesh.indices[t + k]].x),
        hi = std::max(hi, mesh.texcoords[mesh.indices[t + k]].x);
      maxSpan = std::max(maxSpan, hi - lo);
    }
  }
  EXPECT_GT(maxSpan, 113.0f);
  EXPECT_EQ(untextured, 1u);
  // RGBA textures decode with alpha in use; some texture is not a power of two.
  bool anyAlpha = false, anyOdd = false;
  for (size_t i = 0; i < m.textures.size(); ++i) {
    const TextureInfo info = probeTexture(m, i);
    anyOdd = anyOdd || !isPowerOfTwo(info.width) || !isPowerOfTwo(info.height);
    if (info.channels == 4) anyAlpha = anyAlpha || loadTexture(m, i).usesAlpha;
  }
  EXPECT_TRUE(anyAlpha);
  EXPECT_TRUE(anyOdd);
}

void expectSameFiles(const std::string& a, const std::string& b, const std::vector<std::string>& files) {
  for (const std::string& f : files) EXPECT_EQ(testing::readFile(a + "/" + f), testing::readFile(b + "/" + f)) << f;
}

TEST(CityGenerator, TheSameSeedGivesIdenticalBytesInEveryFileForAnyThreadCount) {
  ScratchDir dir;
  for (CityPreset p : {CityPreset::Berlin, CityPreset::Chemnitz}) {
    const CitySummary a = generateSmallCity(p, 5, 11, dir / "a");
    CitySummary b;
    tbb::task_arena one(1);
    one.execute([&] { b = generateSmallCity(p, 5, 11, dir / "b"); });
    ASSERT_EQ(a.files, b.files);
    ASSERT_FALSE(a.files.empty()) << "nothing was generated, so nothing was compared";
    EXPECT_EQ(a.bytesOnDisk, b.bytesOnDisk);
    expectSameFiles(dir / "a", dir / "b", a.files);
  }
}

TEST(CityGenerator, ADifferentSeedGivesDifferentGeometryAndTextures) {
  ScratchDir dir;
  for (CityPreset p : {CityPreset::Berlin, CityPreset::Chemnitz}) {
    const CitySummary a = generateSmallCity(p, 5, 11, dir / "a"), b = generateSmallCity(p, 5, 12, dir / "b");
    const std::string bin = std::string(cityPresetName(p)) + ".bin";
    EXPECT_NE(testing::readFile(dir / "a/" + bin), testing::readFile(dir / "b/" + bin));
    size_t differing = 0;
    for (const std::string& f : a.files)
      if (f.starts_with("textures/"))
        differing += testing::readFile(dir / "a/" + f) != testing::readFile(dir / "b/" + f);
    EXPECT_GT(differing, 0u);
  }
}

TEST(CityGenerator, JpegFormatWritesRgbTexturesAsJpegAndKeepsRgbaTexturesPng) {
  ScratchDir dir;
  const CitySummary s = generateSmallCity(CityPreset::Chemnitz, 4, 1, dir / "out", 64, CityImageFormat::Jpg);
  const Model m = loadModel(s.gltf);
  size_t jpg = 0, png = 0;
  for (size_t i = 0; i < m.textures.size(); ++i) {
    const TextureInfo info = probeTexture(m, i);
    if (info.format == "jpeg") {
      ++jpg;
      EXPECT_EQ(info.channels, 3);
    } else if (info.format == "png") {
      ++png;
      EXPECT_EQ(info.channels, 4);
    }
  }
  EXPECT_EQ(jpg, s.textures - s.rgbaTextures);
  EXPECT_EQ(png, s.rgbaTextures);
}

TEST(CityGenerator, BadOptionsAreClearErrors) {
  ScratchDir dir;
  EXPECT_THROW(parseCityPreset("paris"), Error);
  CityOptions o;
  o.outDir = dir / "out";
  o.textureSize = 3;
  EXPECT_THROW(generateCity(o), Error);
  o.textureSize = 64;
  o.outDir = "/proc/tessera-cannot-write-here";
  o.buildings = 1;
  EXPECT_THROW(generateCity(o), Error);
}

}  // namespace
}  // namespace tessera::model
