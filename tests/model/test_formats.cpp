// Each loader on a small file written by the test: glTF 2.0 features (data: URIs, external images,
// strips, fans, normalized texcoords, KHR_texture_transform, node TRS), OBJ + MTL, COLLADA through
// Assimp (AC3D has its own reader: test_ac3d.cpp). Texcoords far outside [0, 1] must come through
// unclamped.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <nlohmann/json.hpp>

#include "model/model.h"
#include "model_test_util.h"

namespace tessera::model {
namespace {

using testing::ScratchDir;

using testing::hasTexcoord;

// A glTF 2.0 file exercising what real exports use, written beside checker.png.
std::string writeFeatureGltf(const ScratchDir& dir) {
  testing::writeChecker(dir / "checker.png", 4, 4);
  testing::writeChecker(dir / "embedded.png", 2, 2, 128);
  std::string bin;
  testing::appendBytes(bin, std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});         // 0: 48 bytes
  testing::appendBytes(bin, std::vector<uint16_t>{0, 0, 65535, 0, 0, 32768, 65535, 65535});  // 48: 16 bytes
  testing::appendBytes(bin, std::vector<float>{0, 0, 3000, 0, 3000, 2, 0, 2});               // 64: 32 bytes
  testing::appendBytes(bin, std::vector<uint8_t>{0, 1, 3, 2});                               // 96: 4 bytes
  nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"KHR_texture_transform"}},
      {"buffers",
       {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + testing::base64(bin)}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 16}},
        {{"buffer", 0}, {"byteOffset", 64}, {"byteLength", 32}},
        {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 4}}}},
      {"accessors",
       {{{"bufferView", 0},
         {"componentType", 5126},
         {"count", 4},
         {"type", "VEC3"},
         {"min", {0, 0, 0}},
         {"max", {1, 1, 0}}},
        {{"bufferView", 1}, {"componentType", 5123}, {"normalized", true}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 3}, {"componentType", 5121}, {"count", 4}, {"type", "SCALAR"}}}},
      {"images",
       {{{"uri", "checker.png"}},
        {{"uri", "data:image/png;base64," + testing::base64(testing::readFile(dir / "embedded.png"))}}}},
      {"samplers", {{{"wrapS", 33071}, {"wrapT", 33648}}}},
      {"textures", {{{"source", 0}, {"sampler", 0}}, {{"source", 1}}}},
      {"materials",
       {{{"name", "strip"},
         {"alphaMode", "MASK"},
         {"alphaCutoff", 0.25},
         {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}},
        {{"name", "fan"},
         {"alphaMode", "BLEND"},
         {"doubleSided", true},
         {"pbrMetallicRoughness",
          {{"baseColorFactor", {0.5, 0.25, 1.0, 0.75}},
           {"baseColorTexture",
            {{"index", 1},
             {"texCoord", 1},
             {"extensions",
              {{"KHR_texture_transform", {{"offset", {0.5, 0.0}}, {"scale", {2.0, 2.0}}, {"texCoord", 0}}}}}}}}}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"mode", 5}, {"material", 0}},
           {{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 2}, {"TEXCOORD_1", 1}}},
            {"indices", 3},
            {"mode", 6},
            {"material", 1}},
           {{"attributes", {{"POSITION", 0}}}, {"mode", 1}}}}}}},
      {"nodes", {{{"translation", {10.0, 0.0, 0.0}}, {"children", {1}}}, {{"scale", {2.0, 2.0, 2.0}}, {"mesh", 0}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0}};
  const std::string path = dir / "features.gltf";
  testing::writeFile(path, j.dump(1));
  return path;
}

