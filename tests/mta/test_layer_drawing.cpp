// Layer 1 drawn by the atlas tree renderer (thesis §5.1.3, spec choice F13): the light map multiplies
// layer 0 through the node's layer-1 atlas and through the originals, unit 1's binds are counted, the
// memory manager requests layer 1's blocks, the build leaves the layer-1 area of a mesh without one
// white, a file without layer 1 is drawn as before, and a model whose layer 1 cannot share layer 0's
// atlas areas is refused before anything is written (mta/layer_maps.h).
//
// The scene is two unit quads of constant colour facing the camera, so every filter returns the texel
// itself and the expected pixels follow from the formula alone: quad A (200, 100, 50) with a constant
// light map (128, 0, 255), quad B (40, 80, 160) with none.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <string>

#include "base/error.h"
#include "model/model.h"
#include "mta/build.h"
#include "mta/tree_renderer.h"
#include "mta_test_scene.h"
#include "tests/model/occlusion_gltf.h"

namespace tessera::mta {
namespace {

using testing::addSquare;
using testing::TempFile;

constexpr std::array<uint8_t, 3> kBaseA{200, 100, 50}, kBaseB{40, 80, 160}, kLight{128, 0, 255};
// F13 with strength 1 and the R-only mode: A × light.R per channel, 200 · 128 / 255 = 100.39,
// 100 · 128 / 255 = 50.20, 50 · 128 / 255 = 25.10 (none near a rounding boundary of unorm8). With G (0)
// or B (255) taken as the factor, or layer 0 on unit 1, G and B (or all three) would differ.
constexpr std::array<uint8_t, 3> kLitA{100, 50, 25};

Scene twoQuads(bool lightMap) {
  Scene s;
  s.name = "two quads";
  Geometry& g = s.geometry;
  g.layers.resize(lightMap ? 2 : 1);
  // Images 0 and 1: the quads' base colours; image 2: quad A's light map.
  for (uint32_t i = 0; i < (lightMap ? 3u : 2u); ++i) {
    s.images.push_back(SceneImage{16, 16, "img" + std::to_string(i)});
    s.textures.push_back(SceneTexture{i, model::Wrap::ClampToEdge, model::Wrap::ClampToEdge});
  }
  for (int q = 0; q < 2; ++q) {
    // The light map on texcoord set 0, as the city's.
    if (lightMap)
      addSquare(g, float(q), 0, 1, 0, {q, q == 0 ? 2 : -1});
    else
      addSquare(g, float(q), 0, 1, 0, {q});
  }
  s.loadImage = [](uint32_t i) {
    const std::array<uint8_t, 3> c = i == 0 ? kBaseA : i == 1 ? kBaseB : kLight;
    model::Image img;
    img.width = img.height = 16;
    for (int t = 0; t < 16 * 16; ++t) img.rgba.insert(img.rgba.end(), {c[0], c[1], c[2], 255});
    return img;
  };
  return s;
}

// A one-leaf tree (both 16² images fit a 64² atlas); a tiny d_min lets the atlas serve every distance.
void build(const Scene& s, const std::string& path) {
  BuildParams p;
  p.atlasSize = 64;
  p.border = 2;
  p.dMin = 0.01;
  p.screenWidth = 128;
  p.threads = 2;
  p.encoding = BlockEncoding::Raw;  // the tests read exact texels back
  buildMta(s, p, path);
}

RendererOptions layerOptions(RenderMode mode) {
  RendererOptions o;
  o.mode = mode;
  o.width = 128;
  o.height = 96;
  o.threads = 2;
  o.residency.capacityBytes = uint64_t(1) << 30;
  o.residency.budget.kind = LoadBudget::Kind::Blocks;
  o.residency.budget.perFrame = UINT64_MAX;
  o.residency.maxQueue = UINT32_MAX;
  return o;
}

// Both quads fill most of the frame, magnified (level 0 only, bilinear inside each area).
Camera facing() {
  Camera c;
  c.eye = {1.0, 0.5, 1.6};
  c.target = {1.0, 0.5, 0.0};
  c.nearPlane = 0.05;
  c.farPlane = 10.0;
  return c;
}

// How many pixels of the frame have each colour; every pixel must be one of them or the sky.
struct Census {
  uint64_t a = 0, b = 0, other = 0;
};
Census census(const FrameResult& fr, std::array<uint8_t, 3> a, std::array<uint8_t, 3> b) {
  Census c;
  for (size_t i = 0; i + 3 < fr.image.size(); i += 4) {
    const std::array<uint8_t, 3> px{fr.image[i], fr.image[i + 1], fr.image[i + 2]};
    const bool sky = px[0] == 158 && px[1] == 189 && px[2] == 224;  // RecordParams::clear in unorm8
    if (px == a) ++c.a;
    else if (px == b) ++c.b;
    else if (!sky) ++c.other;
  }
  return c;
}

TEST(LayerDrawing, AnAtlasNodeMultipliesItsLayerOneAtlasRedIntoLayerZeroAndAMeshWithoutOneKeepsItsColour) {
  TempFile file("lit.mta");
  build(twoQuads(true), file.path);
  const PagingFile f(file.path);
  ASSERT_EQ(f.meta().layerCount, 2u);
  TreeRenderer r(f, layerOptions(RenderMode::AtlasTree));
  const FrameResult fr = r.renderFrame(facing());
  ASSERT_EQ(fr.plan.atlasNodes, 1u);
  ASSERT_EQ(fr.plan.originalLeaves, 0u);
  const Census c = census(fr, kLitA, kBaseB);
  EXPECT_GT(c.a, 1000u);
  EXPECT_GT(c.b, 1000u);  // the build left quad B's layer-1 area white: factor 1
  EXPECT_EQ(c.other, 0u);
  // One draw, its node's two atlases: one bind on each unit.
  EXPECT_EQ(fr.counters.draw_calls, 1u);
  EXPECT_EQ(fr.counters.units[0].texture_binds, 1u);
  EXPECT_EQ(fr.counters.units[1].texture_binds, 1u);
  EXPECT_EQ(fr.counters.texture_binds, 2u);
}

TEST(LayerDrawing, OriginalTexturesBindTheLightMapOrWhiteOnUnitOnePerRun) {
  TempFile file("lit.mta");
  build(twoQuads(true), file.path);
  const PagingFile f(file.path);
  TreeRenderer r(f, layerOptions(RenderMode::Original));
  const FrameResult fr = r.renderFrame(facing());
  ASSERT_EQ(fr.plan.originalLeaves, 1u);
  const Census c = census(fr, kLitA, kBaseB);
  EXPECT_GT(c.a, 1000u);
  EXPECT_GT(c.b, 1000u);
  EXPECT_EQ(c.other, 0u);
  // Two runs, (A, light map) and (B, none): two binds on unit 0, the light map and white on unit 1.
  EXPECT_EQ(fr.counters.draw_calls, 2u);
  EXPECT_EQ(fr.counters.units[0].texture_binds, 2u);
  EXPECT_EQ(fr.counters.units[1].texture_binds, 2u);
}

TEST(LayerDrawing, AFileWithoutLayerOneBindsNothingOnUnitOneAndDrawsTheBaseColours) {
  TempFile file("plain.mta");
  build(twoQuads(false), file.path);
  const PagingFile f(file.path);
  ASSERT_EQ(f.meta().layerCount, 1u);
  for (RenderMode mode : {RenderMode::AtlasTree, RenderMode::Original}) {
    TreeRenderer r(f, layerOptions(mode));
    const FrameResult fr = r.renderFrame(facing());
    const Census c = census(fr, kBaseA, kBaseB);
    EXPECT_GT(c.a, 1000u) << renderModeName(mode);
    EXPECT_GT(c.b, 1000u) << renderModeName(mode);
    EXPECT_EQ(c.other, 0u) << renderModeName(mode);
    EXPECT_EQ(fr.counters.units[1].texture_binds, 0u) << renderModeName(mode);
    EXPECT_EQ(fr.counters.units[0].texture_binds, mode == RenderMode::AtlasTree ? 1u : 2u) << renderModeName(mode);
  }
}

TEST(LayerDrawing, TheBuildFillsTheLayerOneAreaOfAMeshWithoutALayerOneTextureWhite) {
  TempFile file("lit.mta");
  build(twoQuads(true), file.path);
  const PagingFile f(file.path);
  const Tree& t = f.meta().trees.at(0);
  ASSERT_EQ(t.nodes.size(), 1u);
  const uint32_t A = f.meta().params.atlasSize;
  const std::vector<uint8_t> layer0 = f.readAtlas(0, 0, 0), layer1 = f.readAtlas(0, 0, 1);
  // The texel under each quad's first triangle's centroid: its layer-0 colour, and its light map or white.
  for (uint32_t tri : {0u, 2u}) {
    const bool quadA = t.geometry.layers[0].texture[tri] == 0;
    const glm::vec2 c = (t.atlasUV[tri * 3] + t.atlasUV[tri * 3 + 1] + t.atlasUV[tri * 3 + 2]) / 3.0f;
    const size_t texel = (size_t(c.y * A) * A + size_t(c.x * A)) * 3;
    const std::array<uint8_t, 3> base = quadA ? kBaseA : kBaseB;
    const std::array<uint8_t, 3> light = quadA ? kLight : std::array<uint8_t, 3>{255, 255, 255};
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(layer0[texel + k], base[k]) << "triangle " << tri << " channel " << k;
      EXPECT_EQ(layer1[texel + k], light[k]) << "triangle " << tri << " channel " << k;
    }
  }
  // Outside every area layer 1 is white too, so no texel is anything but the light map or white.
  for (size_t i = 0; i < layer1.size(); i += 3) {
    const bool white = layer1[i] == 255 && layer1[i + 1] == 255 && layer1[i + 2] == 255;
    const bool light = layer1[i] == kLight[0] && layer1[i + 1] == kLight[1] && layer1[i + 2] == kLight[2];
    ASSERT_TRUE(white || light) << "texel " << i / 3;
  }
}

TEST(LayerDrawing, TheMemoryManagerRequestsAndPinsLayerOneBlocks) {
  TempFile file("lit.mta");
  build(twoQuads(true), file.path);
  const PagingFile f(file.path);
  const MtaMeta& m = f.meta();
  TreeRenderer atlas(f, layerOptions(RenderMode::AtlasTree));
  atlas.renderFrame(facing());
  // The root's layer-1 atlas is pinned like its layer 0.
  const uint32_t root1 = m.trees[0].atlasBlocks[1];
  ASSERT_EQ(m.blocks[root1].layer, 1u);
  EXPECT_TRUE(atlas.residency()->resident(root1));
  // The leaf's originals include the light map's image (2): a view close enough to need them requests it.
  const BlockIndex index = buildBlockIndex(m, kRecordedLayers);
  EXPECT_EQ(index.atlasPerNode, 2u);
  ViewParams v = atlas.view(facing());
  bool lightMapRequested = false;
  const std::vector<BlockPriority> pr = usagePriorities(m, index, makeViewContext(m, v));
  for (uint32_t b = 0; b < m.blocks.size(); ++b)
    if (m.blocks[b].kind == BlockKind::Original && m.blocks[b].node == 2) lightMapRequested |= pr[b].usage != Usage::Unused;
  EXPECT_TRUE(lightMapRequested);
}


// Two quads on the same base texture (image 0) over the same texcoords, so both map onto one atlas area
// (layer 0 is not injective); quad A has light map 1 on texcoords uv0, quad B texture `b1` (-1: none) on
// uv0 + bOffset. Textures 1 and 2 are images 1 and 2 with `wrap`.
Scene sharedBase(int32_t b1, glm::vec2 bOffset, model::Wrap wrap) {
  Scene s;
  s.name = "shared.gltf";
  Geometry& g = s.geometry;
  g.layers.resize(2);
  s.images = {SceneImage{16, 16, "base.png"}, SceneImage{16, 16, "light1.png"}, SceneImage{16, 16, "light2.png"}};
  s.textures = {SceneTexture{0}, SceneTexture{1, wrap, wrap}, SceneTexture{2, wrap, wrap}};
  for (int q = 0; q < 2; ++q)
    addSquare(g, float(q), 0, 1, 0, {0, q == 0 ? 1 : b1}, {glm::vec2(0.0f), q == 1 ? bOffset : glm::vec2(0.0f)});
  s.loadImage = [](uint32_t) {
    model::Image img;
    img.width = img.height = 16;
    img.rgba.assign(16 * 16 * 4, 200);
    return img;
  };
  return s;
}

std::string buildError(const Scene& s, const std::string& path) {
  try {
    build(s, path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(LayerMaps, TrianglesSharingAnAtlasAreaAreAcceptedWhenTheyMapLayerOneAlikeModuloTheRepeat) {
  // Not injective (both quads on the same texels), but one light map through the same map, a whole
  // repeat apart: the area's one fill is right for both.
  TempFile file("shared.mta");
  EXPECT_EQ(buildError(sharedBase(1, {1.0f, -2.0f}, model::Wrap::Repeat), file.path), "");
}

TEST(LayerMaps, AnotherLightMapInTheSameAreaIsRefusedNamingBothTriangles) {
  TempFile file("shared.mta");
  const std::string e = buildError(sharedBase(2, {0.0f, 0.0f}, model::Wrap::Repeat), file.path);
  EXPECT_NE(e.find("shared.gltf: layer 1 cannot share layer 0's atlas: input triangle 0 and input triangle 2"),
            std::string::npos) << e;
  EXPECT_NE(e.find("'base.png'"), std::string::npos) << e;
  EXPECT_NE(e.find("textures differ ('light1.png' and 'light2.png'"), std::string::npos) << e;
  EXPECT_FALSE(std::filesystem::exists(file.path)) << "refused before anything is written";
}

TEST(LayerMaps, TheSameLightMapAtOtherTexcoordsIsRefusedWithTheDistanceInTexels) {
  // Half the image to the right, clamped: 8 texels of a 16-texel light map.
  TempFile file("shared.mta");
  const std::string e = buildError(sharedBase(1, {0.5f, 0.0f}, model::Wrap::ClampToEdge), file.path);
  EXPECT_NE(e.find("input triangle 0 and input triangle 2"), std::string::npos) << e;
  EXPECT_NE(e.find("vertex 0 of the second lies 8 texels (s) and 0 texels (t) of 'light1.png'"), std::string::npos) << e;
}

TEST(LayerMaps, AGltfMeshWithoutAnOcclusionTextureOnTheBaseTextureOfOneWithItIsRefusedNamingTheMeshes) {
  // occlusion_gltf.h: meshes 0 ("lit", occlusion on TEXCOORD_1) and 1 ("plain", none) share base texture 0.
  model::testing::ScratchDir dir;
  const Scene s = sceneFromModel(
      std::make_shared<const model::Model>(model::loadModel(model::testing::writeOcclusionGltf(dir, 1.0))));
  TempFile file("gltf.mta");
  const std::string e = buildError(s, file.path);
  EXPECT_NE(e.find("layer 1 cannot share layer 0's atlas: mesh "), std::string::npos) << e;
  EXPECT_NE(e.find("(0) triangle 0 and mesh "), std::string::npos) << e;
  EXPECT_NE(e.find("(1) triangle 0"), std::string::npos) << e;
  EXPECT_NE(e.find("the second has no layer-1 texture"), std::string::npos) << e;
}

}  // namespace
}  // namespace tessera::mta
