// Oracle vs GL (Mesa llvmpipe, headless EGL) on every built-in scene: every pixel is exact or inside
// the interval the GL spec allows, and GL issued exactly the calls the oracle counted.
#include <gtest/gtest.h>

#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "tools/scenes/scenes.h"
#include "verify/crosscheck.h"

namespace tessera {

namespace {
gl::GlBackend& glBackend() {
  static std::unique_ptr<gl::GlBackend> b = gl::GlBackend::create({});
  return *b;
}
// Known GL deviations, each pinned to its implementation, version, condition, frame and draw.
const verify::ExpectationSet& expectations() {
  static const verify::ExpectationSet s =
      verify::loadExpectations(std::string(TESSERA_SOURCE_DIR) + "/tests/expectations/gl-deviations.json");
  return s;
}
}  // namespace

class CrosscheckScene : public ::testing::TestWithParam<std::string> {};

TEST_P(CrosscheckScene, EveryGLPixelIsExactOrExplainedAndCountsAreEqual) {
  const scenes::SceneInfo* s = scenes::find(GetParam());
  const CommandList list = scenes::build(s->name, s->width, s->height);
  verify::CrosscheckOptions o;
  o.threads = 2;
  o.expectations = &expectations();
  const verify::CrosscheckResult r = verify::crosscheck(list, GetParam(), o, &glBackend());
  EXPECT_TRUE(r.json["counters"]["equal"].get<bool>()) << r.json["counters"].dump(1);
  EXPECT_EQ(r.json["unexplained"].get<uint64_t>(), 0u) << r.json.dump(1).substr(0, 4000);
  EXPECT_TRUE(r.passed);
  std::printf("[ crosscheck ] %-15s exact %.2f%%, unexplained %llu, expected deviation %llu, renderer %s\n",
              GetParam().c_str(), r.json["exact_match_percent"].get<double>(),
              static_cast<unsigned long long>(r.json["unexplained"].get<uint64_t>()),
              static_cast<unsigned long long>(r.json["expected_deviation"].get<uint64_t>()),
              glBackend().info().toJson().value("gl_renderer", "?").c_str());
}

INSTANTIATE_TEST_SUITE_P(AllScenes, CrosscheckScene, ::testing::ValuesIn([] {
                           std::vector<std::string> names;
                           for (const auto& s : scenes::all()) names.emplace_back(s.name);
                           return names;
                         }()),
                         [](const auto& param) { return param.param; });

TEST(Crosscheck, TheOraclesFastPathAgreesWithItsOwnProvenanceEverywhere) {
  const CommandList list = scenes::build("city_block", 160, 120);
  verify::CrosscheckOptions o;
  o.selfCheck = true;
  const auto r = verify::crosscheck(list, "city_block", o, nullptr);
  EXPECT_TRUE(r.passed);
  EXPECT_DOUBLE_EQ(r.json["exact_match_percent"].get<double>(), 100.0);
}

// A stand-in for GL that renders like the oracle but corrupts one pixel once the frame has at least
// `badDraw + 1` draws: bisection must name exactly that draw.
TEST(Crosscheck, BisectionNamesTheFirstDrawWhoseOutputDiverges) {
  const CommandList list = scenes::build("wrap_filter", 256, 192);  // 12 draws
  size_t drawsInList = 0;
  for (const Command& c : list.commands()) drawsInList += std::holds_alternative<Draw>(c);
  ASSERT_EQ(drawsInList, 12u);
  const size_t badDraw = 7;
  verify::OtherBackend fake{"fake", [&](const CommandList& l, std::string_view name, double& ms) {
                              ms = 0;
                              CpuBackend b;
                              b.execute(l, name);
                              size_t draws = 0;
                              for (const Command& c : l.commands()) draws += std::holds_alternative<Draw>(c);
                              std::vector<std::vector<uint8_t>> out;
                              for (const PresentedImage& p : b.presented())
                                out.push_back(imagePixels(*b.texture(p.texture), p.level, p.layer));
                              if (draws > badDraw) out[0][0] ^= 0x40;  // top-left pixel: background, unclassed
                              return out;
                            }};
  const auto r = verify::crosscheck(list, "wrap_filter", verify::CrosscheckOptions{}, fake);
  EXPECT_FALSE(r.passed);
  ASSERT_TRUE(r.json.contains("first_diverging_draw"));
  EXPECT_EQ(r.json["first_diverging_draw"]["draw_index"].get<size_t>(), badDraw);
  EXPECT_EQ(r.json["first_diverging_draw"]["state"]["program"].get<std::string>(), "textured");
}

}  // namespace tessera
