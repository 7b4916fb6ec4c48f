// Scene-graph objects on model::Mesh (Mesh::object, Model::objects) for every loader, and RTTA's
// object groupings (model/object_groups.h): one object per mesh, or one per node instance.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "model/city_gen.h"
#include "model/model.h"
#include "model/object_groups.h"
#include "model_test_util.h"

namespace tessera::model {
namespace {

using testing::ScratchDir;

std::vector<uint32_t> meshObjects(const Model& m) {
  std::vector<uint32_t> o;
  for (const Mesh& mesh : m.meshes) o.push_back(mesh.object);
  return o;
}

std::vector<std::vector<uint32_t>> groupMeshes(const std::vector<ObjectGroup>& g) {
  std::vector<std::vector<uint32_t>> out;
  for (const ObjectGroup& x : g) out.push_back(x.meshes);
  return out;
}

TEST(ObjectGroups, RailwayIsThirtyThreeMeshObjectsAndOneNodeObject) {
  // data/railway.glb has one node (index 0, no name) whose one mesh has 33 primitives.
  const Model m = loadModel(TESSERA_SOURCE_DIR "/data/railway.glb");
  ASSERT_EQ(m.meshes.size(), 33u);
  ASSERT_EQ(m.objects.size(), 1u);
  EXPECT_EQ(m.objects[0].node, 0);
  EXPECT_EQ(m.objects[0].instance, 0u);
  EXPECT_EQ(m.objects[0].name, "node0");
  EXPECT_EQ(meshObjects(m), std::vector<uint32_t>(33, 0));
  const std::vector<ObjectGroup> byMesh = groupObjects(m, ObjectGrouping::Mesh);
  ASSERT_EQ(byMesh.size(), 33u);
  for (uint32_t i = 0; i < 33; ++i) EXPECT_EQ(byMesh[i].meshes, std::vector<uint32_t>{i});
  const std::vector<ObjectGroup> byNode = groupObjects(m, ObjectGrouping::Node);
  ASSERT_EQ(byNode.size(), 1u);
  EXPECT_EQ(byNode[0].name, "node0");
  EXPECT_EQ(byNode[0].meshes.size(), 33u);
  EXPECT_EQ(byNode[0].meshes.front(), 0u);
  EXPECT_EQ(byNode[0].meshes.back(), 32u);
}

TEST(ObjectGroups, AGltfNodeReachedTwiceIsTwoObjectsWithOneNodeIndex) {
  ScratchDir dir;
  std::string bin;
  testing::appendBytes(bin, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  // Scene roots 0 and 4; 0 -> 1 -> 3 and 0 -> 2 -> 3: node 3 ("shared", mesh 0 with two primitives)
  // is reached twice, node 4 (no name, mesh 1 with one primitive) once; nodes 0-2 have no mesh.
  const nlohmann::json prim = {{"attributes", {{"POSITION", 0}}}};
  const nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"buffers",
       {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + testing::base64(bin)}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteLength", 36}}}},
      {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}}}},
      {"meshes", {{{"primitives", {prim, prim}}}, {{"primitives", {prim}}}}},
      {"nodes",
       {{{"children", {1, 2}}},
        {{"name", "a"}, {"children", {3}}},
        {{"children", {3}}, {"translation", {5, 0, 0}}},
        {{"name", "shared"}, {"mesh", 0}},
        {{"mesh", 1}}}},
      {"scenes", {{{"nodes", {0, 4}}}}}};
  testing::writeFile(dir / "twice.gltf", j.dump());
  const Model m = loadModel(dir / "twice.gltf");
  ASSERT_EQ(m.meshes.size(), 5u);
  ASSERT_EQ(m.objects.size(), 3u);
  EXPECT_EQ(m.objects[0].name, "shared");
  EXPECT_EQ(m.objects[0].node, 3);
  EXPECT_EQ(m.objects[0].instance, 0u);
  EXPECT_EQ(m.objects[1].name, "shared");
  EXPECT_EQ(m.objects[1].node, 3);
  EXPECT_EQ(m.objects[1].instance, 1u);
  EXPECT_EQ(m.objects[2].name, "node4");
  EXPECT_EQ(m.objects[2].node, 4);
  EXPECT_EQ(m.objects[2].instance, 0u);
  EXPECT_EQ(meshObjects(m), (std::vector<uint32_t>{0, 0, 1, 1, 2}));
  EXPECT_EQ(m.meshes[2].positions[0].x, 5.0f);  // the second instance is the translated one
  EXPECT_EQ(groupMeshes(groupObjects(m, ObjectGrouping::Node)),
            (std::vector<std::vector<uint32_t>>{{0, 1}, {2, 3}, {4}}));
  EXPECT_EQ(groupObjects(m, ObjectGrouping::Mesh).size(), 5u);
}

