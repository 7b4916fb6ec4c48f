// The judgement rule: unclassed pixels must match exactly; classed pixels must lie in their interval.
#include <gtest/gtest.h>

#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "tools/scenes/scenes.h"
#include "verify/judge.h"

using namespace tessera;

namespace {
struct Rendered {
  std::unique_ptr<CpuBackend> b = std::make_unique<CpuBackend>(RenderOptions{0, true});
  const TextureData* tex = nullptr;
  PresentedImage img;
  std::vector<uint8_t> pixels;
};
Rendered render(const char* scene) {
  Rendered r;
  const scenes::SceneInfo* s = scenes::find(scene);
  r.b->execute(scenes::build(s->name, s->width, s->height), scene);
  r.img = r.b->presented().at(0);
  r.tex = r.b->texture(r.img.texture);
  r.pixels = imagePixels(*r.tex, r.img.level, r.img.layer);
  return r;
}
}  // namespace

TEST(Judge, IdenticalImagesAreAllExact) {
  const Rendered r = render("depth");
  const verify::Judgement j = verify::judge(*r.tex, r.img.level, r.img.layer, r.pixels);
  EXPECT_EQ(j.exact, j.pixels);
  EXPECT_TRUE(j.passed());
}

TEST(Judge, AOneLsbChangeOnAnUnclassedPixelIsUnexplained) {
  const Rendered r = render("depth");
  const verify::Judgement ref = verify::judge(*r.tex, r.img.level, r.img.layer, r.pixels);
  size_t i = 0;
  while (ref.classMap[i]) ++i;  // an unclassed pixel
  auto other = r.pixels;
  other[i * 4] = uint8_t(other[i * 4] ^ 1);
  const verify::Judgement j = verify::judge(*r.tex, r.img.level, r.img.layer, other);
  EXPECT_EQ(j.unexplained, 1u);
  ASSERT_EQ(j.firstUnexplained.size(), 1u);
  EXPECT_EQ(size_t(j.firstUnexplained[0].y) * 192 + size_t(j.firstUnexplained[0].x), i);
}

TEST(Judge, AChangeInsideAClassedPixelsIntervalIsExplainedAndOutsideIsNot) {
  const Rendered r = render("blend");
  const verify::Judgement ref = verify::judge(*r.tex, r.img.level, r.img.layer, r.pixels);
  const auto lo = imagePixels(*r.tex->prov->lo, 0, 0), hi = imagePixels(*r.tex->prov->hi, 0, 0);
  size_t i = 0;
  while (i < ref.pixels && !(ref.classMap[i] && hi[i * 4] > r.pixels[i * 4] && hi[i * 4] < 255)) ++i;
  ASSERT_LT(i, ref.pixels) << "no classed pixel with room above its value";
  auto inside = r.pixels, outside = r.pixels;
  inside[i * 4] = hi[i * 4];
  outside[i * 4] = uint8_t(hi[i * 4] + 1);
  const verify::Judgement a = verify::judge(*r.tex, 0, 0, inside);
  const verify::Judgement b = verify::judge(*r.tex, 0, 0, outside);
  EXPECT_EQ(a.explained, 1u);
  EXPECT_EQ(a.unexplained, 0u);
  EXPECT_EQ(b.unexplained, 1u);
  EXPECT_GE(lo[i * 4], 0);
}

TEST(Judge, IdImagesAreComparedExactly) {
  const Rendered r = render("city_ids");
  auto other = r.pixels;
  other[100 * 4] ^= 1;
  const verify::Judgement j = verify::judge(*r.tex, r.img.level, r.img.layer, other);
  EXPECT_EQ(j.unexplained, 1u);
}
