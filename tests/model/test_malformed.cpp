// Malformed inputs are an Error naming the file (and the JSON pointer or the missing path), never a
// crash. Run under ASan+UBSan too (build-asan/tests/model/model_tests).
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>

#include "model/model.h"
#include "model_test_util.h"
#include "base/error.h"

namespace tessera::model {
namespace {

using testing::ScratchDir;

using testing::kRailway;

using testing::errorOf;

// A one-triangle glTF; `edit` may break it.
std::string writeTriangleGltf(const ScratchDir& dir, const std::function<void(nlohmann::json&)>& edit) {
  std::string bin;
  testing::appendBytes(bin, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1});
  testing::appendBytes(bin, std::vector<uint16_t>{0, 1, 2, 0});
  nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"buffers",
       {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + testing::base64(bin)}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
        {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 24}},
        {{"buffer", 0}, {"byteOffset", 60}, {"byteLength", 8}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}},
        {{"bufferView", 2}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}}}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"scenes", {{{"nodes", {0}}}}}};
  edit(j);
  const std::string path = dir / "tri.gltf";
  testing::writeFile(path, j.dump());
  return path;
}

TEST(MalformedInput, TheUneditedTriangleLoads) {
  ScratchDir dir;
  EXPECT_EQ(loadModel(writeTriangleGltf(dir, [](nlohmann::json&) {})).triangleCount(), 1u);
}

TEST(MalformedInput, ATruncatedGlbNamesTheFileAndSaysTruncated) {
  ASSERT_TRUE(std::filesystem::exists(kRailway)) << kRailway << " is missing";
  ScratchDir dir;
  const std::string all = testing::readFile(kRailway);
  for (size_t len : {size_t(10), size_t(19), size_t(100), all.size() / 2, all.size() - 1}) {
    const std::string path = dir / ("cut" + std::to_string(len) + ".glb");
    testing::writeFile(path, all.substr(0, len));
    const std::string e = errorOf([&] { loadModel(path); });
    EXPECT_CONTAINS(e, path);
    EXPECT_CONTAINS(e, "truncated");
  }
}

TEST(MalformedInput, JsonGarbageNamesTheFile) {
  ScratchDir dir;
  testing::writeFile(dir / "garbage.gltf", "{ \"asset\": { \"version\": \"2.0\" }, \"meshes\": [ {,,, ");
  const std::string e = errorOf([&] { loadModel(dir / "garbage.gltf"); });
  EXPECT_CONTAINS(e, dir / "garbage.gltf");
  EXPECT_CONTAINS(e, "not valid JSON");
}

TEST(MalformedInput, BrokenReferencesNameTheJsonPointer) {
  ScratchDir dir;
  struct Case {
    std::function<void(nlohmann::json&)> edit;
    std::string pointer;
  };
  const Case cases[] = {
      {[](nlohmann::json& j) { j["accessors"][0]["count"] = 1000; }, "/accessors/0"},
      {[](nlohmann::json& j) { j["accessors"][1]["byteOffset"] = 20; }, "/accessors/1"},
      {[](nlohmann::json& j) { j["accessors"][1]["type"] = "VEC3"; }, "/accessors/1/type"},
      {[](nlohmann::json& j) { j["bufferViews"][2]["byteLength"] = 800; }, "/bufferViews/2"},
      {[](nlohmann::json& j) { j["nodes"][0]["mesh"] = 7; }, "/nodes/0/mesh"},
      {[](nlohmann::json& j) { j["nodes"][0]["children"] = {0}; }, "/nodes/0"},
      {[](nlohmann::json& j) { j["meshes"][0]["primitives"][0]["material"] = 3; }, "/meshes/0/primitives/0/material"},
      {[](nlohmann::json& j) { j["asset"]["version"] = "3.0"; }, "/asset/version"},
      {[](nlohmann::json& j) {
         j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 4}}}}}}};
         j["meshes"][0]["primitives"][0]["material"] = 0;
       },
       "/materials/0/pbrMetallicRoughness/baseColorTexture/index"},
  };
  for (const Case& c : cases) {
    const std::string path = writeTriangleGltf(dir, c.edit);
    const std::string e = errorOf([&] { loadModel(path); });
    EXPECT_CONTAINS(e, path);
    EXPECT_CONTAINS(e, c.pointer);
  }
  // An index past the vertices: tinygltf accepts it, the loader does not.
  std::string bin;
  const std::string path = writeTriangleGltf(dir, [](nlohmann::json& j) {
    j["accessors"][2]["componentType"] = 5125;
    j["accessors"][2]["count"] = 2;
  });
  EXPECT_CONTAINS(errorOf([&] { loadModel(path); }), "/meshes/0/primitives/0/indices");
}