TEST(ObjectGroups, ObjShapesFromOAndGStatementsAreTheObjects) {
  ScratchDir dir;
  testing::writeFile(dir / "m.mtl", "newmtl red\nKd 1 0 0\nnewmtl green\nKd 0 1 0\n");
  // Shape "first" uses two materials (two meshes, one object); shape "second" one.
  testing::writeFile(dir / "m.obj",
                     "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\no first\nusemtl red\nf 1 2 3\nusemtl green\nf 1 3 2\n"
                     "g second\nusemtl red\nf 1 2 3\n");
  const Model m = loadModel(dir / "m.obj");
  ASSERT_EQ(m.meshes.size(), 3u);
  ASSERT_EQ(m.objects.size(), 2u);
  EXPECT_EQ(m.objects[0].name, "first");
  EXPECT_EQ(m.objects[0].node, 0);
  EXPECT_EQ(m.objects[1].name, "second");
  EXPECT_EQ(m.objects[1].node, 1);
  EXPECT_EQ(meshObjects(m), (std::vector<uint32_t>{0, 0, 1}));
  EXPECT_EQ(groupMeshes(groupObjects(m, ObjectGrouping::Node)), (std::vector<std::vector<uint32_t>>{{0, 1}, {2}}));
}

TEST(ObjectGroups, Ac3dObjectsWithTrianglesAreTheObjectsInFileOrder) {
  ScratchDir dir;
  // Objects in file order: 0 world, 1 group "g" (no surfaces), 2 poly "two" (two materials), 3 poly
  // without a name.
  const std::string tri = "numvert 3\n0 0 0\n1 0 0\n0 1 0\n";
  const std::string text =
      "AC3Db\nMATERIAL \"a\" rgb 1 1 1 amb 0 0 0 emis 0 0 0 spec 0 0 0 shi 0 trans 0\n"
      "MATERIAL \"b\" rgb 1 0 0 amb 0 0 0 emis 0 0 0 spec 0 0 0 shi 0 trans 0\n"
      "OBJECT world\nkids 2\nOBJECT group\nname \"g\"\nkids 1\nOBJECT poly\nname \"two\"\n" +
      tri +
      "numsurf 2\nSURF 0\nmat 0\nrefs 3\n0 0 0\n1 0 0\n2 0 0\nSURF 0\nmat 1\nrefs 3\n"
      "0 0 0\n2 0 0\n1 0 0\nkids 0\nOBJECT poly\n" +
      tri + "numsurf 1\nSURF 0\nmat 0\nrefs 3\n0 0 0\n1 0 0\n2 0 0\nkids 0\n";
  testing::writeFile(dir / "m.ac", text);
  const Model m = loadModel(dir / "m.ac");
  ASSERT_EQ(m.meshes.size(), 3u);
  ASSERT_EQ(m.objects.size(), 2u);
  EXPECT_EQ(m.objects[0].name, "two");
  EXPECT_EQ(m.objects[0].node, 2);
  EXPECT_EQ(m.objects[1].name, "object3");
  EXPECT_EQ(m.objects[1].node, 3);
  EXPECT_EQ(meshObjects(m), (std::vector<uint32_t>{0, 0, 1}));
}

