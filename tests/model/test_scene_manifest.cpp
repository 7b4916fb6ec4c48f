// Scenes of several model files (model/scene_manifest.h): a JSON manifest with a transform per entry, or
// a directory, read by loadModel() like one model. Positions after the transforms are worked out by
// hand; every refusal is asserted with its whole message (file, JSON pointer, reason).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "model/model.h"
#include "model_test_util.h"

namespace tessera::model {
namespace {

using testing::errorOf;
using testing::ScratchDir;

// An AC3D triangle (0,0,0) (1,0,0) (0,1,0), counter-clockwise seen from +z, textured with tex.png
// (written beside it), in the object `name`.
void writeTriangle(const ScratchDir& dir, const std::string& file, const std::string& name = "tri") {
  testing::writeChecker((std::filesystem::path(dir / file).parent_path() / "tex.png").string(), 2, 2);
  testing::writeFile(dir / file,
                     "AC3Db\nMATERIAL \"white\" rgb 1 1 1 amb 0 0 0 emis 0 0 0 spec 0 0 0 shi 0 trans 0\n"
                     "OBJECT world\nkids 1\nOBJECT poly\nname \"" +
                         name +
                         "\"\ntexture \"tex.png\"\n"
                         "numvert 3\n0 0 0\n1 0 0\n0 1 0\nnumsurf 1\nSURF 0x10\nmat 0\nrefs 3\n"
                         "0 0 0\n1 1 0\n2 0 1\nkids 0\n");
}

std::string writeManifest(const ScratchDir& dir, const nlohmann::json& models, const std::string& name = "scene.json") {
  testing::writeFile(dir / name, nlohmann::json{{"schema", 1}, {"models", models}}.dump(2));
  return dir / name;
}

// The positions of mesh `i` in the order of its triangle's corners.
std::vector<glm::vec3> meshCorners(const Model& m, size_t i) {
  std::vector<glm::vec3> out;
  for (uint32_t k : m.meshes.at(i).indices) out.push_back(m.meshes[i].positions[k]);
  return out;
}

TEST(SceneManifest, EntriesAreMergedInOrderWithTheirTransformsSharingTexturesAndMaterials) {
  ScratchDir dir;
  writeTriangle(dir, "a.ac");
  const std::string scene = writeManifest(
      dir, {{{"file", "a.ac"}, {"translation", {10, 0, 0}}},
            {{"file", "a.ac"}, {"name", "second"}, {"transform", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 7, 8, 9, 1}}}});
  const Model m = loadModel(scene);
  EXPECT_EQ(m.loader, "scene:manifest");
  EXPECT_EQ(m.source, scene);
  ASSERT_EQ(m.meshes.size(), 2u);
  EXPECT_EQ(meshCorners(m, 0), (std::vector<glm::vec3>{{10, 0, 0}, {11, 0, 0}, {10, 1, 0}}));
  // Column-major, as glTF's node.matrix: elements 12, 13, 14 are the translation.
  EXPECT_EQ(meshCorners(m, 1), (std::vector<glm::vec3>{{7, 8, 9}, {8, 8, 9}, {7, 9, 9}}));
  EXPECT_EQ(m.textures.size(), 1u);  // the same tex.png, once
  EXPECT_EQ(m.materials.size(), 1u);
  EXPECT_EQ(m.meshes[0].material, m.meshes[1].material);
  ASSERT_EQ(m.objects.size(), 2u);
  EXPECT_EQ(m.objects[0].name, "tri");
  EXPECT_EQ(m.objects[1].name, "second");  // a model of one object takes the entry's name
  EXPECT_NE(m.objects[0].node, m.objects[1].node);
  EXPECT_EQ(m.meshes[1].object, 1u);
  EXPECT_EQ(m.bounds.min, glm::vec3(7, 0, 0));
  EXPECT_EQ(m.bounds.max, glm::vec3(11, 9, 9));
}

TEST(SceneManifest, RotationIsInDegreesXThenYThenZAndQuarterTurnsAreExact) {
  ScratchDir dir;
  writeTriangle(dir, "a.ac");
  const std::string scene = writeManifest(dir, {{{"file", "a.ac"}, {"rotation", {0, 90, 0}}},
                                                {{"file", "a.ac"}, {"rotation", {90, 0, 90}}},
                                                {{"file", "a.ac"}, {"rotation", {0, 0, -630}}},
                                                {{"file", "a.ac"}, {"rotation", {0, 0, 180}}, {"scale", {2, 3, 4}}}});
  const Model m = loadModel(scene);
  ASSERT_EQ(m.meshes.size(), 4u);
  // About y by 90: x -> -z, y stays.
  EXPECT_EQ(meshCorners(m, 0), (std::vector<glm::vec3>{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}}));
  // x first (y -> z), then z (x -> y): (1,0,0) -> (0,1,0), (0,1,0) -> (0,0,1). The other order would
  // send (1,0,0) to (0,0,1).
  EXPECT_EQ(meshCorners(m, 1), (std::vector<glm::vec3>{{0, 0, 0}, {0, 1, 0}, {0, 0, 1}}));
  // -630 = 90 (mod 360) about z: x -> y, y -> -x.
  EXPECT_EQ(meshCorners(m, 2), (std::vector<glm::vec3>{{0, 0, 0}, {0, 1, 0}, {-1, 0, 0}}));
  // Scale first, then a half turn: (1,0,0) -> (2,0,0) -> (-2,0,0); (0,1,0) -> (0,3,0) -> (0,-3,0).
  EXPECT_EQ(meshCorners(m, 3), (std::vector<glm::vec3>{{0, 0, 0}, {-2, 0, 0}, {0, -3, 0}}));
}

