// OBJ / MTL inputs from the fuzz campaign (fuzz/crashers/README.md), one test per bug: each is a tessera::Error naming
// file:line and the reason, where tinyobjloader accepted it silently, wrapped an index, or read the
// wrong file. The small reproducers live in tests/model/hostile/obj/.
#include <gtest/gtest.h>

#include <string>

#include "model/model.h"
#include "model_test_util.h"

namespace tessera::model {
namespace {

using testing::errorOf;
using testing::ScratchDir;

const std::string kHostileObj = TESSERA_SOURCE_DIR "/tests/model/hostile/obj/";
const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

TEST(Obj, AVtIndexPastTheEndIsAnErrorNamingTheLine) {
  // The loader dropped the texcoord of that corner without a word.
  const std::string path = kHostileObj + "vt-index-past-the-end.obj";
  EXPECT_CONTAINS(errorOf([&] { loadModel(path); }),
                  path + ":7: f: texcoord index 9 does not exist: the file has 3 vt");
}

TEST(Obj, AFaceIndexThatOverflows32BitsIsAnErrorNotAWrap) {
  // tinyobjloader's atoi turned 99999999999999999999 into -1: the last vertex.
  const std::string path = kHostileObj + "face-index-overflowing-32-bits.obj";
  EXPECT_CONTAINS(errorOf([&] { loadModel(path); }),
                  path + ":4: f: vertex index 99999999999999999999 does not fit in 32 bits");
  ScratchDir dir;
  testing::writeFile(dir / "a.obj", kTriangle + "f 1 2 2147483648\n");  // INT32_MAX + 1 wrapped to a negative
  EXPECT_CONTAINS(errorOf([&] { loadModel(dir / "a.obj"); }), ":4: f: vertex index 2147483648 does not fit in 32 bits");
}

TEST(Obj, IndicesOutsideTheFileAreErrorsForVerticesTexcoordsAndNormalsAlike) {
  ScratchDir dir;
  const std::pair<std::string, std::string> cases[] = {
      {"f 1 2 4\n", ":4: f: vertex index 4 does not exist: the file has 3 v"},
      {"vn 0 0 1\nf 1//1 2//1 3//2\n", ":5: f: normal index 2 does not exist: the file has 1 vn"},
      {"f -1 -2 -4\n", ":4: f: vertex index -4 reaches before the first v (3 defined so far)"},
      {"f 1 2 0\n", ":4: f: vertex index 0 (OBJ indices start at 1)"},
      {"f 1 2 x\n", ":4: f: vertex index missing ('x' is not a number)"},
      {"f 1/ 2/ 3/\n", ":4: f: texcoord index missing"},
      {"l 1 7\n", ":4: l: vertex index 7 does not exist: the file has 3 v"},
  };
  for (const auto& [faces, expected] : cases) {
    testing::writeFile(dir / "a.obj", kTriangle + faces);
    EXPECT_CONTAINS(errorOf([&] { loadModel(dir / "a.obj"); }), dir / "a.obj" + expected);
  }
}

TEST(Obj, EveryValidIndexFormStillLoads) {
  // i, i/j, i//k, i/j/k, negative (relative) indices, and a face written before the vertices it names.
  ScratchDir dir;
  testing::writeFile(dir / "ok.obj",
                     "f 4 5 6\n" + kTriangle + "v 0 0 1\nv 1 0 1\nv 0 1 1\nvt 0 0\nvt 1 0\nvt 0 1\n" +
                         "vn 0 0 1\nf 1/1 2/2 3/3\nf 1//1 2//1 3//1\nf 1/1/1 2/2/1 3/3/1\nf -6 -5 -4\n" +
                         "f -3/-3/-1 -2/-2/-1 -1/-1/-1\n");
  EXPECT_EQ(loadModel(dir / "ok.obj").triangleCount(), 6u);
}

TEST(Obj, AMissingMtllibFileIsAnErrorNamingTheLine) {
  // tinyobjloader warned and went on with a default material.
  const std::string path = kHostileObj + "mtllib-missing.obj";
  EXPECT_CONTAINS(errorOf([&] { loadModel(path); }),
                  path + ":1: mtllib 'missing.mtl': material library '" + kHostileObj + "missing.mtl' does not exist");
  ScratchDir dir;
  std::filesystem::create_directories(dir.path / "lib.mtl");
  testing::writeFile(dir / "a.obj", "mtllib lib.mtl\n" + kTriangle + "f 1 2 3\n");
  EXPECT_CONTAINS(errorOf([&] { loadModel(dir / "a.obj"); }), "lib.mtl' is not a regular file");
  testing::writeFile(dir / "b.obj", "mtllib \n" + kTriangle + "f 1 2 3\n");
  EXPECT_CONTAINS(errorOf([&] { loadModel(dir / "b.obj"); }), dir / "b.obj" + ":1: mtllib names no file");
}

TEST(Obj, AnMtllibNamingTheObjItselfIsAnError) {
  // tinyobjloader read the OBJ as a material library, ignoring every line it did not know.
  const std::string path = kHostileObj + "mtllib-naming-itself.obj";
  EXPECT_CONTAINS(errorOf([&] { loadModel(path); }),
                  path + ":1: mtllib 'mtllib-naming-itself.obj' names this OBJ file itself, not a material library");
}

TEST(Obj, AMaterialLibraryThatIncludesItselfIsAnError) {
  const std::string path = kHostileObj + "mtllib-recursive.obj";
  EXPECT_CONTAINS(
      errorOf([&] { loadModel(path); }),
      kHostileObj + "recursive.mtl:3: mtllib inside a material library (an MTL file cannot include other files)");
}

TEST(Obj, AnMtllibListingTwoLibrariesLoadsBoth) {
  // tinyobjloader read only the first library of the statement, so `usemtl b` found no material.
  ScratchDir dir;
  testing::writeFile(dir / "a.mtl", "newmtl a\nKd 1 0 0\n");
  testing::writeFile(dir / "b.mtl", "newmtl b\nKd 0 0 1\n");
  testing::writeFile(dir / "two.obj", "mtllib a.mtl b.mtl\n" + kTriangle + "usemtl a\nf 1 2 3\nusemtl b\nf 3 2 1\n");
  const Model m = loadModel(dir / "two.obj");
  ASSERT_EQ(m.meshes.size(), 2u);
  EXPECT_EQ(m.materials[m.meshes[0].material].name, "a");
  EXPECT_EQ(m.materials[m.meshes[1].material].name, "b");
  EXPECT_EQ(m.materials[m.meshes[1].material].baseColorFactor[2], 1.0f);
}

TEST(Obj, AFaceOfManyCornersIsRefusedBeforeTriangulation) {
  // tinyobjloader's ear clipping takes about k^2 steps for a face of k corners: a million corners ran for hours.
  ScratchDir dir;
  std::string face = "f";
  for (int i = 0; i < 20000; ++i) face += i % 2 ? " 2" : " 1";  // 20,000 corners: 4e8 steps
  testing::writeFile(dir / "big.obj", kTriangle + face + "\n");
  EXPECT_CONTAINS(errorOf([&] { loadModel(dir / "big.obj"); }),
                  dir / "big.obj" +
                      ":4: f: a face of 20000 corners; triangulating the file's polygons would take more "
                      "than 268435456 steps");
}

TEST(Obj, TheTriangleBudgetIsCheckedBeforeTinyobjloaderReadsTheFaces) {
  ScratchDir dir;
  testing::writeFile(dir / "q.obj", kTriangle + "v 1 1 0\nf 1 2 4 3\nf 1 2 3\n");  // a quad (2) and a triangle
  ResourceLimits l;
  l.modelTriangles = 2;
  EXPECT_CONTAINS(
      errorOf([&] { loadModel(dir / "q.obj", l); }),
      dir / "q.obj" + ": needs 3 triangles, over the limit of 2 by 1 (raise it with --model-budget-triangles)");
  l.modelTriangles = 3;
  EXPECT_EQ(loadModel(dir / "q.obj", l).triangleCount(), 3u);
}

}  // namespace
}  // namespace tessera::model
