// Rotated atlas areas (packing.h, tree.h AtlasEntry::rotated): the packing turns wide rectangles where
// that lets a set fit one atlas, and the builder carries the turn through the atlas texels and the
// texture coordinates, so that sampling the atlas gives the texels of the unrotated image.
#include <gtest/gtest.h>

#include <cmath>

#include "mta/build.h"
#include "mta/packing.h"
#include "mta/paging_file.h"
#include "mta/tree_build.h"
#include "mta_test_scene.h"

namespace tessera::mta {
namespace {

using testing::TempFile;

// Marks every texel of every placement; fails on an overlap or a texel outside the atlas.
void expectDisjointInside(const std::vector<PackRect>& rects, const PackResult& r, uint32_t a) {
  std::vector<uint8_t> used(size_t(a) * a, 0);
  for (size_t i = 0; i < rects.size(); ++i) {
    const Placement& p = r.placements[i];
    const uint32_t w = p.rotated ? rects[i].h : rects[i].w, h = p.rotated ? rects[i].w : rects[i].h;
    ASSERT_LE(p.x + w, a) << "rect " << i;
    ASSERT_LE(p.y + h, a) << "rect " << i;
    for (uint32_t y = p.y; y < p.y + h; ++y)
      for (uint32_t x = p.x; x < p.x + w; ++x) {
        ASSERT_EQ(used[size_t(y) * a + x], 0) << "overlap at rect " << i;
        used[size_t(y) * a + x] = 1;
      }
  }
}

TEST(Packing, TurningWideRectanglesFitsASetThatDoesNotFitAsGiven) {
  // A 30 x 64 column and two 60 x 16 strips: as given, the strips cannot sit beside the column (30 + 60 > 64)
  // nor above it (64 + 16 > 64). Turned upright (16 x 60) they stand beside it: 30 + 16 + 16 = 62 columns.
  const std::vector<PackRect> rects = {{30, 64}, {60, 16}, {60, 16}};
  EXPECT_FALSE(packAtlas(rects, 64, false).ok);
  const PackResult r = packAtlas(rects, 64);
  ASSERT_TRUE(r.ok);
  EXPECT_TRUE(r.anyRotated);
  EXPECT_FALSE(r.placements[0].rotated);
  EXPECT_TRUE(r.placements[1].rotated);
  EXPECT_TRUE(r.placements[2].rotated);
  expectDisjointInside(rects, r, 64);
  EXPECT_EQ(r.usedTexels, 30u * 64 + 2 * 60 * 16);
  // A set that fits as given keeps its layout: nothing is turned.
  const std::vector<PackRect> easy = {{60, 16}, {60, 16}, {30, 30}};
  const PackResult e = packAtlas(easy, 64);
  ASSERT_TRUE(e.ok);
  EXPECT_FALSE(e.anyRotated);
}

// Three facades whose images are the rectangles above: a 30 x 64 one and two 60 x 16 ones, each a unit
// quad with texcoords [0, 1]², no border and a tiny d_min, so every area is its image texel for texel.
Scene facades() {
  Scene s;
  s.name = "facades";
  const uint32_t size[3][2] = {{30, 64}, {60, 16}, {60, 16}};
  s.geometry.layers.resize(1);
  for (uint32_t q = 0; q < 3; ++q) {
    s.images.push_back(SceneImage{size[q][0], size[q][1], "facade" + std::to_string(q)});
    s.textures.push_back(SceneTexture{q, model::Wrap::Repeat, model::Wrap::Repeat});
    const float x = 1.5f * float(q);
    const glm::vec3 p[4] = {{x, 0, 0}, {x + 1, 0, 0}, {x + 1, 1, 0}, {x, 1, 0}};
    const glm::vec2 t[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (const auto& k : tri) {
      for (int i : k) s.geometry.positions.push_back(p[i]), s.geometry.layers[0].uv.push_back(t[i]);
      s.geometry.layers[0].texture.push_back(int32_t(q));
      s.geometry.source.push_back(uint32_t(s.geometry.source.size()));
      s.geometry.alpha.push_back(0);
    }
  }
  const std::vector<SceneImage> images = s.images;
  s.loadImage = [images](uint32_t i) {
    model::Image img;
    img.width = images[i].width, img.height = images[i].height;
    img.rgba.resize(size_t(img.width) * img.height * 4);
    for (uint32_t y = 0; y < img.height; ++y)
      for (uint32_t x = 0; x < img.width; ++x) {
        uint8_t* p = &img.rgba[(size_t(y) * img.width + x) * 4];
        p[0] = uint8_t(x * 4 + i), p[1] = uint8_t(y * 3 + i * 70), p[2] = uint8_t(x * y + 11 * i), p[3] = 255;
      }
    return img;
  };
  return s;
}

BuildParams facadeParams() {
  BuildParams p;
  p.atlasSize = 64;
  p.border = 0;
  p.dMin = 0.001;  // every area capped at its image's size
  p.encoding = BlockEncoding::Raw;  // the tests compare atlas texels with the images' own
  p.threads = 2;
  return p;
}

TEST(Rotation, TheFacadesFitOneLeafOnlyWithTheStripsTurned) {
  const Scene s = facades();
  std::vector<uint32_t> tris(s.geometry.triangleCount());
  for (uint32_t i = 0; i < tris.size(); ++i) tris[i] = i;
  const Tree tree = buildTree(s, s.geometry, tris, 0, facadeParams(), 0.001);
  ASSERT_EQ(tree.nodes.size(), 1u) << "the three areas should share the root atlas";
  ASSERT_EQ(tree.nodes[0].entries.size(), 3u);
  for (const AtlasEntry& e : tree.nodes[0].entries) {
    EXPECT_EQ(e.rotated, e.texture != 0) << "texture " << e.texture;
    // Placed extents: the strips stand upright (16 wide, 60 tall).
    EXPECT_EQ(e.w, e.texture == 0 ? 30u : 16u);
    EXPECT_EQ(e.h, e.texture == 0 ? 64u : 60u);
  }
}

TEST(Rotation, SamplingATurnedAreaThroughItsAtlasTexcoordsGivesTheImagesOwnTexels) {
  const Scene s = facades();
  TempFile file("facades.mta");
  buildMta(s, facadeParams(), file.path);
  const PagingFile f(file.path);
  const MtaMeta& m = f.meta();
  ASSERT_EQ(m.trees.size(), 1u);
  ASSERT_EQ(m.trees[0].nodes.size(), 1u);
  const Tree& t = m.trees[0];
  const uint32_t A = m.params.atlasSize;
  const std::vector<uint8_t> atlas = f.readAtlas(0, 0);
  uint64_t compared = 0;
  for (uint32_t tri = 0; tri < t.geometry.triangleCount(); ++tri) {
    const int32_t tex = t.geometry.layers[0].texture[tri];
    const model::Image img = s.loadImage(uint32_t(tex));
    const glm::vec2* uv = &t.geometry.layers[0].uv[tri * 3];
    const glm::vec2* st = &t.atlasUV[tri * 3];
    if (tex != 0) {  // turned: along u the atlas coordinate moves in t, not in s
      const glm::vec2 du = uv[1] - uv[0], ds = st[1] - st[0];
      if (du.y == 0.0f && du.x != 0.0f) {
        EXPECT_EQ(ds.x, 0.0f) << "triangle " << tri;
      }
    }
    // Every image texel centre inside the triangle: barycentrics in texcoord space, the same weights on
    // the atlas texcoords, then the atlas texel there must hold the image texel.
    const double d = double(uv[1].x - uv[0].x) * (uv[2].y - uv[0].y) - double(uv[2].x - uv[0].x) * (uv[1].y - uv[0].y);
    ASSERT_NE(d, 0.0);
    for (uint32_t j = 0; j < img.height; ++j)
      for (uint32_t i = 0; i < img.width; ++i) {
        const double u = (i + 0.5) / img.width, v = (j + 0.5) / img.height;
        const double b1 = ((u - uv[0].x) * (uv[2].y - uv[0].y) - (uv[2].x - uv[0].x) * (v - uv[0].y)) / d;
        const double b2 = ((uv[1].x - uv[0].x) * (v - uv[0].y) - (u - uv[0].x) * (uv[1].y - uv[0].y)) / d;
        const double b0 = 1.0 - b1 - b2;
        if (b0 < 1e-9 || b1 < 1e-9 || b2 < 1e-9) continue;  // on the diagonal or outside: the other triangle
        const double sx = (b0 * st[0].x + b1 * st[1].x + b2 * st[2].x) * A;
        const double sy = (b0 * st[0].y + b1 * st[1].y + b2 * st[2].y) * A;
        const uint32_t ax = uint32_t(std::floor(sx)), ay = uint32_t(std::floor(sy));
        ASSERT_LT(ax, A);
        ASSERT_LT(ay, A);
        for (int c = 0; c < 3; ++c)
          ASSERT_EQ(atlas[(size_t(ay) * A + ax) * 3 + c], img.rgba[(size_t(j) * img.width + i) * 4 + c])
              << "texture " << tex << " texel (" << i << ", " << j << ") channel " << c << " at atlas (" << ax << ", "
              << ay << ")";
        ++compared;
      }
  }
  // Every texel off the quads' diagonals, of all three images.
  EXPECT_GT(compared, (30u * 64 + 2 * 60 * 16) * 9 / 10);
}

}  // namespace
}  // namespace tessera::mta
