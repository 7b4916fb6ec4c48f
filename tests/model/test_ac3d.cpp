// The project's AC3D reader (model/load_ac3d.cpp, model/ac3d_file.h) on files written by the tests:
// what valid files give (the results Assimp gave before, worked out by hand here), the TORCS .acc variant,
// and hostile files, each an Error naming the file and line, found before anything is allocated for it.
#include <gtest/gtest.h>

#include <algorithm>

#include "base/error.h"
#include "model/loaders.h"
#include "model/model.h"
#include "model_test_util.h"

namespace tessera::model {
namespace {

using testing::errorOf;
using testing::ScratchDir;

const std::string kWhite =
    "MATERIAL \"white\" rgb 1 1 1  amb 0.2 0.2 0.2  emis 0 0 0  spec 0.5 0.5 0.5  shi 10  trans 0\n";

// Writes `text` as dir/name and loads it with the given limits.
Model load(const ScratchDir& dir, const std::string& name, const std::string& text, const ResourceLimits& limits = {}) {
  testing::writeFile(dir / name, text);
  return detail::loadAc3d(dir / name, limits);
}

std::string loadError(const ScratchDir& dir, const std::string& name, const std::string& text,
                      const ResourceLimits& limits = {}) {
  return errorOf([&] { load(dir, name, text, limits); });
}

// The (position, texcoord) corners of triangle t of `mesh`.
std::array<std::pair<glm::vec3, glm::vec2>, 3> triangleCorners(const Mesh& mesh, size_t t) {
  std::array<std::pair<glm::vec3, glm::vec2>, 3> c;
  for (size_t k = 0; k < 3; ++k) {
    const uint32_t i = mesh.indices[3 * t + k];
    c[k] = {mesh.positions[i], mesh.texcoords.empty() ? glm::vec2(0.0f) : mesh.texcoords[i]};
  }
  return c;
}

// A world with one poly: four vertices of the unit square, one SURF with `refs` (each "index u v").
// Lines: 1 header, 2 MATERIAL, 3-4 world, 5 OBJECT poly, 6 name, then `objectLines`; without them 7
// numvert, 8-11 vertices, 12 numsurf, 13 SURF, 14 mat, 15 refs, 16... the refs lines.
std::string square(const std::string& objectLines, const std::string& surf, const std::string& refs,
                   const std::string& mat = "0") {
  return "AC3Db\n" + kWhite + "OBJECT world\nkids 1\nOBJECT poly\nname \"sq\"\n" + objectLines +
         "numvert 4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\nnumsurf 1\nSURF " + surf + "\nmat " + mat + "\n" + refs + "kids 0\n";
}

TEST(Ac3d, AFileLoadsWithItsTextureAndRepeatedTexcoords) {
  ScratchDir dir;
  testing::writeChecker(dir / "wall.png", 4, 2);
  const Model m =
      load(dir, "wall.ac", square("texture \"wall.png\"\n", "0x10", "refs 4\n0 0 0\n1 3000 0\n2 3000 1\n3 0 1\n"));
  EXPECT_EQ(m.loader, "ac3d");
  ASSERT_EQ(m.meshes.size(), 1u);
  ASSERT_EQ(m.textures.size(), 1u);
  EXPECT_EQ(m.textures[0].uri, "wall.png");
  EXPECT_EQ(m.textures[0].path, dir / "wall.png");
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_EQ(m.materials[0].name, "white");
  EXPECT_EQ(m.materials[0].baseColorTexture, 0);
  EXPECT_FALSE(m.materials[0].doubleSided);
  // The quad is split along the diagonal from corner 0; v is flipped (v' = 1 - v), u is not clamped.
  const Mesh& mesh = m.meshes[0];
  ASSERT_EQ(mesh.triangleCount(), 2u);
  const auto a = triangleCorners(mesh, 0), b = triangleCorners(mesh, 1);
  EXPECT_EQ(a[0].first, glm::vec3(0, 0, 0));
  EXPECT_EQ(a[1].first, glm::vec3(1, 0, 0));
  EXPECT_EQ(a[2].first, glm::vec3(1, 1, 0));
  EXPECT_EQ(b[0].first, glm::vec3(0, 0, 0));
  EXPECT_EQ(b[1].first, glm::vec3(1, 1, 0));
  EXPECT_EQ(b[2].first, glm::vec3(0, 1, 0));
  EXPECT_EQ(a[1].second, glm::vec2(3000, 1));
  EXPECT_EQ(a[2].second, glm::vec2(3000, 0));
  EXPECT_EQ(b[2].second, glm::vec2(0, 0));
  EXPECT_TRUE(m.notes.empty());
  EXPECT_EQ(probeTexture(loadModel(dir / "wall.ac"), 0).height, 2u);
}

TEST(Ac3d, LoadModelChoosesThisReaderByContentAndByExtension) {
  ScratchDir dir;
  const std::string text = square("", "0x10", "refs 3\n0 0 0\n1 0 0\n2 0 0\n");
  testing::writeFile(dir / "no_extension", text);
  EXPECT_EQ(loadModel(dir / "no_extension").loader, "ac3d");
  testing::writeFile(dir / "car.acc", text);
  EXPECT_EQ(loadModel(dir / "car.acc").loader, "ac3d");
  testing::writeFile(dir / "fake.ac", "solid cube\n");
  EXPECT_CONTAINS(errorOf([&] { loadModel(dir / "fake.ac"); }), dir / "fake.ac" + ": not an AC3D file");
}

TEST(Ac3d, ASurfaceNamingAMissingMaterialIsAnErrorNotAnAbort) {
  ScratchDir dir;
  // Line 14 is "mat 77"; the file defines material 0 only.
  const std::string e = loadError(dir, "m.ac", square("", "0x10", "refs 3\n0 0 0\n1 0 0\n2 0 0\n", "77"));
  EXPECT_CONTAINS(e, dir / "m.ac" + ":14: mat 77 names a missing material: the file defines 1 (0 to 0)");
}

TEST(Ac3d, ARefsIndexPastNumvertIsAnError) {
  ScratchDir dir;
  const std::string e = loadError(dir, "r.ac", square("", "0x10", "refs 4\n0 0 0\n1 0 0\n99 0 0\n3 0 0\n"));
  EXPECT_CONTAINS(e, dir / "r.ac" + ":18: refs index 99 is past the 4 vertices of object 'sq' (line 5)");
}

TEST(Ac3d, TwentyThousandNestedKidsAreRefusedWithoutRecursion) {
  ScratchDir dir;
  // Group k (1-based) is on lines 3k - 1 to 3k + 1; each moves its kids by (1, 0, 0).
  std::string text = "AC3Db\n";
  const int depth = 20000;
  for (int k = 0; k < depth; ++k) text += "OBJECT group\nloc 1 0 0\nkids 1\n";
  text +=
      "OBJECT poly\nloc 0.5 0 0\nnumvert 3\n0 0 0\n1 0 0\n0 1 0\nnumsurf 1\nSURF 0\nrefs 3\n0 0 0\n1 0 0\n2 0 0\nkids "
      "0\n";
  // The 256th group may not have kids: they would be at depth 257. Its kids line is line 769.
  EXPECT_CONTAINS(loadError(dir, "deep.ac", text), dir / "deep.ac" + ":769: kids nest deeper than 256 levels");
  // With the limit raised, the chain is walked with the parser's own stack and the triangle comes out.
  ResourceLimits deep;
  deep.graphDepth = 30000;
  const Model m = load(dir, "deep.ac", text, deep);
  ASSERT_EQ(m.triangleCount(), 1u);
  EXPECT_EQ(m.meshes[0].positions[1], glm::vec3(20001.5f, 0, 0));  // 20000 + 0.5 + 1, exact in float
}

TEST(Ac3d, KidsTwoBillionIsRefusedBeforeAllocating) {
  ScratchDir dir;
  const std::string text = "AC3Db\nOBJECT world\nkids 2000000000\nOBJECT poly\nkids 0\n";
  EXPECT_CONTAINS(loadError(dir, "k.ac", text),
                  dir / "k.ac" + ":3: kids 2000000000 cannot fit in the 19 bytes that follow");
}

TEST(Ac3d, CountsLargerThanTheRestOfTheFileAreRefusedBeforeReserving) {
  ScratchDir dir;
  EXPECT_CONTAINS(loadError(dir, "v.ac", "AC3Db\nOBJECT poly\nnumvert 4000000000\n0 0 0\nkids 0\n"),
                  ":3: numvert 4000000000 cannot fit in the 13 bytes that follow");
  EXPECT_CONTAINS(loadError(dir, "s.ac", "AC3Db\nOBJECT poly\nnumsurf 99\nSURF 0\nkids 0\n"),
                  ":3: numsurf 99 cannot fit in the 14 bytes that follow");
  EXPECT_CONTAINS(loadError(dir, "r.ac", square("", "0", "refs 18446744073709551615\n0 0 0\n")),
                  ":15: refs 18446744073709551615 cannot fit");
  EXPECT_CONTAINS(loadError(dir, "d.ac", "AC3Db\nOBJECT poly\ndata 5000000000\nabc\nkids 0\n"),
                  ":3: data 5000000000 is longer than the 11 bytes that follow");
  EXPECT_CONTAINS(loadError(dir, "big.ac", "AC3Db\nOBJECT poly\nkids 99999999999999999999\n"),
                  ":3: kids 99999999999999999999 is too large");
}

TEST(Ac3d, NanAndInfinityAreErrorsNamingTheLine) {
  ScratchDir dir;
  EXPECT_CONTAINS(loadError(dir, "n.ac", square("loc 0 nan 0\n", "0", "refs 0\n")),
                  "n.ac:7: loc: 'nan' is not a finite number");
  EXPECT_CONTAINS(loadError(dir, "i.ac", square("", "0", "refs 1\n0 inf 0\n")),
                  "i.ac:16: u: 'inf' is not a finite number");
  EXPECT_CONTAINS(loadError(dir, "b.ac", square("texrep 1e39 1\n", "0", "refs 0\n")),
                  "b.ac:7: texrep: '1e39' is outside the range of a float");
  EXPECT_CONTAINS(loadError(dir, "x.ac", square("rot 1 0 0 0 1 0 0 0 one\n", "0", "refs 0\n")),
                  "x.ac:7: rot: 'one' is not a number");
}

TEST(Ac3d, ATruncatedFileIsAnErrorNamingWhereItEnds) {
  ScratchDir dir;
  const std::string full = square("", "0x10", "refs 3\n0 0 0\n1 0 0\n2 0 0\n");
  EXPECT_CONTAINS(loadError(dir, "t1.ac", full.substr(0, full.find("1 1 0"))),
                  "t1.ac:7: the file ends after 2 of these 4 vertices");
  EXPECT_CONTAINS(loadError(dir, "t2.ac", full.substr(0, full.find("kids 0"))),
                  "t2.ac:5: the file ends inside this OBJECT, before its kids line");
  EXPECT_CONTAINS(loadError(dir, "t3.ac", "AC3Db\nOBJECT world\nkids 2\nOBJECT poly\nkids 0\n"),
                  "t3.ac: the file ends before the last 1 kids of object '' (line 2)");
  EXPECT_CONTAINS(loadError(dir, "t4.ac", "AC3Db\nOBJECT poly\nnumsurf 1\nSURF 0x10\nmat 0\n"),
                  "t4.ac:4: the file ends inside this SURF, before its refs line");
  EXPECT_CONTAINS(loadError(dir, "t5.ac", "AC3Db\n"), "t5.ac: no OBJECT in the file");
  EXPECT_CONTAINS(loadError(dir, "t6.ac", "AC3Dx\nOBJECT world\n"), "t6.ac:1: the header needs a hex version digit");
  EXPECT_CONTAINS(loadError(dir, "t7.ac", "AC3Db\nOBJECT poly\nname \"open\nkids 0\n"),
                  "t7.ac:3: a string opened with \" is not closed on its line");
}

TEST(Ac3d, AMissingTextureNamesTheFileLineAndResolvedPath) {
  ScratchDir dir;
  EXPECT_CONTAINS(
      loadError(dir, "w.ac", square("texture \"tex\\missing.png\"\n", "0", "refs 3\n0 0 0\n1 0 0\n2 0 0\n")),
      dir / "w.ac" + ":7: texture of object 'sq': texture file '" + dir / "tex/missing.png" +
          "' (written as 'tex\\missing.png') does not exist");
}

TEST(Ac3d, TrianglesAndInstancesOverTheBudgetAreRefusedBeforeMeshesAreMade) {
  ScratchDir dir;
  const std::string text = square("", "0", "refs 4\n0 0 0\n1 0 0\n2 0 0\n3 0 0\n");
  ResourceLimits tight;
  tight.modelTriangles = 1;
  EXPECT_EQ(loadError(dir, "q.ac", text, tight),
            dir / "q.ac" + ": needs 2 triangles, over the limit of 1 by 1 (raise it with --model-budget-triangles)");
  std::string two = "AC3Db\nOBJECT world\nkids 2\n";
  for (int i = 0; i < 2; ++i)
    two += "OBJECT poly\nnumvert 3\n0 0 0\n1 0 0\n0 1 0\nnumsurf 1\nSURF 0\nrefs 3\n0\n1\n2\nkids 0\n";
  tight = {};
  tight.modelInstances = 1;
  EXPECT_EQ(
      loadError(dir, "two.ac", two, tight),
      dir / "two.ac" + ": needs 2 mesh instances, over the limit of 1 by 1 (raise it with --model-budget-instances)");
  EXPECT_EQ(load(dir, "two.ac", two).triangleCount(), 2u);
}

TEST(Ac3d, LocAndRotComposeDownTheKidsHierarchy) {
  ScratchDir dir;
  // The group turns by 90 degrees about z (rows 0 -1 0 / 1 0 0 / 0 0 1: (x, y) -> (-y, x)) and moves by
  // (10, 0, 0); the poly inside moves by (1, 0, 0) first, and so does the poly's own kid.
  // Vertex (1, 0, 0) of the poly: (2, 0, 0) -> (0, 2, 0) -> (10, 2, 0).
  // Vertex (0, 1, 0) of the kid: (1, 1, 0) in the poly, plus the kid's loc (0, 0, 5): (1, 1, 5) -> (9, 1, 5).
  const std::string tri = "numvert 3\n0 0 0\n1 0 0\n0 1 0\nnumsurf 1\nSURF 0\nmat 0\nrefs 3\n0 0 0\n1 0 0\n2 0 0\n";
  const Model m = load(dir, "h.ac",
                       "AC3Db\n" + kWhite + "OBJECT world\nkids 1\nOBJECT group\nrot 0 -1 0 1 0 0 0 0 1\nloc 10 0 0\n" +
                           "kids 1\nOBJECT poly\nname \"p\"\nloc 1 0 0\n" + tri +
                           "kids 1\nOBJECT poly\nname \"kid\"\n" + "loc 0 0 5\n" + tri + "kids 0\n");
  ASSERT_EQ(m.meshes.size(), 2u);
  EXPECT_EQ(m.meshes[0].name, "p");
  EXPECT_EQ(m.meshes[0].positions[0], glm::vec3(10, 1, 0));
  EXPECT_EQ(m.meshes[0].positions[1], glm::vec3(10, 2, 0));
  EXPECT_EQ(m.meshes[0].positions[2], glm::vec3(9, 1, 0));
  EXPECT_EQ(m.meshes[1].name, "kid");
  EXPECT_EQ(m.meshes[1].positions[2], glm::vec3(9, 1, 5));
}

TEST(Ac3d, AMirroringRotKeepsTrianglesCounterClockwise) {
  ScratchDir dir;
  // x -> -x turns the counter-clockwise triangle (0,0) (1,0) (0,1) clockwise; the loader swaps two corners.
  const Model m = load(dir, "mirror.ac", square("rot -1 0 0 0 1 0 0 0 1\n", "0", "refs 3\n0 0 0\n1 0 0\n3 0 0\n"));
  ASSERT_EQ(m.triangleCount(), 1u);
  const Mesh& mesh = m.meshes[0];
  const glm::vec3 a = mesh.positions[mesh.indices[0]], b = mesh.positions[mesh.indices[1]],
                  c = mesh.positions[mesh.indices[2]];
  EXPECT_EQ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x), 1.0f);  // twice the area, positive
}