TEST(ObjectGroups, AssimpNodesAreNumberedInDepthFirstPreOrderFromTheRoot) {
  ScratchDir dir;
  // The visual scene is Assimp's root node (ordinal 0); "outer" (1) instances the triangle and holds
  // "inner" (2), which instances it again; "empty" (3) has no geometry.
  testing::writeFile(dir / "two.dae", R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Y_UP</up_axis></asset>
  <library_geometries><geometry id="geo0" name="tri"><mesh>
    <source id="pos"><float_array id="pos-arr" count="9">0 0 0 1 0 0 0 1 0</float_array>
      <technique_common><accessor source="#pos-arr" count="3" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <vertices id="verts"><input semantic="POSITION" source="#pos"/></vertices>
    <triangles count="1"><input semantic="VERTEX" source="#verts" offset="0"/><p>0 1 2</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="scene" name="scene">
    <node id="outer" name="outer"><instance_geometry url="#geo0"/>
      <node id="inner" name="inner"><translate>0 0 5</translate><instance_geometry url="#geo0"/></node>
    </node>
    <node id="empty" name="empty"/>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
)");
  const Model m = loadModel(dir / "two.dae");
  ASSERT_EQ(m.meshes.size(), 2u);
  ASSERT_EQ(m.objects.size(), 2u);
  EXPECT_EQ(m.objects[0].name, "outer");
  EXPECT_EQ(m.objects[0].node, 1);
  EXPECT_EQ(m.objects[1].name, "inner");
  EXPECT_EQ(m.objects[1].node, 2);
  EXPECT_EQ(meshObjects(m), (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(m.meshes[1].positions[0].z, 5.0f);
}

TEST(ObjectGroups, SmallBerlinIsOneNodeObjectPerBuildingPlusTheGround) {
  ScratchDir dir;
  CityOptions o;
  o.buildings = 4;
  o.textureSize = 16;
  o.outDir = dir / "out";
  o.progress = false;
  const Model m = loadModel(generateCity(o).gltf);
  // Node 0 "berlin" (no mesh) holds buildings 1-4 (a facade and a roof primitive each) and the ground
  // (node 5: lot and street primitives).
  ASSERT_EQ(m.meshes.size(), 10u);
  const std::vector<ObjectGroup> g = groupObjects(m, ObjectGrouping::Node);
  ASSERT_EQ(g.size(), 5u);
  for (uint32_t i = 0; i < 4; ++i) {
    EXPECT_EQ(g[i].name, "building_" + std::to_string(i));
    EXPECT_EQ(g[i].meshes, (std::vector<uint32_t>{2 * i, 2 * i + 1}));
    EXPECT_EQ(m.objects[i].node, int32_t(i + 1));
  }
  EXPECT_EQ(g[4].name, "ground");
  EXPECT_EQ(g[4].meshes, (std::vector<uint32_t>{8, 9}));
  EXPECT_EQ(groupObjects(m, ObjectGrouping::Mesh).size(), 10u);
}

TEST(ObjectGroups, AModelBuiltInCodeWithoutObjectsIsOneNodeObject) {
  Model m;
  m.meshes.resize(3);
  const std::vector<ObjectGroup> g = groupObjects(m, ObjectGrouping::Node);
  ASSERT_EQ(g.size(), 1u);
  EXPECT_EQ(g[0].name, "object0");
  EXPECT_EQ(g[0].meshes, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_EQ(groupObjects(Model{}, ObjectGrouping::Node).size(), 0u);
  m.objects.resize(1);
  m.meshes[1].object = 1;
  m.source = "built.gltf";
  EXPECT_CONTAINS(testing::errorOf([&] { groupObjects(m, ObjectGrouping::Node); }),
                  "built.gltf: mesh 1 names object 1 of 1");
}

TEST(ObjectGroups, GroupingNamesParseAndUnknownOnesAreErrors) {
  EXPECT_EQ(parseObjectGrouping("mesh"), ObjectGrouping::Mesh);
  EXPECT_EQ(parseObjectGrouping("node"), ObjectGrouping::Node);
  EXPECT_STREQ(objectGroupingName(ObjectGrouping::Node), "node");
  EXPECT_CONTAINS(testing::errorOf([] { parseObjectGrouping("nodes"); }), "--objects 'nodes': expected mesh or node");
}

}  // namespace
}  // namespace tessera::model

namespace tessera::model {
namespace {

struct Counts {
  size_t objects = 0, vertices = 0, faces = 0;
};

Counts tableOneCounts(const testing::ScratchDir& dir, CityPreset preset, uint32_t buildings) {
  CityOptions o;
  o.preset = preset;
  o.buildings = buildings;
  o.textureSize = 16;  // texture sizes never change the geometry
  o.outDir = dir / cityPresetName(preset);
  o.progress = false;
  const Model m = loadModel(generateCity(o).gltf);
  Counts c{.objects = groupObjects(m, ObjectGrouping::Node).size()};
  for (const Mesh& mesh : m.meshes) c.vertices += mesh.positions.size(), c.faces += mesh.triangleCount();
  return c;
}

// docs/model-import.md "RTTA inputs": the cities of Table 1's first two rows (#Obj 5 and 21).
TEST(RttaTableOne, BerlinWithFourAndTwentyBuildingsHasFiveAndTwentyOneNodeObjects) {
  testing::ScratchDir dir;
  // Per building 4 wall quads and a roof quad (20 vertices, 10 triangles); per cell of the g x g grid
  // (g = ceil(sqrt(N))) a lot quad and two street quads (12 vertices, 6 triangles).
  const Counts five = tableOneCounts(dir, CityPreset::Berlin, 4);  // g = 2
  EXPECT_EQ(five.objects, 5u);
  EXPECT_EQ(five.vertices, 20u * 4 + 12u * 4);
  EXPECT_EQ(five.faces, 10u * 4 + 6u * 4);
  const Counts twentyOne = tableOneCounts(dir, CityPreset::Berlin, 20);  // g = 5
  EXPECT_EQ(twentyOne.objects, 21u);
  EXPECT_EQ(twentyOne.vertices, 20u * 20 + 12u * 25);
  EXPECT_EQ(twentyOne.faces, 10u * 20 + 6u * 25);
}

TEST(RttaTableOne, ChemnitzWithFourAndTwentyBuildingsHasFiveAndTwentyOneNodeObjects) {
  testing::ScratchDir dir;
  // Block nodes have no mesh: the objects are the buildings and the ground.
  EXPECT_EQ(tableOneCounts(dir, CityPreset::Chemnitz, 4).objects, 5u);
  EXPECT_EQ(tableOneCounts(dir, CityPreset::Chemnitz, 20).objects, 21u);
}

}  // namespace
}  // namespace tessera::model
