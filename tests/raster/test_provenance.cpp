// Provenance mode: the same bytes as the fast path, plus intervals that always contain the value.
#include <gtest/gtest.h>

#include "raster/provenance.h"
#include "tests/raster/render_helpers.h"
#include "tools/scenes/scenes.h"

using namespace tessera;

class ProvenanceMode : public ::testing::TestWithParam<std::string> {};

TEST_P(ProvenanceMode, ValuesMatchTheFastPathAndLieInsideTheirIntervals) {
  const scenes::SceneInfo* info = scenes::find(GetParam());
  const CommandList cl = scenes::build(info->name, info->width, info->height);
  const auto fast = tessera::testing::renderList(cl, 2);
  CpuBackend b(RenderOptions{2, true});
  b.execute(cl, GetParam());
  const auto images = b.presented();
  ASSERT_EQ(images.size(), fast.hashes.size());
  size_t classed = 0, pixels = 0;
  for (size_t i = 0; i < images.size(); ++i) {
    const TextureData& t = *b.texture(images[i].texture);
    EXPECT_EQ(imageSha256(t, images[i].level, images[i].layer), fast.hashes[i]) << "provenance changed the bytes";
    ASSERT_TRUE(t.prov) << "no interval images for a presented target";
    const auto v = imagePixels(t, images[i].level, images[i].layer);
    const auto lo = imagePixels(*t.prov->lo, images[i].level, images[i].layer);
    const auto hi = imagePixels(*t.prov->hi, images[i].level, images[i].layer);
    if (isUnorm(t.desc.format)) {
      for (size_t k = 0; k < v.size(); ++k) {
        ASSERT_LE(lo[k], v[k]) << "byte " << k;
        ASSERT_GE(hi[k], v[k]) << "byte " << k;
      }
    }
    for (uint16_t c : t.prov->classes[images[i].level]) classed += c != 0, ++pixels;
  }
  std::printf("%s: %zu of %zu pixels classed\n", GetParam().c_str(), classed, pixels);
}

INSTANTIATE_TEST_SUITE_P(AllScenes, ProvenanceMode, ::testing::ValuesIn([] {
                           std::vector<std::string> names;
                           for (const auto& s : scenes::all()) names.emplace_back(s.name);
                           return names;
                         }()),
                         [](const auto& param) { return param.param; });
