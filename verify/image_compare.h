// Image comparison with idiff's exit-code semantics, for goldens and oracle-vs-GL checks.
//
// Implements compareImages(A, B): A is the expected image, B the actual one. Both are read with
// image_read.h (any OIIO-readable file; channel types kept as stored). Status, as idiff:
//   0 PASS, 1 WARN, 2 FAIL, 3 size/format mismatch (different width, height, data window origin,
//   channel count or any channel's type; also deep/volume files and unsupported types): refused,
//   never compared; 4 I/O error: a file cannot be opened or read (the message names it).
// Units. Every per-channel threshold and difference is in the units of the channel's stored type:
//   integer channels (8-bit PNG, 16-bit, uint32 EXR ids) in integer steps, i.e. LSBs for 8-bit;
//   float channels (half, float, double) in absolute value.
// Decision. A pixel FAILS when any channel's |A - B| > failThreshold, WARNS when > warnThreshold.
//   FAIL when failing pixels > failPercent % of the pixels; else WARN when warning pixels >
//   warnPercent %; else PASS. failThreshold 0 is exact. warnThreshold defaults to failThreshold
//   (idiff's default of 1e-6 would turn every tolerated difference into a warning).
// NaN and infinities. NaN vs NaN is equal (|Δ| = 0); NaN vs anything else and +inf vs anything but
//   +inf (same for -inf) is a non-finite mismatch: |Δ| = +inf, above every threshold. Non-finite
//   mismatches count in max_abs_diff (as inf) but not in mean_abs_diff; PSNR takes them as a
//   full-scale error.
// Statistics. exact_match_percent = pixels with every channel equal; max / mean |Δ| per channel;
//   PSNR = 10 log10(1 / mean((Δ / peak)^2)) over all channels, peak = the type's maximum (255 for
//   8-bit, 1 for floats), +inf for identical images (|Δ|, the maxima and the PSNR are base/image_diff.h's,
//   with NonFiniteRule::FullScale and relativeToPeak); the error histogram counts pixels by the largest
//   channel |Δ| in histogram units (integer steps for integer channels, 1/255 for float channels),
//   rounded up, in bins 0, 1, 2, 3-4, 5-8, 9-16, 17-32, 33-64, 65-128, 129-255 (the last bin takes
//   everything >= 129, non-finite mismatches included), so the bins sum to the pixel count.
// Coordinates are image-file coordinates: (0, 0) is the top-left pixel (plus the data window origin).
// Does not implement: perceptual metrics, masks, the CLI (callers wire `tessera compare`).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace tessera::verify {

struct DecodedImage;

enum class CompareStatus : int { Pass = 0, Warn = 1, Fail = 2, Mismatch = 3, IoError = 4 };
const char* compareStatusName(CompareStatus s);  // "pass", "warn", "fail", "mismatch", "io_error"

struct CompareOptions {
  double failThreshold = 0.0;
  double failPercent = 0.0;
  std::optional<double> warnThreshold;  // unset: = failThreshold
  double warnPercent = 0.0;
  size_t maxListed = 20;  // first differing pixels kept
};

constexpr int kHistogramBins = 10;
extern const std::array<const char*, kHistogramBins> kHistogramLabels;

struct PixelDifference {
  int32_t x = 0, y = 0;
  std::vector<double> a, b;
};

struct CompareResult {
  CompareStatus status = CompareStatus::IoError;
  std::string message;  // one line, idiff-like; for 3 and 4 it names the file / the difference
  std::string pathA, pathB;
  CompareOptions options;
  double warnThreshold = 0;  // the effective one
  int32_t width = 0, height = 0, channels = 0;
  std::vector<std::string> channelNames, channelTypes;
  std::vector<std::string> channelUnits;  // "lsb" (integer steps) or "abs"
  uint64_t pixels = 0, differingPixels = 0, failingPixels = 0, warningPixels = 0, nonfiniteMismatches = 0;
  double exactMatchPercent = 0;
  std::vector<double> maxAbsDiff, meanAbsDiff;  // per channel, channel units (+inf for non-finite)
  int32_t maxX = 0, maxY = 0, maxChannel = 0;   // where the largest difference is
  double psnr = 0;                              // +inf when identical
  std::array<uint64_t, kHistogramBins> histogram{};
  std::vector<PixelDifference> firstDifferences;

  // The decoded images and the per-pixel histogram bin, for writeCompareReport (absent for 3 / 4).
  struct Images {
    std::shared_ptr<const DecodedImage> a, b;
    std::vector<uint8_t> bin;  // per pixel: histogram bin, or kNonFiniteBin
  };
  static constexpr uint8_t kNonFiniteBin = kHistogramBins;
  std::shared_ptr<const Images> images;

  int exitCode() const { return int(status); }
};

CompareResult compareImages(const std::string& pathA, const std::string& pathB, const CompareOptions& options = {});

nlohmann::json compareToJson(const CompareResult& result);

}  // namespace tessera::verify
