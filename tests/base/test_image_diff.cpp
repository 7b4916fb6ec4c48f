// base/image_diff.h: differing pixels, maxima, MSE and PSNR of small images whose differences are
// worked out by hand in each test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "base/error.h"
#include "base/image_diff.h"

namespace tessera {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN(), kInff = std::numeric_limits<float>::infinity();

std::vector<uint8_t> floats(std::initializer_list<float> values) {
  std::vector<uint8_t> out(values.size() * 4);
  size_t i = 0;
  for (float v : values) std::memcpy(&out[4 * i++], &v, 4);
  return out;
}

}  // namespace

TEST(ImageDiff, IdenticalImagesHaveNoDifferenceAndAnInfinitePsnr) {
  const std::vector<uint8_t> a = {1, 2, 3, 4, 5, 6, 7, 8};
  const ImageDiff d = diffPixels(a, a, DiffChannelType::UInt8, 4, {});
  EXPECT_EQ(d.pixels, 2u);
  EXPECT_EQ(d.differingPixels, 0u);
  EXPECT_EQ(d.pixelsWithinTolerance, 2u);
  EXPECT_EQ(d.sumOfSquares, 0.0);
  EXPECT_EQ(d.mse(), 0.0);
  EXPECT_EQ(d.psnr(), kInf);
}

TEST(ImageDiff, OneChannelOffByTenGivesTheMseOverEveryChannelOfEveryPixel) {
  // Two RGBA8 pixels, the green of the second differs by 10: sum of squares 100 over 8 values.
  const std::vector<uint8_t> a = {0, 0, 0, 255, 50, 60, 70, 255}, b = {0, 0, 0, 255, 50, 70, 70, 255};
  const ImageDiff d = diffPixels(a, b, DiffChannelType::UInt8, 4, {});
  EXPECT_EQ(d.differingPixels, 1u);
  EXPECT_EQ(d.sumOfSquares, 100.0);
  EXPECT_EQ(d.mse(), 12.5);
  EXPECT_EQ(d.maxAbsDelta, (std::vector<double>{0, 10, 0, 0}));
  EXPECT_EQ(d.maxAbsDeltaOverChannels(), 10.0);
  // 65025 / 12.5 = 5202.
  EXPECT_DOUBLE_EQ(d.psnr(), 10.0 * std::log10(5202.0));
}

TEST(ImageDiff, ChannelsNotCountedEnterNothing) {
  // Only alpha differs; with RGB counted the pixel is equal, and the MSE is over 3 values per pixel.
  const std::vector<uint8_t> a = {9, 9, 9, 0, 10, 20, 30, 0}, b = {9, 9, 9, 200, 13, 20, 30, 0};
  const ImageDiff d = diffPixels(a, b, DiffChannelType::UInt8, 4, {}, 3);
  EXPECT_EQ(d.channels, 3);
  EXPECT_EQ(d.differingPixels, 1u);  // the second pixel's red
  EXPECT_EQ(d.maxAbsDelta, (std::vector<double>{3, 0, 0}));
  EXPECT_EQ(d.mse(), 9.0 / 6.0);
}

TEST(ImageDiff, ToleranceCountsPixelsWhoseLargestDeltaIsWithinIt) {
  // Largest deltas per pixel: 0, 4, 5 (and 2 in another channel of the last).
  const std::vector<uint8_t> a = {10, 10, 10, 10, 10, 10}, b = {10, 10, 14, 10, 8, 15};
  ImageDiffRules rules;
  rules.tolerance = 4;
  const ImageDiff d = diffPixels(a, b, DiffChannelType::UInt8, 2, rules);
  EXPECT_EQ(d.pixels, 3u);
  EXPECT_EQ(d.pixelsWithinTolerance, 2u);
  EXPECT_EQ(d.sumOfSquares, 16.0 + 4.0 + 25.0);
}

TEST(ImageDiff, RelativeToPeakSquaresTheFractionOfFullScale) {
  // 51 of 255 is 0.2 of full scale: one value of two, so MSE = 0.2^2 / 2 and PSNR = 10 log10(1 / MSE).
  ImageDiffRules rules;
  rules.relativeToPeak = true;
  ImageDiffAccumulator acc(2, rules);
  acc.add(0, 100.0, 49.0);
  acc.add(1, 7.0, 7.0);
  acc.endPixel(true);
  const ImageDiff& d = acc.result();
  const double rel = 51.0 / 255.0;
  EXPECT_EQ(d.sumOfSquares, rel * rel);
  EXPECT_EQ(d.peak, 1.0);
  EXPECT_EQ(d.maxAbsDelta[0], 51.0);  // maxima stay in channel units
  EXPECT_DOUBLE_EQ(d.psnr(), 10.0 * std::log10(2.0 / (rel * rel)));
}

TEST(ImageDiff, PerChannelPeaksScaleEachChannelByItsOwnPeak) {
  ImageDiffRules rules;
  rules.relativeToPeak = true;
  ImageDiffAccumulator acc(2, rules, {255.0, 1.0});
  acc.add(0, 255.0, 0.0);  // full scale: 1
  acc.add(1, 0.5, 0.0);    // half scale: 0.25
  acc.endPixel(true);
  EXPECT_EQ(acc.result().sumOfSquares, 1.25);
}

TEST(ImageDiff, PerChannelPeaksWithoutRelativeSquaresAreRefused) {
  EXPECT_THROW(ImageDiffAccumulator(2, ImageDiffRules{}, {255.0, 1.0}), Error);
  ImageDiffRules rules;
  rules.relativeToPeak = true;
  EXPECT_THROW(ImageDiffAccumulator(2, rules, {255.0}), Error);
}

