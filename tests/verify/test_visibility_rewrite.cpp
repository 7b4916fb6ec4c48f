// Visibility for frames not drawn with object_id (verify/visibility_rewrite.h): the frame is rewritten
// to object_id with the same geometry and state; object id = draw index.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "raster/cpu_backend.h"
#include "base/error.h"
#include "raster/image_io.h"
#include "tools/scenes/scenes.h"
#include "verify/visibility.h"
#include "verify/visibility_rewrite.h"

namespace tessera::verify {

namespace {
size_t drawCount(const CommandList& list) {
  size_t n = 0;
  for (const Command& c : list.commands()) n += std::holds_alternative<Draw>(c);
  return n;
}
}  // namespace

// wrap_filter at 256x192: a 4 x 3 grid of quads, issued column by column (draw = 3 col + row), each
// quad covering x, y in [0.05, 0.95] of its 64 x 64 cell (y up), drawn with "textured" and no depth.
// Quad (p0 p1 p2 p3) is indexed (0 1 2)(0 2 3): primitive 0 is the half below the diagonal.
TEST(VisibilityRewrite, AFrameNotDrawnWithObjectIdGetsTheIdsOfItsGeometry) {
  const CommandList list = scenes::build("wrap_filter", 256, 192);
  ASSERT_TRUE(needsObjectIdRewrite(list));
  const CommandList ids = rewriteToObjectIds(list);
  EXPECT_EQ(drawCount(ids), drawCount(list));
  const IdImages oracle = renderOracleIds(ids);
  const VisibilityResult r = castVisibility(list);
  EXPECT_TRUE(r.rewrittenToObjectId);
  EXPECT_EQ(r.unexplained, 0u);
  EXPECT_EQ(r.draws, 12u);
  ASSERT_EQ(oracle.width, 256);
  ASSERT_EQ(r.embree.width, 256);
  auto at = [](const std::vector<uint32_t>& img, int x, int y) { return img[size_t(y) * 256 + size_t(x)]; };
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 3; ++row) {
      const uint32_t draw = uint32_t(col * 3 + row);
      const int x0 = col * 64, y0 = row * 64;
      for (const IdImages* img : {&oracle, &r.embree}) {
        EXPECT_EQ(at(img->object, x0 + 50, y0 + 10), draw) << col << "," << row;
        EXPECT_EQ(at(img->primitive, x0 + 50, y0 + 10), 0u);  // below the diagonal
        EXPECT_EQ(at(img->object, x0 + 10, y0 + 50), draw);
        EXPECT_EQ(at(img->primitive, x0 + 10, y0 + 50), 1u);  // above it
        EXPECT_EQ(at(img->object, x0 + 1, y0 + 1), 0xffffffffu);  // the gap between cells: background
        EXPECT_EQ(at(img->object, x0 + 62, y0 + 62), 0xffffffffu);
      }
    }
}

TEST(VisibilityRewrite, AFrameDrawnWithObjectIdIsCheckedAsItIs) {
  const CommandList list = scenes::build("city_ids", 64, 48);
  EXPECT_FALSE(needsObjectIdRewrite(list));
  EXPECT_EQ(rewriteToObjectIds(list).commands().size(), list.commands().size());
  EXPECT_FALSE(castVisibility(list).rewrittenToObjectId);
}

// city_block (textured, depth-tested buildings) has overlapping geometry: the rewrite keeps its depth
// state, so the nearest draw must win exactly where Embree says it does.
TEST(VisibilityRewrite, ADepthTestedSceneWithOtherProgramsIsFullyExplained) {
  const CommandList list = scenes::build("city_block", 160, 120);
  const VisibilityResult r = castVisibility(list);
  EXPECT_TRUE(r.rewrittenToObjectId);
  EXPECT_EQ(r.unexplained, 0u) << visibilityToJson(r).dump(1).substr(0, 2000);
  EXPECT_GT(r.matching, r.pixels / 2);
  // Some pixel shows a draw other than the first: the ids are draw indices, not a constant.
  uint32_t lo = 0xffffffffu, hi = 0;
  for (uint32_t id : r.embree.object)
    if (id != 0xffffffffu) lo = std::min(lo, id), hi = std::max(hi, id);
  EXPECT_LT(lo, hi);
}

// Same geometry, clipping included: clip_planes cuts a vertex_color fan with three user clip planes
// and the near plane. A pixel is covered by the rewritten frame exactly where the original frame
// changes the target (its render differs from the render of the frame cut before its first draw).
TEST(VisibilityRewrite, TheRewriteCoversExactlyThePixelsTheOriginalDrawsIncludingUserClipping) {
  for (const char* scene : {"clip_planes", "wrap_filter", "fill_fan"}) {
    const scenes::SceneInfo* s = scenes::find(scene);
    const CommandList list = scenes::build(scene, s->width, s->height);
    CommandList background = list;
    for (size_t i = 0; i < list.commands().size(); ++i)
      if (std::holds_alternative<Draw>(list.commands()[i])) {
        background.truncate(i);
        break;
      }
    auto image = [](const CommandList& l) {
      CpuBackend b;
      b.execute(l, "rewrite test");
      const PresentedImage p = b.presented()[0];
      return imagePixels(*b.texture(p.texture), p.level, p.layer);  // top row first
    };
    const std::vector<uint8_t> drawn = image(list), clear = image(background);
    const IdImages ids = renderOracleIds(rewriteToObjectIds(list));
    ASSERT_EQ(drawn.size(), size_t(ids.width) * size_t(ids.height) * 4);
    uint64_t covered = 0, disagree = 0;
    for (int y = 0; y < ids.height; ++y)
      for (int x = 0; x < ids.width; ++x) {
        const size_t file = (size_t(ids.height - 1 - y) * size_t(ids.width) + size_t(x)) * 4;
        const bool changed = !std::equal(drawn.begin() + file, drawn.begin() + file + 4, clear.begin() + file);
        const bool hit = ids.object[size_t(y) * size_t(ids.width) + size_t(x)] != 0xffffffffu;
        covered += hit;
        disagree += changed != hit;
      }
    EXPECT_GT(covered, 0u) << scene;
    EXPECT_EQ(disagree, 0u) << scene;
  }
}

TEST(VisibilityRewrite, AFrameWithAProgramThatWritesItsDepthIsRefusedNamingTheProgram) {
  // atlas_sprite's position is attribute 0 as is and its depth a texel: the object_id rewrite (MVP from
  // slots 0-3, interpolated depth) would check other geometry than the frame's, so it refuses.
  try {
    rewriteToObjectIds(scenes::build("atlas_sprites", 64, 64));
    FAIL() << "atlas_sprites must be refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'atlas_sprite' writes its fragment depth"), std::string::npos) << e.what();
  }
}

}  // namespace tessera::verify
