// glTF 1.0 files go to Assimp whatever their asset.version says: a string "1.0", a number (early
// COLLADA converters wrote "version": 1), or nothing when 1.0-only keys (techniques, programs,
// shaders) are there. A file with neither a version nor those keys is glTF 2.0 and gets its error.
// The files are written by the tests: a textured quad, its buffer embedded as a data: URI or in a .bin
// beside the file (which Assimp must still find when it reads the document from memory).
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "model/model.h"
#include "model_test_util.h"

namespace tessera::model {
namespace {

using testing::ScratchDir;

using testing::hasTexcoord;

// A glTF 1.0 quad (positions, texcoords with u up to 2500, 6 indices) textured with checker.png,
// written beside it. `bufferUri` empty: the buffer is a data: URI; else it is written to that file.
nlohmann::json gltf1Quad(const ScratchDir& dir, const std::string& bufferUri = "") {
  testing::writeChecker(dir / "checker.png", 4, 4);
  std::string bin;
  testing::appendBytes(bin, std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});  // 48 bytes
  testing::appendBytes(bin, std::vector<float>{0, 0, 2500, 0, 2500, 3, 0, 3});        // 32 bytes
  testing::appendBytes(bin, std::vector<uint16_t>{0, 1, 2, 0, 2, 3});                 // 12 bytes
  std::string uri = "data:application/octet-stream;base64," + testing::base64(bin);
  if (!bufferUri.empty()) testing::writeFile(dir / bufferUri, bin), uri = bufferUri;
  return {{"asset", {{"version", "1.0"}}},
          {"buffers", {{"buf", {{"byteLength", bin.size()}, {"type", "arraybuffer"}, {"uri", uri}}}}},
          {"bufferViews",
           {{"vPos", {{"buffer", "buf"}, {"byteOffset", 0}, {"byteLength", 48}, {"target", 34962}}},
            {"vUv", {{"buffer", "buf"}, {"byteOffset", 48}, {"byteLength", 32}, {"target", 34962}}},
            {"vIdx", {{"buffer", "buf"}, {"byteOffset", 80}, {"byteLength", 12}, {"target", 34963}}}}},
          {"accessors",
           {{"aPos",
             {{"bufferView", "vPos"},
              {"byteOffset", 0},
              {"byteStride", 12},
              {"componentType", 5126},
              {"count", 4},
              {"type", "VEC3"},
              {"min", {0, 0, 0}},
              {"max", {1, 1, 0}}}},
            {"aUv",
             {{"bufferView", "vUv"},
              {"byteOffset", 0},
              {"byteStride", 8},
              {"componentType", 5126},
              {"count", 4},
              {"type", "VEC2"}}},
            {"aIdx",
             {{"bufferView", "vIdx"}, {"byteOffset", 0}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}}},
          {"images", {{"img0", {{"uri", "checker.png"}}}}},
          {"samplers", {{"s0", {{"wrapS", 10497}, {"wrapT", 10497}}}}},
          {"textures", {{"tex0", {{"source", "img0"}, {"sampler", "s0"}}}}},
          {"materials", {{"mat0", {{"values", {{"diffuse", "tex0"}}}}}}},
          {"meshes",
           {{"quad",
             {{"primitives",
               {{{"attributes", {{"POSITION", "aPos"}, {"TEXCOORD_0", "aUv"}}},
                 {"indices", "aIdx"},
                 {"material", "mat0"},
                 {"mode", 4}}}}}}}},
          {"nodes", {{"n0", {{"meshes", {"quad"}}}}}},
          {"scenes", {{"s", {{"nodes", {"n0"}}}}}},
          {"scene", "s"}};
}

// What Assimp gives for gltf1Quad(): 2 triangles, the texture, texcoords unclamped.
void expectTheQuad(const Model& m) {
  EXPECT_EQ(m.loader, "assimp:gltf");
  EXPECT_EQ(m.triangleCount(), 2u);
  ASSERT_EQ(m.textures.size(), 1u);
  ASSERT_EQ(m.meshes.size(), 1u);
  EXPECT_TRUE(hasTexcoord(m.meshes[0], 2500.0f, 3.0f));  // Assimp's v flip and ours cancel
  EXPECT_EQ(loadTexture(m, 0).width, 4u);
}

bool hasNote(const Model& m, const std::string& prefix) {
  return std::any_of(m.notes.begin(), m.notes.end(), [&](const std::string& n) { return n.starts_with(prefix); });
}

TEST(AssimpLoader, Gltf1FileIsHandedToAssimpAndKeepsItsTexcoords) {
  ScratchDir dir;
  testing::writeFile(dir / "v1.gltf", gltf1Quad(dir).dump(1));
  const Model m = loadModel(dir / "v1.gltf");
  expectTheQuad(m);
  EXPECT_FALSE(hasNote(m, "glTF 1.0 without a string asset.version"));
}

TEST(Gltf1Detection, ANumericVersionOneIsReadAsGltf1WithItsBinFileBesideIt) {
  ScratchDir dir;
  nlohmann::json j = gltf1Quad(dir, "quad.bin");
  j["asset"]["version"] = 1;
  testing::writeFile(dir / "numeric.gltf", j.dump(1));
  const Model m = loadModel(dir / "numeric.gltf");
  expectTheQuad(m);
  EXPECT_TRUE(hasNote(m, "glTF 1.0 without a string asset.version"));
}

TEST(Gltf1Detection, AMissingVersionWithTechniquesIsReadAsGltf1) {
  ScratchDir dir;
  nlohmann::json j = gltf1Quad(dir);
  j.erase("asset");
  j["techniques"] = nlohmann::json::object();  // 1.0-only: glTF 2.0 has no techniques
  testing::writeFile(dir / "noversion.gltf", j.dump(1));
  expectTheQuad(loadModel(dir / "noversion.gltf"));
  j["asset"] = {{"generator", "x"}};  // an asset without its version is the same case
  testing::writeFile(dir / "noversion2.gltf", j.dump(1));
  expectTheQuad(loadModel(dir / "noversion2.gltf"));
}

TEST(Gltf1Detection, AMissingVersionWithoutGltf1KeysStillGetsTheGltf2Error) {
  ScratchDir dir;
  const nlohmann::json j = {{"meshes", nlohmann::json::array()}, {"nodes", nlohmann::json::array()}};
  testing::writeFile(dir / "v2.gltf", j.dump());
  EXPECT_EQ(testing::errorOf([&] { loadModel(dir / "v2.gltf"); }),
            dir / "v2.gltf" + ": /asset/version: missing (required by glTF 2.0)");
}

TEST(Gltf1Detection, ANumberOutsideOneToTwoIsAGltf2ErrorAskingForAString) {
  ScratchDir dir;
  const nlohmann::json j = {{"asset", {{"version", 2}}}, {"meshes", nlohmann::json::array()}};
  testing::writeFile(dir / "n2.gltf", j.dump());
  EXPECT_EQ(
      testing::errorOf([&] { loadModel(dir / "n2.gltf"); }),
      dir / "n2.gltf" +
          ": /asset/version: expected a string such as \"2.0\", not 2 (a number is read as glTF 1.0 only in [1, 2))");
}

}  // namespace
}  // namespace tessera::model