TEST(Ac3d, TexrepAndTexoffScaleAndShiftTexcoordsBeforeVIsFlipped) {
  ScratchDir dir;
  testing::writeChecker(dir / "t.png", 2, 2);
  // u' = 0.5 * 2 + 0.5 = 1.5; v' = 0.5 * 4 + 0.25 = 2.25, stored as 1 - 2.25 = -1.25.
  const Model m =
      load(dir, "rep.ac",
           square("texture \"t.png\"\ntexrep 2 4\ntexoff 0.5 0.25\n", "0", "refs 3\n0 0.5 0.5\n1 0 0\n2 0 0\n"));
  ASSERT_EQ(m.meshes.size(), 1u);
  EXPECT_EQ(m.meshes[0].texcoords[0], glm::vec2(1.5f, -1.25f));
  EXPECT_EQ(m.meshes[0].texcoords[1], glm::vec2(0.5f, 0.75f));
}

TEST(Ac3d, LinesAreDroppedWithANoteAndTwoSidedSurfacesGetTheirOwnMaterial) {
  ScratchDir dir;
  const std::string text = "AC3Db\n" + kWhite +
                           "MATERIAL \"glass\" rgb 0.5 0.7 1  amb 0 0 0  emis 0 0 0  spec 0 0 0  shi 0  trans 0.25\n" +
                           "OBJECT poly\nnumvert 3\n0 0 0\n1 0 0\n0 1 0\nnumsurf 4\n" +
                           "SURF 0x1\nmat 0\nrefs 3\n0 0 0\n1 0 0\n2 0 0\n" +   // closed line
                           "SURF 0x2\nmat 0\nrefs 2\n0 0 0\n1 0 0\n" +          // line
                           "SURF 0x30\nmat 1\nrefs 3\n0 0 0\n1 0 0\n2 0 0\n" +  // shaded, two-sided
                           "SURF 0x10\nmat 1\nrefs 3\n0 0 0\n1 0 0\n2 0 0\n" +  // shaded
                           "kids 0\n";
  const Model m = load(dir, "l.ac", text);
  ASSERT_EQ(m.meshes.size(), 2u);
  ASSERT_EQ(m.materials.size(), 2u);
  // Meshes come in (material, two-sided) order: one-sided first.
  const Material& one = m.materials[m.meshes[0].material];
  const Material& two = m.materials[m.meshes[1].material];
  EXPECT_FALSE(one.doubleSided);
  EXPECT_TRUE(two.doubleSided);
  EXPECT_EQ(one.name, "glass");
  EXPECT_EQ(one.baseColorFactor, (std::array<float, 4>{0.5f, 0.7f, 1.0f, 0.75f}));  // alpha = 1 - trans
  EXPECT_EQ(one.alphaMode, AlphaMode::Blend);
  EXPECT_EQ(one.baseColorTexture, -1);
  EXPECT_TRUE(m.meshes[0].texcoords.empty());  // no texture, no texcoords
  EXPECT_NE(std::find(m.notes.begin(), m.notes.end(), "2 line surfaces dropped (closed and open lines)"),
            m.notes.end());
}