TEST(ImageDiff, SkipLeavesNonFiniteDeltasOutOfMaximaSumsAndTolerance) {
  ImageDiffRules rules;
  rules.nonFinite = NonFiniteRule::Skip;
  rules.peak = 1.0;
  ImageDiffAccumulator acc(1, rules);
  EXPECT_TRUE(std::isnan(acc.add(0, kNaN, 1.0)));
  acc.endPixel(true);
  EXPECT_EQ(acc.add(0, kInf, 1.0), kInf);
  acc.endPixel(true);
  EXPECT_EQ(acc.add(0, 0.5, 0.25), 0.25);
  acc.endPixel(true);
  const ImageDiff& d = acc.result();
  EXPECT_EQ(d.maxAbsDelta[0], 0.25);
  EXPECT_EQ(d.sumOfSquares, 0.0625);
  EXPECT_EQ(d.pixelsWithinTolerance, 2u);  // tolerance 0: the NaN and infinite pixels count as 0
  EXPECT_EQ(d.mse(), 0.0625 / 3.0);
}

TEST(ImageDiff, IeeeIgnoresNaNButKeepsAnInfiniteDelta) {
  ImageDiffRules rules;
  rules.nonFinite = NonFiniteRule::Ieee;
  const std::vector<uint8_t> a = floats({kNaNf, 2.0f, 1.0f}), b = floats({1.0f, 2.0f, -kInff});
  ImageDiff d = diffPixels(a, b, DiffChannelType::Float32, 1, rules);
  EXPECT_EQ(d.differingPixels, 2u);
  EXPECT_EQ(d.maxAbsDelta[0], kInf);
  EXPECT_EQ(d.sumOfSquares, kInf);
  EXPECT_EQ(d.psnr(), -kInf);
  // Without the infinity the NaN alone leaves the maximum at 0.
  d = diffPixels(floats({kNaNf}), floats({1.0f}), DiffChannelType::Float32, 1, rules);
  EXPECT_EQ(d.differingPixels, 1u);
  EXPECT_EQ(d.maxAbsDelta[0], 0.0);
}

TEST(ImageDiff, FullScaleEqualsNaNToNaNAndMakesOtherNonFiniteMismatchesFullScaleErrors) {
  ImageDiffRules rules;
  rules.nonFinite = NonFiniteRule::FullScale;
  rules.peak = 2.0;
  ImageDiffAccumulator acc(1, rules);
  EXPECT_EQ(acc.add(0, kNaN, kNaN), 0.0);
  acc.endPixel(false);
  EXPECT_EQ(acc.add(0, kInf, kInf), 0.0);
  acc.endPixel(false);
  EXPECT_EQ(acc.add(0, kNaN, 0.0), kInf);
  acc.endPixel(true);
  EXPECT_EQ(acc.add(0, 1.0, -kInf), kInf);
  acc.endPixel(true);
  const ImageDiff& d = acc.result();
  EXPECT_EQ(d.maxAbsDelta[0], kInf);
  EXPECT_EQ(d.sumOfSquares, 8.0);  // two errors of peak^2 = 4
  EXPECT_EQ(d.differingPixels, 2u);
  EXPECT_EQ(d.pixelsWithinTolerance, 2u);
  // MSE 8 / 4 = 2, PSNR 10 log10(4 / 2).
  EXPECT_DOUBLE_EQ(d.psnr(), 10.0 * std::log10(2.0));
}

TEST(ImageDiff, ABytewiseDifferenceWithoutAValueDifferenceStillDiffers) {
  // -0 and +0 differ in their bytes, not in value: the pixel differs with |delta| 0.
  const ImageDiff d = diffPixels(floats({-0.0f}), floats({0.0f}), DiffChannelType::Float32, 1, {});
  EXPECT_EQ(d.differingPixels, 1u);
  EXPECT_EQ(d.maxAbsDelta[0], 0.0);
  EXPECT_EQ(d.psnr(), kInf);
}

TEST(ImageDiff, UnsignedThirtyTwoBitChannelsAreReadLittleEndian) {
  // 1000 = 0x3e8 and 3.
  const std::vector<uint8_t> a = {0xe8, 0x03, 0, 0}, b = {3, 0, 0, 0};
  const ImageDiff d = diffPixels(a, b, DiffChannelType::UInt32, 1, {});
  EXPECT_EQ(d.maxAbsDelta[0], 997.0);
  EXPECT_EQ(d.sumOfSquares, 994009.0);
}

TEST(ImageDiff, ArraysOfDifferentSizesOrPartialPixelsAreRefused) {
  const std::vector<uint8_t> four(4), eight(8), six(6);
  EXPECT_THROW(diffPixels(four, eight, DiffChannelType::UInt8, 4, {}), Error);
  EXPECT_THROW(diffPixels(six, six, DiffChannelType::UInt8, 4, {}), Error);
  EXPECT_THROW(diffPixels(four, four, DiffChannelType::UInt8, 4, {}, 5), Error);
}

TEST(ImageDiff, PsnrOfZeroMseIsInfiniteAndOtherwiseFollowsTheFormula) {
  EXPECT_EQ(psnrFromMse(0.0, 255.0), kInf);
  EXPECT_DOUBLE_EQ(psnrFromMse(1.0, 10.0), 20.0);  // 10 log10(100)
  EXPECT_DOUBLE_EQ(psnrFromMse(0.01, 1.0), 20.0);  // 10 log10(100)
}

}  // namespace tessera