TEST(GltfLoader, StripsFansNormalizedTexcoordsTextureTransformAndNodeTransformsAreApplied) {
  ScratchDir dir;
  const Model m = loadModel(writeFeatureGltf(dir));
  ASSERT_EQ(m.meshes.size(), 2u);  // the lines primitive is dropped with a note
  EXPECT_TRUE(std::any_of(m.notes.begin(), m.notes.end(),
                          [](const std::string& n) { return n.find("lines") != std::string::npos; }));
  const Mesh &strip = m.meshes[0], &fan = m.meshes[1];
  EXPECT_EQ(strip.triangleCount(), 2u);
  EXPECT_EQ(fan.triangleCount(), 2u);
  // Strip triangle 1 is (2, 1, 3): odd strip triangles swap their first two vertices.
  EXPECT_EQ(strip.indices, (std::vector<uint32_t>{0, 1, 2, 2, 1, 3}));
  EXPECT_EQ(fan.indices, (std::vector<uint32_t>{0, 1, 3, 0, 3, 2}));
  // Node 0 translates by 10 in x, node 1 scales by 2.
  EXPECT_EQ(strip.positions[3].x, 12.0f);
  EXPECT_EQ(strip.positions[3].y, 2.0f);
  // Normalized ushort texcoords: 32768 / 65535.
  EXPECT_EQ(strip.texcoords[2].y, 32768.0f / 65535.0f);
  // KHR_texture_transform on TEXCOORD_0 (the extension's texCoord overrides the textureInfo's 1):
  // u' = 2u + 0.5, v' = 2v.
  EXPECT_TRUE(hasTexcoord(fan, 6000.5f, 4.0f));
  EXPECT_TRUE(hasTexcoord(fan, 0.5f, 0.0f));
  const Material &ms = m.materials[0], &mf = m.materials[1];
  EXPECT_EQ(ms.alphaMode, AlphaMode::Mask);
  EXPECT_EQ(ms.alphaCutoff, 0.25f);
  EXPECT_EQ(ms.wrapS, Wrap::ClampToEdge);
  EXPECT_EQ(ms.wrapT, Wrap::MirroredRepeat);
  EXPECT_EQ(mf.alphaMode, AlphaMode::Blend);
  EXPECT_TRUE(mf.doubleSided);
  EXPECT_EQ(mf.baseColorFactor[3], 0.75f);
  ASSERT_EQ(m.textures.size(), 2u);
  EXPECT_EQ(m.textures[0].source, TextureRef::Source::File);
  EXPECT_EQ(m.textures[1].source, TextureRef::Source::Memory);
  const Image external = loadTexture(m, 0), embedded = loadTexture(m, 1);
  EXPECT_EQ(external.width, 4u);
  EXPECT_FALSE(external.usesAlpha);
  EXPECT_EQ(embedded.width, 2u);
  EXPECT_TRUE(embedded.usesAlpha);
  // Rows are in file order: texel (1, 0) of the file is blue with alpha 128.
  EXPECT_EQ(embedded.rgba[4 + 2], 255);
  EXPECT_EQ(embedded.rgba[4 + 3], 128);
  EXPECT_EQ(probeTexture(m, 1).width, 2u);
}

TEST(ObjLoader, ObjWithMtlLoadsItsTextureAndKeepsLargeTexcoords) {
  ScratchDir dir;
  std::filesystem::create_directories(dir.path / "tex");
  testing::writeChecker(dir / "tex/brick.png", 4, 4);
  testing::writeFile(dir / "quad.mtl",
                     "newmtl brick\nKd 0.8 0.7 0.6\nmap_Kd tex/brick.png\n\n"
                     "newmtl scaled\nKd 1 1 1\nd 0.5\nmap_Kd -s 2 3 1 tex/brick.png\n");
  testing::writeFile(dir / "quad.obj",
                     "mtllib quad.mtl\n"
                     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1.5 0\n"
                     "vt 0 0\nvt 1500 0\nvt 1500 0.25\nvt 0 0.25\nvt 0.5 -2000\n"
                     "vn 0 0 1\n"
                     "usemtl brick\nf 1/1/1 2/2/1 3/3/1 4/4/1\nf 4/4/1 3/3/1 5/5/1\n"
                     "usemtl scaled\nf 1/1/1 2/2/1 3/3/1\n");
  const Model m = loadModel(dir / "quad.obj");
  EXPECT_EQ(m.loader, "obj");
  ASSERT_EQ(m.meshes.size(), 2u);
  EXPECT_EQ(m.meshes[0].triangleCount(), 3u);  // the quad is triangulated
  EXPECT_EQ(m.meshes[1].triangleCount(), 1u);
  ASSERT_EQ(m.textures.size(), 1u);  // both materials use one image
  EXPECT_EQ(std::filesystem::path(m.textures[0].path), std::filesystem::path(dir / "tex/brick.png"));
  // v is flipped to the glTF convention; u and v are not wrapped.
  EXPECT_TRUE(hasTexcoord(m.meshes[0], 1500.0f, 0.75f));
  EXPECT_TRUE(hasTexcoord(m.meshes[0], 0.5f, 2001.0f));
  // -s 2 3: u * 2, v * 3, then v flipped.
  EXPECT_TRUE(hasTexcoord(m.meshes[1], 3000.0f, 0.25f));
  EXPECT_EQ(m.materials[m.meshes[1].material].alphaMode, AlphaMode::Blend);
  EXPECT_EQ(m.materials[m.meshes[0].material].baseColorFactor[0], 0.8f);
  ASSERT_EQ(m.meshes[0].normals.size(), m.meshes[0].positions.size());
  const Image img = loadTexture(m, 0);
  EXPECT_EQ(img.width, 4u);
  EXPECT_EQ(img.rgba[0], 255);  // texel (0, 0) is red
}