TEST(Ac3d, AConcavePolygonIsCutAlongItsInside) {
  ScratchDir dir;
  // An L: the square [0,2]^2 without [1,2]^2, area 3; corner 3 (1, 1) is reflex. Every triangle must be
  // counter-clockwise, and their areas must add up to 3 (a triangle across the notch would exceed it).
  const std::string text = "AC3Db\n" + kWhite +
                           "OBJECT poly\nnumvert 6\n0 0 0\n2 0 0\n2 1 0\n1 1 0\n1 2 0\n0 2 0\nnumsurf 1\nSURF 0\n"
                           "mat 0\nrefs 6\n0 0 0\n1 0 0\n2 0 0\n3 0 0\n4 0 0\n5 0 0\nkids 0\n";
  const Model m = load(dir, "l.ac", text);
  ASSERT_EQ(m.triangleCount(), 4u);
  float sum = 0;
  for (size_t t = 0; t < 4; ++t) {
    const auto c = triangleCorners(m.meshes[0], t);
    const float a = (c[1].first.x - c[0].first.x) * (c[2].first.y - c[0].first.y) -
                    (c[1].first.y - c[0].first.y) * (c[2].first.x - c[0].first.x);
    EXPECT_GT(a, 0.0f);
    sum += a;
  }
  EXPECT_EQ(sum, 6.0f);
}

