// `crosscheck --stability` (verify/stability.h): conditions whose GL output changes are reported as
// "GL nondeterministic / fast-path dependent", naming the first draw whose output changes.
#include <gtest/gtest.h>

#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "tools/scenes/scenes.h"
#include "verify/stability.h"

namespace tessera::verify {

namespace {

// The oracle's images of the list (through draw `through`), standing in for GL.
std::vector<std::vector<uint8_t>> renderImages(const CommandList& list, std::optional<size_t> through) {
  CommandList l = list;
  size_t draws = 0;
  if (through)
    for (size_t i = 0; i < l.commands().size(); ++i)
      if (std::holds_alternative<Draw>(l.commands()[i]) && draws++ == *through) {
        l.truncate(i + 1);
        break;
      }
  CpuBackend b;
  b.execute(l, "stability");
  std::vector<std::vector<uint8_t>> out;
  for (const PresentedImage& p : b.presented()) out.push_back(imagePixels(*b.texture(p.texture), p.level, p.layer));
  return out;
}

size_t drawsIn(const CommandList& l, std::optional<size_t> through) {
  size_t n = 0;
  for (const Command& c : l.commands()) n += std::holds_alternative<Draw>(c);
  return through ? std::min(n, *through + 1) : n;
}

}  // namespace

TEST(Stability, AConditionThatChangesOneDrawIsReportedWithThatDraw) {
  const CommandList list = scenes::build("wrap_filter", 256, 192);  // 12 draws
  const auto conditions = stabilityConditions(2);
  ASSERT_EQ(conditions[0].name, "reference");
  const size_t bad = 2;
  // "lp_threads_1" corrupts pixel 0 once draw 2 is in the prefix; "repeat_in_process" differs between
  // its two runs once draw 9 is in; everything else is stable.
  auto renderer = [&](const StabilityCondition& c, std::optional<size_t> through) {
    GlRuns runs;
    for (int r = 0; r < c.runs; ++r) {
      auto imgs = renderImages(list, through);
      if (c.name == "lp_threads_1" && drawsIn(list, through) > bad) imgs[0][0] ^= 0xff;
      if (c.name == "repeat_in_process" && r == 1 && drawsIn(list, through) > 9) imgs[0][4] ^= 1, imgs[0][5] ^= 1;
      runs.push_back(imgs);
    }
    return runs;
  };
  const nlohmann::json j = checkStability(list, conditions, renderer, {size_t(256 * 192)});
  EXPECT_FALSE(j["stable"].get<bool>());
  EXPECT_EQ(j["verdict"].get<std::string>(), "GL nondeterministic / fast-path dependent");
  for (const auto& row : j["conditions"]) {
    const std::string name = row["name"];
    if (name == "lp_threads_1") {
      EXPECT_FALSE(row["identical"].get<bool>());
      EXPECT_EQ(row["images"][0]["differing_pixels"].get<uint64_t>(), 1u);
      EXPECT_EQ(row["first_changing_draw"]["draw_index"].get<size_t>(), bad);
      EXPECT_EQ(row["first_changing_draw"]["state"]["program"].get<std::string>(), "textured");
    } else if (name == "repeat_in_process") {
      EXPECT_FALSE(row["identical"].get<bool>());
      EXPECT_EQ(row["images"][0]["differing_pixels"].get<uint64_t>(), 1u);  // two bytes of pixel 1
      EXPECT_EQ(row["images"][0]["differing_bytes"].get<uint64_t>(), 2u);
      EXPECT_EQ(row["first_changing_draw"]["draw_index"].get<size_t>(), 9u);
    } else {
      EXPECT_TRUE(row["identical"].get<bool>()) << name;
      EXPECT_FALSE(row.contains("first_changing_draw")) << name;
    }
  }
  const nlohmann::json same = checkStability(
      list, conditions,
      [&](const StabilityCondition& c, std::optional<size_t> t) { return GlRuns(c.runs, renderImages(list, t)); },
      {size_t(256 * 192)});
  EXPECT_TRUE(same["stable"].get<bool>());
}

TEST(Stability, TheCatalogueCoversRepeatThreadCountsOneCpuAndStrict) {
  const auto c = stabilityConditions(8);
  std::vector<std::string> names;
  for (const auto& x : c) names.push_back(x.name);
  EXPECT_EQ(names, (std::vector<std::string>{"reference", "repeat_in_process", "another_process", "lp_threads_1",
                                             "lp_threads_8", "one_cpu", "strict"}));
  EXPECT_EQ(c[1].runs, 2);
  EXPECT_TRUE(c[5].oneCpu);
  EXPECT_TRUE(c[6].strict);
  EXPECT_EQ(stabilityConditions(1)[4].name, "lp_threads_2");  // N is at least 2, so it differs from 1
}

}  // namespace tessera::verify