TEST(SceneManifest, AMirroringScaleKeepsTrianglesCounterClockwise) {
  ScratchDir dir;
  writeTriangle(dir, "a.ac");
  const Model m = loadModel(writeManifest(dir, {{{"file", "a.ac"}, {"scale", {-1, 1, 1}}}}));
  const std::vector<glm::vec3> c = meshCorners(m, 0);
  ASSERT_EQ(c.size(), 3u);
  const glm::vec3 e1 = c[1] - c[0], e2 = c[2] - c[0];
  EXPECT_EQ(e1.x * e2.y - e1.y * e2.x, 1.0f);  // twice the area, positive: still counter-clockwise
}

TEST(SceneManifest, ADirectoryIsEveryModelFileInItSortedByNameWithIdentityTransforms) {
  ScratchDir dir;
  std::filesystem::create_directories(dir.path / "scene" / "textures");
  writeTriangle(dir, "scene/b.ac", "bee");
  writeTriangle(dir, "scene/a.AC", "ay");
  testing::writeFile(dir / "scene/readme.txt", "not a model");
  testing::writeFile(dir / "scene/other.json", "{}");  // a manifest is not a model file of a directory
  const Model m = loadModel(dir / "scene");
  EXPECT_EQ(m.loader, "scene:directory");
  ASSERT_EQ(m.objects.size(), 2u);
  EXPECT_EQ(m.objects[0].name, "ay");
  EXPECT_EQ(m.objects[1].name, "bee");
  EXPECT_EQ(meshCorners(m, 1), (std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
  std::filesystem::create_directories(dir.path / "empty");
  EXPECT_EQ(
      errorOf([&] { loadModel(dir / "empty"); }),
      dir / "empty" + ": no model file in this directory (.gltf .glb .obj .ac .acc .ac3d .dae .fbx .3ds .ply .stl)");
}

TEST(SceneManifest, BadJsonIsAnErrorNamingTheLineAndColumn) {
  ScratchDir dir;
  testing::writeFile(dir / "scene.json", "{\n  \"schema\": 1,\n  \"models\": [ x ]\n}\n");
  // Line 3 is `  "models": [ x ]`: the x is its 15th character.
  EXPECT_CONTAINS(errorOf([&] { loadModel(dir / "scene.json"); }), dir / "scene.json" + ":3:15: not valid JSON: ");
  EXPECT_EQ(errorOf([&] { loadModel(dir / "missing.json"); }), dir / "missing.json" + ": no such model file");
}

TEST(SceneManifest, ANumberBeyondTheRangeOfADoubleIsAnErrorNamingTheManifest) {
  ScratchDir dir;
  writeTriangle(dir, "a.ac");
  testing::writeFile(dir / "scene.json", "{\"schema\": 1, \"models\": [{\"file\": \"a.ac\", \"scale\": [1e309, 1, 1]}]}\n");
  EXPECT_EQ(errorOf([&] { loadModel(dir / "scene.json"); }),
            dir / "scene.json" +
                ": not valid JSON: a number beyond the range of a double: [json.exception.out_of_range.406] number "
                "overflow parsing '1e309'");
}

TEST(SceneManifest, EveryMalformedEntryIsAnErrorNamingTheManifestAndTheJsonPointer) {
  ScratchDir dir;
  writeTriangle(dir, "a.ac");
  const std::string path = dir / "scene.json";
  const auto error = [&](const nlohmann::json& doc) {
    testing::writeFile(path, doc.dump());
    return errorOf([&] { loadModel(path); });
  };
  const auto withModels = [](const nlohmann::json& models) {
    return nlohmann::json{{"schema", 1}, {"models", models}};
  };
  const nlohmann::json a = {{"file", "a.ac"}};
  EXPECT_EQ(error(nlohmann::json::array()), path + ": a scene manifest is a JSON object, not []");
  EXPECT_EQ(error({{"models", {a}}}), path + ": /schema: missing: a scene manifest says \"schema\": 1");
  EXPECT_EQ(error({{"schema", 2}, {"models", {a}}}), path + ": /schema: expected 1, got 2");
  EXPECT_EQ(error({{"schema", 1}, {"models", {a}}, {"model", 1}}),
            path + ": /model: unknown key (a scene manifest has schema, models and comment)");
  EXPECT_EQ(error({{"schema", 1}}), path + ": /models: missing: the list of model files");
  EXPECT_EQ(error(withModels(nlohmann::json::object())), path + ": /models: expected an array of entries, got {}");
  EXPECT_EQ(error(withModels(nlohmann::json::array())),
            path + ": /models: empty: a scene needs at least one model file");
  EXPECT_EQ(error(withModels({a, "a.ac"})), path + ": /models/1: expected an object with \"file\", got \"a.ac\"");
  EXPECT_EQ(error(withModels({{{"name", "x"}}})), path + ": /models/0/file: missing: the model file of this entry");
  EXPECT_EQ(error(withModels({{{"file", 3}}})), path + ": /models/0/file: expected a file name, got 3");
  EXPECT_EQ(
      error(withModels({a, {{"file", "a.ac"}, {"rotate", {0, 0, 0}}}})),
      path +
          ": /models/1/rotate: unknown key (an entry has file, name, and transform or translation / rotation / scale)");
  EXPECT_EQ(error(withModels({a, a, a, {{"file", "a.ac"}, {"transform", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0}}}})),
            path + ": /models/3/transform: expected 16 numbers, got 12");
  EXPECT_EQ(error(withModels({{{"file", "a.ac"}, {"translation", {1, "a", 3}}}})),
            path + ": /models/0/translation/1: expected a finite number, got \"a\"");
  EXPECT_EQ(error(withModels({{{"file", "a.ac"}, {"rotation", 90}}})),
            path + ": /models/0/rotation: expected 3 numbers, got 90");
  EXPECT_EQ(error(withModels({{{"file", "a.ac"}, {"scale", {1, 0, 1}}}})),
            path + ": /models/0/scale/1: 0 would flatten the model");
  EXPECT_EQ(error(withModels({{{"file", "a.ac"}, {"name", 5}}})), path + ": /models/0/name: expected a string, got 5");
  EXPECT_EQ(
      error(withModels(
          {{{"file", "a.ac"}, {"transform", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}, {"scale", {2, 2, 2}}}})),
      path + ": /models/0: has both transform and translation / rotation / scale: give one or the other");
  // A row-major matrix with its translation in elements 3, 7, 11.
  EXPECT_EQ(error(withModels({{{"file", "a.ac"}, {"transform", {1, 0, 0, 5, 0, 1, 0, 6, 0, 0, 1, 7, 0, 0, 0, 1}}}})),
            path +
                ": /models/0/transform: not affine: elements 3, 7, 11, 15 (the last row, column-major as glTF's "
                "node.matrix) must be 0 0 0 1, got [5.0,6.0,7.0,1.0] (a row-major matrix puts its translation there)");
  EXPECT_EQ(error(withModels({a, {{"file", "missing.ac"}}})),
            path + ": /models/1/file: 'missing.ac' (resolved to '" + dir / "missing.ac" + "') does not exist");
  std::filesystem::create_directories(dir.path / "sub");
  EXPECT_EQ(error(withModels({{{"file", "sub"}}})),
            path + ": /models/0/file: 'sub' is a directory: a manifest lists model files, not scenes");
  // A manifest listing itself (or any manifest) is refused before anything is loaded: no cycle is possible.
  EXPECT_EQ(
      error(withModels({{{"file", "scene.json"}}})),
      path + ": /models/0/file: 'scene.json' is a scene manifest: manifests do not nest (so they cannot form a cycle)");
}

TEST(SceneManifest, AnErrorInsideAModelNamesTheEntryAndThenTheModelsOwnError) {
  ScratchDir dir;
  writeTriangle(dir, "a.ac");
  testing::writeFile(dir / "bad.ac", "AC3Db\nOBJECT world\nkids 1\n");
  EXPECT_EQ(errorOf([&] {
              loadModel(writeManifest(dir, {{{"file", "a.ac"}}, {{"file", "bad.ac"}}}));
            }),
            dir / "scene.json" + ": /models/1: " + dir / "bad.ac" +
                ":3: kids 1 cannot fit in the 0 bytes that follow (a line takes 2 at least)");
}

TEST(SceneManifest, TheMergedTrianglesAreCheckedAgainstTheBudget) {
  ScratchDir dir;
  writeTriangle(dir, "a.ac");
  ResourceLimits limits;
  limits.modelTriangles = 1;  // each file alone is within it
  EXPECT_CONTAINS(errorOf([&] {
                    loadModel(writeManifest(dir, {{{"file", "a.ac"}}, {{"file", "a.ac"}}}), limits);
                  }),
                  dir / "scene.json" + ": needs 2 triangles, over the limit of 1");
}

}  // namespace
}  // namespace tessera::model
