// The judgement rule: unclassed pixels must match exactly; classed pixels must lie in their interval
// (inclusive bounds, every channel). Each test edits a known set of pixels of the oracle's own image
// and checks the judge's verdict and counts against that set.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>

#include "base/error.h"
#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "tests/crosscheck/find_pixels.h"
#include "tools/scenes/scenes.h"
#include "verify/judge.h"

namespace tessera {

namespace {
struct BoundedRender {
  std::unique_ptr<CpuBackend> b = std::make_unique<CpuBackend>(RenderOptions{0, true});
  const TextureData* tex = nullptr;
  PresentedImage img;
  std::vector<uint8_t> pixels, lo, hi;  // top-down, imagePixels() layout
  size_t count = 0;                     // pixels
};
BoundedRender renderWithBounds(const char* scene) {
  BoundedRender r;
  const scenes::SceneInfo* s = scenes::find(scene);
  r.b->execute(scenes::build(s->name, s->width, s->height), scene);
  r.img = r.b->presented().at(0);
  r.tex = r.b->texture(r.img.texture);
  r.pixels = imagePixels(*r.tex, r.img.level, r.img.layer);
  r.lo = imagePixels(*r.tex->prov->lo, r.img.level, r.img.layer);
  r.hi = imagePixels(*r.tex->prov->hi, r.img.level, r.img.layer);
  r.count = size_t(s->width) * size_t(s->height);
  return r;
}

verify::Judgement judgeImage(const BoundedRender& r, const std::vector<uint8_t>& other) {
  return verify::judge(*r.tex, r.img.level, r.img.layer, other);
}

using tessera::testing::findPixels;

// The classes of pixel i (top-down index) read straight from the provenance storage, which keeps rows
// bottom first: an independent path from the judge's classMap.
uint16_t storedClasses(const BoundedRender& r, size_t i) {
  const size_t w = r.tex->desc.width, h = r.tex->desc.height;
  const size_t x = i % w, yTop = i / w;
  return r.tex->prov->classes[r.img.level][(size_t(r.img.layer) * h + (h - 1 - yTop)) * w + x];
}
}  // namespace

TEST(Judge, IdenticalImagesAreAllExact) {
  const BoundedRender r = renderWithBounds("depth");
  const verify::Judgement j = judgeImage(r, r.pixels);
  EXPECT_EQ(j.pixels, uint64_t(192 * 192));
  EXPECT_EQ(j.exact, j.pixels);
  EXPECT_EQ(j.explained, 0u);
  EXPECT_EQ(j.unexplained, 0u);
  EXPECT_EQ(j.histogram[0], j.pixels);
  EXPECT_EQ(j.mse, 0.0);
  EXPECT_TRUE(std::isinf(j.psnr()));
  EXPECT_TRUE(j.passed());
  // The classed count is the number of pixels whose stored class mask is non-zero, and the class map
  // is that mask pixel by pixel (flipped to top-down).
  uint64_t classed = 0;
  for (size_t i = 0; i < r.count; ++i) {
    ASSERT_EQ(j.classMap[i], storedClasses(r, i)) << "pixel " << i;
    classed += storedClasses(r, i) != 0;
  }
  EXPECT_EQ(j.classed, classed);
  EXPECT_GT(classed, 0u) << "the depth scene has triangle edges, so some pixels must be classed";
}

TEST(Judge, AOneLsbChangeOnAnUnclassedPixelIsUnexplainedInEitherDirection) {
  const BoundedRender r = renderWithBounds("depth");
  const verify::Judgement ref = judgeImage(r, r.pixels);
  // An unclassed pixel whose red byte can move by one both ways.
  const auto found = findPixels(
      r.count, 1, [&](size_t i) { return ref.classMap[i] == 0 && r.pixels[i * 4] > 0 && r.pixels[i * 4] < 255; });
  ASSERT_EQ(found.size(), 1u) << "no unclassed pixel with a red byte strictly inside 0..255";
  const size_t i = found[0];
  ASSERT_EQ(r.lo[i * 4], r.pixels[i * 4]) << "an unclassed pixel must have a zero-width interval";
  ASSERT_EQ(r.hi[i * 4], r.pixels[i * 4]) << "an unclassed pixel must have a zero-width interval";
  for (int delta : {+1, -1}) {
    auto other = r.pixels;
    other[i * 4] = uint8_t(other[i * 4] + delta);
    const verify::Judgement j = judgeImage(r, other);
    EXPECT_EQ(j.unexplained, 1u) << "delta " << delta;
    EXPECT_EQ(j.explained, 0u) << "delta " << delta;
    EXPECT_EQ(j.exact, j.pixels - 1) << "delta " << delta;
    EXPECT_EQ(j.histogram[1], 1u) << "a 1-LSB difference falls in the second bin";
    EXPECT_EQ(j.maxAbsDiff[0], 1.0);
    EXPECT_EQ(j.failMap[i], 2);
    EXPECT_FALSE(j.passed());
    ASSERT_EQ(j.firstUnexplained.size(), 1u);
    const verify::PixelRecord& rec = j.firstUnexplained[0];
    EXPECT_EQ(size_t(rec.y) * 192 + size_t(rec.x), i);
    EXPECT_EQ(rec.classes, 0);
    EXPECT_EQ(rec.oracle[0], double(r.pixels[i * 4]));
    EXPECT_EQ(rec.other[0], double(r.pixels[i * 4] + delta));
  }
}

TEST(Judge, TheIntervalBoundsAreInclusiveAndOneLsbBeyondEitherBoundIsUnexplained) {
  const BoundedRender r = renderWithBounds("blend");
  const verify::Judgement ref = judgeImage(r, r.pixels);
  // Classed pixels whose red interval lies strictly inside 0..255 and strictly contains the value, so
  // that lo, hi, lo - 1 and hi + 1 are all different from the oracle's byte and representable.
  const auto roomy = [&](size_t i) {
    const uint8_t v = r.pixels[i * 4], l = r.lo[i * 4], h = r.hi[i * 4];
    return ref.classMap[i] != 0 && l > 0 && l < v && v < h && h < 255;
  };
  const auto c = findPixels(r.count, 5, roomy);
  ASSERT_EQ(c.size(), 5u) << "the blend scene must have classed pixels with room on both sides";
  const auto u = findPixels(r.count, 1, [&](size_t i) { return ref.classMap[i] == 0 && r.pixels[i * 4] < 255; });
  ASSERT_EQ(u.size(), 1u) << "no unclassed pixel";

  auto other = r.pixels;
  other[c[0] * 4] = r.hi[c[0] * 4];               // on the upper bound: explained
  other[c[1] * 4] = r.lo[c[1] * 4];               // on the lower bound: explained
  other[c[2] * 4] = uint8_t(r.hi[c[2] * 4] + 1);  // one above: unexplained
  other[c[3] * 4] = uint8_t(r.lo[c[3] * 4] - 1);  // one below: unexplained
  // Red on its bound but green one beyond: every channel must be inside, so unexplained.
  other[c[4] * 4] = r.hi[c[4] * 4];
  if (r.hi[c[4] * 4 + 1] < 255) {
    other[c[4] * 4 + 1] = uint8_t(r.hi[c[4] * 4 + 1] + 1);
  } else {
    ASSERT_GT(r.lo[c[4] * 4 + 1], 0) << "green interval covers 0..255";
    other[c[4] * 4 + 1] = uint8_t(r.lo[c[4] * 4 + 1] - 1);
  }
  other[u[0] * 4] = uint8_t(r.pixels[u[0] * 4] + 1);  // unclassed, one LSB: unexplained

  const verify::Judgement j = judgeImage(r, other);
  EXPECT_EQ(j.explained, 2u);
  EXPECT_EQ(j.unexplained, 4u);
  EXPECT_EQ(j.exact, j.pixels - 6);
  EXPECT_EQ(j.failMap[c[0]], 1);
  EXPECT_EQ(j.failMap[c[1]], 1);
  EXPECT_EQ(j.failMap[c[2]], 2);
  EXPECT_EQ(j.failMap[c[3]], 2);
  EXPECT_EQ(j.failMap[c[4]], 2);
  EXPECT_EQ(j.failMap[u[0]], 2);
  // Explained differences are counted under each class of their pixel, and only there.
  for (int b = 0; b < kClassCount; ++b) {
    const uint64_t expected = uint64_t((ref.classMap[c[0]] >> b) & 1) + uint64_t((ref.classMap[c[1]] >> b) & 1);
    EXPECT_EQ(j.classExplained[size_t(b)], expected) << ambiguityClassName(b);
  }
  // The unexplained records come in scan order and name the pixels that were edited.
  std::vector<size_t> bad = {c[2], c[3], c[4], u[0]};
  std::sort(bad.begin(), bad.end());
  ASSERT_EQ(j.firstUnexplained.size(), 4u);
  for (size_t k = 0; k < 4; ++k) {
    const verify::PixelRecord& rec = j.firstUnexplained[k];
    EXPECT_EQ(size_t(rec.y) * 256 + size_t(rec.x), bad[k]) << "record " << k;
    EXPECT_EQ(rec.classes, ref.classMap[bad[k]]) << "record " << k;
    EXPECT_EQ(rec.lo[0], double(r.lo[bad[k] * 4])) << "record " << k;
    EXPECT_EQ(rec.hi[0], double(r.hi[bad[k] * 4])) << "record " << k;
  }
  // The JSON report carries the same counts.
  const nlohmann::json js = verify::toJson(j);
  EXPECT_EQ(js["pixels"].get<uint64_t>(), uint64_t(256 * 128));
  EXPECT_EQ(js["explained"].get<uint64_t>(), 2u);
  EXPECT_EQ(js["unexplained"].get<uint64_t>(), 4u);
  EXPECT_EQ(js["exact"].get<uint64_t>(), uint64_t(256 * 128 - 6));
  EXPECT_EQ(js["classed"].get<uint64_t>(), ref.classed);
  EXPECT_FALSE(js["passed"].get<bool>());
  EXPECT_EQ(js["first_unexplained"].size(), 4u);
  EXPECT_DOUBLE_EQ(js["exact_match_percent"].get<double>(), 100.0 * double(256 * 128 - 6) / double(256 * 128));
}

TEST(Judge, IdImagesAreComparedAgainstTheirIntervalsLikeColours) {
  const BoundedRender r = renderWithBounds("city_ids");
  ASSERT_EQ(r.tex->desc.format, Format::R32UI);
  const verify::Judgement ref = judgeImage(r, r.pixels);
  auto word = [](const std::vector<uint8_t>& v, size_t i) {
    uint32_t x;
    std::memcpy(&x, &v[i * 4], 4);
    return x;
  };
  auto put = [](std::vector<uint8_t>& v, size_t i, uint32_t x) { std::memcpy(&v[i * 4], &x, 4); };
  const auto u = findPixels(r.count, 1, [&](size_t i) { return ref.classMap[i] == 0; });
  ASSERT_EQ(u.size(), 1u) << "no unclassed id pixel";
  const auto c = findPixels(r.count, 1, [&](size_t i) {
    return ref.classMap[i] != 0 && word(r.lo, i) < word(r.pixels, i) && word(r.hi, i) < 0xffffffffu;
  });
  ASSERT_EQ(c.size(), 1u) << "no classed id pixel with an interval below its value";

  auto other = r.pixels;
  put(other, u[0], word(r.pixels, u[0]) ^ 1u);  // any other id on an unclassed pixel
  put(other, c[0], word(r.lo, c[0]));           // the other candidate of an edge pixel
  verify::Judgement j = judgeImage(r, other);
  EXPECT_EQ(j.unexplained, 1u);
  EXPECT_EQ(j.explained, 1u);
  EXPECT_EQ(j.failMap[u[0]], 2);
  EXPECT_EQ(j.failMap[c[0]], 1);

  put(other, c[0], word(r.hi, c[0]) + 1u);  // beyond every candidate
  j = judgeImage(r, other);
  EXPECT_EQ(j.unexplained, 2u);
  EXPECT_EQ(j.explained, 0u);
}

TEST(Judge, AnImageOfTheWrongSizeIsAnError) {
  const BoundedRender r = renderWithBounds("depth");
  std::vector<uint8_t> shorter(r.pixels.begin(), r.pixels.end() - 4);
  EXPECT_THROW(judgeImage(r, shorter), Error);
}

}  // namespace tessera