TEST(Ac3d, ATorcsAccFileUsesItsBaseTexture) {
  ScratchDir dir;
  testing::writeChecker(dir / "base.png", 2, 2);
  // The layers' images do not exist: they are not read. Refs carry one u v pair per layer, the first
  // is the base's; vertex lines carry normals; SURF 0x14 is a triangle strip.
  const std::string text =
      "AC3Db\n" + kWhite +
      "OBJECT world\nkids 1\nOBJECT poly\nname \"car\"\ntexture \"base.png\" base\ntexture \"tiled.png\" tiled\n"
      "texture empty_texture_no_mapping skids\ntexture \"shad.png\" shad\n"
      "numvert 4\n0 0 0 0 0 2\n1 0 0 0 0 2\n0 1 0 0 0 2\n1 1 0 0 0 2\nnumsurf 1\nSURF 0x14\nmat 0\nrefs 4\n"
      "0 0 0 5 5 6 6\n1 1 0 5 5 6 6\n2 0 1 5 5 6 6\n3 1 1 5 5 6 6\nkids 0\n";
  const Model m = load(dir, "car.acc", text);
  ASSERT_EQ(m.textures.size(), 1u);
  EXPECT_EQ(m.textures[0].uri, "base.png");
  ASSERT_EQ(m.meshes.size(), 1u);
  const Mesh& mesh = m.meshes[0];
  // The strip gives (0, 1, 2) and, odd, (2, 1, 3): both counter-clockwise.
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 2, 1, 3}));
  EXPECT_EQ(mesh.texcoords[3], glm::vec2(1, 0));   // (1, 1) of the base layer, v flipped
  EXPECT_EQ(mesh.normals[0], glm::vec3(0, 0, 2));  // as the file gives it: no transform applies
  EXPECT_NE(std::find(m.notes.begin(), m.notes.end(),
                      "3 TORCS texture layers (tiled, skids, shad) ignored: the base texture is used"),
            m.notes.end());
}