TEST(AssimpLoader, ColladaFileLoadsWithItsPercentEncodedTextureAndNodeTranslation) {
  ScratchDir dir;
  std::filesystem::create_directories(dir.path / "tex");
  testing::writeChecker(dir / "tex/brick wall.png", 8, 8);
  testing::writeFile(dir / "quad.dae", R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Y_UP</up_axis></asset>
  <library_images><image id="img0"><init_from>tex/brick%20wall.png</init_from></image></library_images>
  <library_effects><effect id="fx0"><profile_COMMON>
    <newparam sid="surf"><surface type="2D"><init_from>img0</init_from></surface></newparam>
    <newparam sid="samp"><sampler2D><source>surf</source></sampler2D></newparam>
    <technique sid="common"><lambert><diffuse><texture texture="samp" texcoord="UV0"/></diffuse></lambert></technique>
  </profile_COMMON></effect></library_effects>
  <library_materials><material id="mat0" name="brick"><instance_effect url="#fx0"/></material></library_materials>
  <library_geometries><geometry id="geo0" name="quad"><mesh>
    <source id="pos"><float_array id="pos-arr" count="12">0 0 0 1 0 0 1 1 0 0 1 0</float_array>
      <technique_common><accessor source="#pos-arr" count="4" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <source id="uv"><float_array id="uv-arr" count="8">0 0 2500 0 2500 3 0 3</float_array>
      <technique_common><accessor source="#uv-arr" count="4" stride="2">
        <param name="S" type="float"/><param name="T" type="float"/></accessor></technique_common></source>
    <vertices id="verts"><input semantic="POSITION" source="#pos"/></vertices>
    <triangles material="m" count="2">
      <input semantic="VERTEX" source="#verts" offset="0"/>
      <input semantic="TEXCOORD" source="#uv" offset="1" set="0"/>
      <p>0 0 1 1 2 2 0 0 2 2 3 3</p>
    </triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="scene"><node id="n0"><translate>0 0 5</translate>
    <instance_geometry url="#geo0"><bind_material><technique_common>
      <instance_material symbol="m" target="#mat0">
        <bind_vertex_input semantic="UV0" input_semantic="TEXCOORD" input_set="0"/>
      </instance_material>
    </technique_common></bind_material></instance_geometry></node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
)");
  const Model m = loadModel(dir / "quad.dae");
  EXPECT_EQ(m.loader, "assimp:dae");
  EXPECT_EQ(m.triangleCount(), 2u);
  ASSERT_EQ(m.textures.size(), 1u);
  EXPECT_EQ(std::filesystem::path(m.textures[0].path).filename(), "brick wall.png");
  ASSERT_EQ(m.meshes.size(), 1u);
  EXPECT_EQ(m.meshes[0].positions[0].z, 5.0f);
  EXPECT_TRUE(hasTexcoord(m.meshes[0], 2500.0f, -2.0f));  // T = 3 flipped to v = 1 - 3
  EXPECT_EQ(loadTexture(m, 0).width, 8u);
}

}  // namespace
}  // namespace tessera::model
