// The idiff-compatible image comparison and its report directory.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "raster/image_io.h"
#include "raster/image_module.h"
#include "verify/compare_report.h"
#include "verify/image_compare.h"

namespace tessera::verify {
namespace fs = std::filesystem;

namespace {

// A fresh directory per test.
std::string testDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path d =
      fs::path(::testing::TempDir()) / "tessera_verify" / (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

template <typename T>
std::string writeFile(const std::string& path, int w, int h, int channels, imagemod::Type type, const std::vector<T>& px) {
  imagemod::WriteSpec spec;
  spec.width = w, spec.height = h, spec.channels = channels, spec.type = type;
  spec.alphaLast = channels == 4;
  EXPECT_EQ(imagemod::api().write(path, path, spec, px.data()), "") << path;
  return path;
}

std::string png8(const std::string& path, int w, int h, const std::vector<uint8_t>& rgba) {
  writePngRGBA8(path, w, h, rgba.data());
  return path;
}

std::string readText(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::vector<uint8_t> gradient(int w, int h) {
  std::vector<uint8_t> px(size_t(w) * size_t(h) * 4);
  for (size_t i = 0; i < px.size(); ++i) px[i] = uint8_t((i * 7) % 251);
  return px;
}

}  // namespace

TEST(Compare, IdenticalImagesPassWithInfinitePsnr) {
  const std::string d = testDir();
  const auto px = gradient(17, 9);
  const CompareResult r = compareImages(png8(d + "/a.png", 17, 9, px), png8(d + "/b.png", 17, 9, px));
  EXPECT_EQ(r.exitCode(), 0) << r.message;
  EXPECT_EQ(r.differingPixels, 0u);
  EXPECT_EQ(r.exactMatchPercent, 100.0);
  EXPECT_TRUE(std::isinf(r.psnr));
  EXPECT_EQ(r.histogram[0], r.pixels);
  EXPECT_EQ(compareToJson(r)["psnr"], "inf");
  EXPECT_EQ(r.channelUnits[0], "lsb");
}

TEST(Compare, OneLsbDifferencePassesAtFailOneAndFailsAtZero) {
  const std::string d = testDir();
  auto a = gradient(8, 8), b = a;
  b[4 * 10 + 1] = uint8_t(b[4 * 10 + 1] + 1);  // pixel (2, 1), green, +1 LSB
  png8(d + "/a.png", 8, 8, a), png8(d + "/b.png", 8, 8, b);
  CompareOptions loose;
  loose.failThreshold = 1;
  const CompareResult pass = compareImages(d + "/a.png", d + "/b.png", loose);
  EXPECT_EQ(pass.exitCode(), 0) << pass.message;
  EXPECT_EQ(pass.differingPixels, 1u);
  EXPECT_EQ(pass.maxAbsDiff[1], 1.0);
  const CompareResult fail = compareImages(d + "/a.png", d + "/b.png");
  EXPECT_EQ(fail.exitCode(), 2) << fail.message;
  EXPECT_EQ(fail.failingPixels, 1u);
  ASSERT_EQ(fail.firstDifferences.size(), 1u);
  EXPECT_EQ(fail.firstDifferences[0].x, 2);
  EXPECT_EQ(fail.firstDifferences[0].y, 1);
  EXPECT_EQ(fail.firstDifferences[0].b[1] - fail.firstDifferences[0].a[1], 1.0);
  CompareOptions warn = loose;
  warn.warnThreshold = 0;
  EXPECT_EQ(compareImages(d + "/a.png", d + "/b.png", warn).exitCode(), 1);
}

TEST(Compare, PercentThresholdsCountPixelsLikeIdiff) {
  const std::string d = testDir();
  auto a = gradient(10, 10), b = a;
  for (int p : {3, 50, 97}) b[size_t(p) * 4] = uint8_t(b[size_t(p) * 4] ^ 0x10);  // 3 % of the pixels
  png8(d + "/a.png", 10, 10, a), png8(d + "/b.png", 10, 10, b);
  CompareOptions o;
  o.failPercent = 3;                                                      // 3 failing pixels are not more than 3 %
  EXPECT_EQ(compareImages(d + "/a.png", d + "/b.png", o).exitCode(), 1);  // but they exceed warn 0 %
  o.warnPercent = 3;
  EXPECT_EQ(compareImages(d + "/a.png", d + "/b.png", o).exitCode(), 0);
  o.failPercent = 2.9;
  EXPECT_EQ(compareImages(d + "/a.png", d + "/b.png", o).exitCode(), 2);
}

TEST(Compare, SizeChannelOrTypeMismatchIsRefusedWithThree) {
  const std::string d = testDir();
  png8(d + "/a.png", 8, 8, gradient(8, 8));
  png8(d + "/wide.png", 9, 8, gradient(9, 8));
  const CompareResult size = compareImages(d + "/a.png", d + "/wide.png");
  EXPECT_EQ(size.exitCode(), 3);
  EXPECT_NE(size.message.find("9x8"), std::string::npos) << size.message;
  EXPECT_EQ(size.pixels, 0u);  // never compared
  writeFile(d + "/rgb.png", 8, 8, 3, imagemod::Type::U8, std::vector<uint8_t>(8 * 8 * 3, 1));
  EXPECT_EQ(compareImages(d + "/a.png", d + "/rgb.png").exitCode(), 3);
  writeFile(d + "/f.exr", 8, 8, 4, imagemod::Type::Float, std::vector<float>(8 * 8 * 4, 0.5f));
  const CompareResult type = compareImages(d + "/a.png", d + "/f.exr");
  EXPECT_EQ(type.exitCode(), 3);
  EXPECT_NE(type.message.find("float"), std::string::npos) << type.message;
}

TEST(Compare, UnreadableFilesAreIoErrorsNamingTheFile) {
  const std::string d = testDir();
  png8(d + "/a.png", 4, 4, gradient(4, 4));
  const std::string missing = d + "/does_not_exist.png";
  const CompareResult r = compareImages(d + "/a.png", missing);
  EXPECT_EQ(r.exitCode(), 4);
  EXPECT_NE(r.message.find(missing), std::string::npos) << r.message;
  std::ofstream(d + "/garbage.png") << "not a png";
  const CompareResult both = compareImages(d + "/garbage.png", missing);
  EXPECT_EQ(both.exitCode(), 4);
  EXPECT_NE(both.message.find("garbage.png"), std::string::npos) << both.message;
  EXPECT_NE(both.message.find(missing), std::string::npos) << both.message;
}

TEST(Compare, NanEqualsNanAndNothingElse) {
  const std::string d = testDir();
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  // Pixel: NaN/NaN (equal), NaN/0.5 (mismatch), inf/inf (equal), inf/-inf (mismatch), 0.25/0.25.
  const std::vector<float> a = {nan, nan, inf, inf, 0.25f}, b = {nan, 0.5f, inf, -inf, 0.25f};
  writeFile(d + "/a.exr", 5, 1, 1, imagemod::Type::Float, a);
  writeFile(d + "/b.exr", 5, 1, 1, imagemod::Type::Float, b);
  CompareOptions huge;
  huge.failThreshold = 1e30;
  const CompareResult r = compareImages(d + "/a.exr", d + "/b.exr", huge);
  EXPECT_EQ(r.exitCode(), 2) << "a non-finite mismatch is above every threshold";
  EXPECT_EQ(r.differingPixels, 2u);
  EXPECT_EQ(r.nonfiniteMismatches, 2u);
  EXPECT_EQ(r.firstDifferences[0].x, 1);
  EXPECT_EQ(r.firstDifferences[1].x, 3);
  EXPECT_EQ(r.meanAbsDiff[0], 0.0);  // non-finite mismatches are not averaged
  EXPECT_EQ(r.channelUnits[0], "abs");
  const nlohmann::json j = compareToJson(r);
  EXPECT_EQ(j["max_abs_diff"][0], "inf");
  EXPECT_EQ(j["first_differences"][0]["expected"][0], "nan");
  EXPECT_EQ(r.histogram[9], 2u);
}

TEST(Compare, HistogramMeanAndPsnrOfAHandMadePair) {
  const std::string d = testDir();
  const std::vector<int> deltas = {0, 1, 2, 3, 4, 5, 8, 9, 100, 200};
  std::vector<uint8_t> a(deltas.size(), 20), b;
  for (size_t i = 0; i < deltas.size(); ++i) b.push_back(uint8_t(20 + deltas[i]));
  writeFile(d + "/a.png", 10, 1, 1, imagemod::Type::U8, a);
  writeFile(d + "/b.png", 10, 1, 1, imagemod::Type::U8, b);
  const CompareResult r = compareImages(d + "/a.png", d + "/b.png");
  const std::array<uint64_t, kHistogramBins> expected = {1, 1, 1, 2, 2, 1, 0, 0, 1, 1};
  EXPECT_EQ(r.histogram, expected);
  EXPECT_EQ(r.maxAbsDiff[0], 200.0);
  EXPECT_DOUBLE_EQ(r.meanAbsDiff[0], 33.2);
  // MSE = (0 + 1 + 4 + 9 + 16 + 25 + 64 + 81 + 10000 + 40000) / 10 = 5020 LSB^2.
  EXPECT_NEAR(r.psnr, 10.0 * std::log10(255.0 * 255.0 / 5020.0), 1e-12);
  EXPECT_EQ(r.maxX, 9);
  EXPECT_NEAR(r.exactMatchPercent, 10.0, 1e-12);
}

TEST(Compare, Uint32ExrIdsCompareExactlyInIntegerSteps) {
  const std::string d = testDir();
  std::vector<uint32_t> a = {0xffffffffu, 7, 4294967294u, 12}, b = a;
  b[3] = 1012;
  writeFile(d + "/a.exr", 2, 2, 1, imagemod::Type::U32, a);
  writeFile(d + "/b.exr", 2, 2, 1, imagemod::Type::U32, b);
  const CompareResult r = compareImages(d + "/a.exr", d + "/b.exr");
  EXPECT_EQ(r.exitCode(), 2);
  EXPECT_EQ(r.differingPixels, 1u);
  EXPECT_EQ(r.maxAbsDiff[0], 1000.0);
  EXPECT_EQ(r.channelTypes[0], "uint32");
  EXPECT_EQ(r.histogram[9], 1u);
  EXPECT_EQ(r.firstDifferences[0].a[0], 12.0);
}

TEST(Compare, AlphaIsComparedAsStoredNotPremultiplied) {
  const std::string d = testDir();
  // Fully transparent pixels with different colours: premultiplying on read would make them equal.
  png8(d + "/a.png", 1, 1, {200, 100, 50, 0});
  png8(d + "/b.png", 1, 1, {0, 0, 0, 0});
  const CompareResult r = compareImages(d + "/a.png", d + "/b.png");
  EXPECT_EQ(r.exitCode(), 2);
  EXPECT_EQ(r.maxAbsDiff[0], 200.0);
}

TEST(Compare, ReportDirectoryHoldsEveryFileAndThePageReferencesThem) {
  const std::string d = testDir();
  auto a = gradient(40, 30), b = a;
  for (size_t i = 0; i < 40; ++i) b[i * 4 * 7] = uint8_t(b[i * 4 * 7] + (i % 5) * 30);
  png8(d + "/a.png", 40, 30, a), png8(d + "/b.png", 40, 30, b);
  const CompareResult r = compareImages(d + "/a.png", d + "/b.png");
  const std::string report = d + "/report";
  writeCompareReport(r, report);
  for (const char* f : {"report.json", "expected.png", "actual.png", "heatmap.png", "histogram.png", "index.html"})
    EXPECT_TRUE(fs::exists(report + "/" + f)) << f;
  for (const auto& e : fs::directory_iterator(report))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << "temporary left: " << e.path();
  EXPECT_EQ(nlohmann::json::parse(readText(report + "/report.json")), compareToJson(r));
  const std::string html = readText(report + "/index.html");
  for (const char* ref : {"expected.png", "actual.png", "heatmap.png", "histogram.png", "const PIXELS=", "id=\"flip\"",
                          "id=\"inspector\""})
    EXPECT_NE(html.find(ref), std::string::npos) << ref;

  // The heat map: image area, then the legend strip; a differing pixel has its bin's colour.
  std::string error;
  const auto in = imagemod::api().open(report + "/heatmap.png", error);
  ASSERT_TRUE(in) << error;
  const imagemod::Header spec = in->header();
  EXPECT_EQ(spec.width, 330);  // narrower images are padded to the legend's width
  EXPECT_EQ(spec.height, 30 + 22);
  std::vector<uint8_t> heat(size_t(spec.width) * size_t(spec.height) * 4);
  ASSERT_EQ(in->read(imagemod::Type::U8, heat.data()), "");
  const auto& first = r.firstDifferences.at(0);
  const size_t at = (size_t(first.y) * size_t(spec.width) + size_t(first.x)) * 4;
  const Rgba expected = heatColor(r.images->bin[size_t(first.y) * 40 + size_t(first.x)]);
  EXPECT_EQ((Rgba{heat[at], heat[at + 1], heat[at + 2], heat[at + 3]}), expected);
  EXPECT_EQ((Rgba{heat[0], heat[1], heat[2], heat[3]}), heatColor(0));
}

TEST(Compare, RefusedComparisonStillWritesAReport) {
  const std::string d = testDir();
  const CompareResult r = compareImages(d + "/nope_a.png", d + "/nope_b.png");
  writeCompareReport(r, d + "/report");
  EXPECT_TRUE(fs::exists(d + "/report/report.json"));
  EXPECT_FALSE(fs::exists(d + "/report/heatmap.png"));
  EXPECT_NE(readText(d + "/report/index.html").find("nope_a.png"), std::string::npos);
}

}  // namespace tessera::verify