// A TORCS track object (the syntax of grloadac.cpp / accc): a base texture and a tiled layer, so every
// refs line holds two u v pairs; the second pair is the layer's and must not reach the texcoords.
std::string accTrack(const std::string& base) {
  return "AC3Db\n" + kWhite + "OBJECT world\nkids 1\nOBJECT poly\nname \"road\"\ntexture \"" + base +
         "\" base\ntexture \"tiled.png\" tiled\ntexture empty_texture_no_mapping skids\n"
         "numvert 3\n0 0 0\n4 0 0\n0 4 0\nnumsurf 1\nSURF 0x10\nmat 0\nrefs 3\n"
         "0 0.25 0.5 9 9\n1 0.75 0.5 9 9\n2 0.25 1 9 9\nkids 0\n";
}

TEST(Ac3d, AnAccTrackUsesTheFirstUvPairOfEachRefForItsBaseTextureAndIgnoresTheLayerPairs) {
  ScratchDir dir;
  testing::writeChecker(dir / "asphalt.png", 2, 2);
  const Model m = load(dir, "track.acc", accTrack("asphalt.png"));  // tiled.png does not exist: never read
  ASSERT_EQ(m.textures.size(), 1u);
  EXPECT_EQ(m.textures[0].uri, "asphalt.png");
  ASSERT_EQ(m.meshes.size(), 1u);
  EXPECT_EQ(m.materials[m.meshes[0].material].baseColorTexture, 0);
  // Hand-derived: the base pairs (0.25, 0.5), (0.75, 0.5), (0.25, 1) with v flipped; no 9 anywhere.
  EXPECT_EQ(m.meshes[0].texcoords,
            (std::vector<glm::vec2>{glm::vec2(0.25f, 0.5f), glm::vec2(0.75f, 0.5f), glm::vec2(0.25f, 0.0f)}));
}