TEST(MalformedInput, AMissingTextureFileNamesTheModelAndTheMissingPath) {
  ScratchDir dir;
  const std::string gltf = writeTriangleGltf(dir, [](nlohmann::json& j) {
    j["images"] = {{{"uri", "textures/missing%20one.png"}}};
    j["textures"] = {{{"source", 0}}};
    j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    j["meshes"][0]["primitives"][0]["material"] = 0;
  });
  std::string e = errorOf([&] { loadModel(gltf); });
  EXPECT_CONTAINS(e, gltf);
  EXPECT_CONTAINS(e, dir / "textures/missing one.png");
  EXPECT_CONTAINS(e, "/images/0/uri");

  testing::writeFile(dir / "a.mtl", "newmtl m\nmap_Kd nowhere/brick.png\n");
  testing::writeFile(dir / "a.obj", "mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl m\nf 1/1 2/1 3/1\n");
  e = errorOf([&] { loadModel(dir / "a.obj"); });
  EXPECT_CONTAINS(e, dir / "a.obj");
  EXPECT_CONTAINS(e, dir / "nowhere/brick.png");
}

TEST(MalformedInput, AnUndecodableTextureIsAnErrorWhenLoadedNotWhenTheModelIs) {
  ScratchDir dir;
  testing::writeFile(dir / "broken.png", "\x89PNG\r\n\x1a\n this is not a png");
  const std::string gltf = writeTriangleGltf(dir, [](nlohmann::json& j) { j["images"] = {{{"uri", "broken.png"}}}; });
  const Model m = loadModel(gltf);
  ASSERT_EQ(m.textures.size(), 1u);
  const std::string e = errorOf([&] { loadTexture(m, 0); });
  EXPECT_CONTAINS(e, gltf);
  EXPECT_CONTAINS(e, dir / "broken.png");
  EXPECT_CONTAINS(errorOf([&] { probeTexture(m, 0); }), "broken.png");
  EXPECT_CONTAINS(errorOf([&] { loadTexture(m, 5); }), "texture 5");
}

TEST(MalformedInput, OtherFormatsAndMissingFilesNameTheFile) {
  ScratchDir dir;
  EXPECT_CONTAINS(errorOf([&] { loadModel(dir / "nothing.glb"); }), dir / "nothing.glb");
  testing::writeFile(dir / "junk.dae", "<COLLADA><library_geometries><geometry");
  EXPECT_CONTAINS(errorOf([&] { loadModel(dir / "junk.dae"); }), dir / "junk.dae");
  testing::writeFile(dir / "junk.xyz", std::string(64, '\x07'));
  EXPECT_CONTAINS(errorOf([&] { loadModel(dir / "junk.xyz"); }), dir / "junk.xyz");
}

// Deterministic corruption of railway.glb: bytes of the JSON chunk and of the binary chunk are
// overwritten at many places. Each variant must load or throw tessera::Error; under ASan this also
// proves no out-of-bounds read.
TEST(MalformedInput, CorruptedRailwayVariantsLoadOrFailCleanly) {
  ASSERT_TRUE(std::filesystem::exists(kRailway)) << kRailway << " is missing";
  ScratchDir dir;
  const std::string all = testing::readFile(kRailway);
  uint64_t state = 12345;
  auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return state >> 33;
  };
  const char* replacements[] = {"9", "-", "\"", "}", "]", "0", "99999999", "-1", "\x01", "e"};
  size_t loaded = 0, failed = 0;
  for (int i = 0; i < 120; ++i) {
    std::string v = all;
    const size_t jsonLen =
        uint8_t(all[12]) | uint8_t(all[13]) << 8 | uint8_t(all[14]) << 16 | uint32_t(uint8_t(all[15])) << 24;
    const size_t at = i % 3 == 2 ? 20 + jsonLen + next() % (all.size() - 20 - jsonLen) : 20 + next() % jsonLen;
    const std::string r = replacements[next() % std::size(replacements)];
    v.replace(at, std::min(r.size(), v.size() - at), r.substr(0, v.size() - at));
    const std::string path = dir / "v.glb";
    testing::writeFile(path, v);
    try {
      const Model m = loadModel(path);
      ++loaded;
      for (size_t t = 0; t < m.textures.size(); t += 9) try {
          loadTexture(m, t);
        } catch (const Error&) {
        }
    } catch (const Error& e) {
      ++failed;
      EXPECT_CONTAINS(e.what(), path);
    }
  }
  EXPECT_GT(failed, 0u);
  EXPECT_GT(loaded, 0u);
}

}  // namespace
}  // namespace tessera::model