TEST(Ac3d, AnAccTrackWithAMissingBaseTextureNamesTheFileAndTheLineOfItsBaseTexture) {
  ScratchDir dir;
  EXPECT_EQ(loadError(dir, "track.acc", accTrack("missing.png")),
            dir / "track.acc" + ":7: texture of object 'road': texture file '" + dir / "missing.png" +
                "' (written as 'missing.png') does not exist");
}

TEST(Ac3d, AnAccRefsLineWithHalfAUvPairIsAnErrorNamingItsLine) {
  ScratchDir dir;
  std::string text = accTrack("asphalt.png");
  text.replace(text.find("1 0.75 0.5 9 9"), 14, "1 0.75 0.5 9");
  EXPECT_EQ(loadError(dir, "track.acc", text),
            dir / "track.acc" + ":19: a refs line holds a vertex index and u v pairs, not 4 numbers");
}

TEST(Ac3d, Ac3dcTokensAreReadAndUnknownOnesAreSkippedWithANote) {
  ScratchDir dir;
  const std::string text =
      "AC3Dc\nMAT \"m\"\nrgb 0.25 0.5 1\namb 0 0 0\ndata 8\nline\ntwo\nENDMAT\nOBJECT world\n"
      "name \"w\"\ncrease 30.0\nsubdiv 2\nhidden\nfolded\nlocked\nurl \"http://x\"\n"
      "data 4\nkids\nshininess 3\nshininess 4\nnumvert 3\n0 0 0\n1 0 0\n0 1 0\nnumsurf 1\nSURF 0x10\n"
      "refs 3\n0 0 0\n1 0 0\n2 0 0\nkids 0\n";
  const Model m = load(dir, "c.ac", text);
  ASSERT_EQ(m.triangleCount(), 1u);  // the "kids" inside the data section was skipped with it
  EXPECT_EQ(m.materials[0].baseColorFactor, (std::array<float, 4>{0.25f, 0.5f, 1.0f, 1.0f}));
  EXPECT_NE(
      std::find(m.notes.begin(), m.notes.end(), "unknown token 'shininess' skipped on 2 line(s), the first at line 19"),
      m.notes.end());
  EXPECT_NE(
      std::find(m.notes.begin(), m.notes.end(), "1 objects with subdiv > 0: the control mesh is kept, not subdivided"),
      m.notes.end());
}

TEST(Ac3d, AnObjectWithoutItsKidsLineIsAnError) {
  ScratchDir dir;
  EXPECT_CONTAINS(loadError(dir, "k.ac", "AC3Db\nOBJECT world\nname \"w\"\nOBJECT poly\nkids 0\n"),
                  "k.ac:2: this OBJECT has no kids line before the OBJECT at line 4");
}

}  // namespace
}  // namespace tessera::model
