// How different two images of the same shape are: the one implementation behind the golden check
// (golden/), `tessera compare` (verify/image_compare), the cross-check judgement (verify/judge) and the
// atlas tree's PSNR against original textures (`tessera mta runs`).
//
// Implements: per-channel absolute differences |Δ| = |expected - actual| under a stated rule for
// non-finite values, accumulated pixel after pixel, channel after channel, into
//   - the pixels that differ and the pixels whose largest |Δ| is within a tolerance,
//   - the maximum |Δ| of every channel,
//   - the sum of squares of |Δ| (or of |Δ| / peak), MSE = sum of squares / (pixels × channels) and
//     PSNR = 10 log10(peak² / MSE) in dB, +inf when the MSE is 0.
// Two entry points share that arithmetic: ImageDiffAccumulator, for a caller that visits every pixel
// itself because it decides more per pixel (an interval test, a threshold, a histogram), and
// diffPixels(), for two raw pixel arrays of one channel type.
// Determinism: one thread, values added in the order they are given (pixel order, then channel
// order), in double. 8- and 16-bit differences square exactly and their sums stay exact integers
// (below 2^53), so for them the order cannot matter; for float channels (and large 32-bit integers)
// it does, which is why it is fixed. PSNR calls std::log10: it is a report number, never part of an
// image's bytes.
// The details in which the four callers differed are parameters (ImageDiffRules), not forks:
// what a non-finite value means, whether |Δ| is divided by the peak before squaring, the peak, the
// channels counted, the tolerance. Peak and channel count enter the MSE and PSNR exactly as written
// above, so a caller that used those formulas before gets the same bits from this one.
// Does not implement: reading images (raster/image_io.h, verify/image_read.h), verdicts, thresholds
// in percent or histograms (the callers own what they decide), or differences of images of different
// shapes (a caller reports that before it gets here).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace tessera {

// What a difference involving NaN or an infinity is.
enum class NonFiniteRule : uint8_t {
  // |Δ| = fabs(expected - actual) in IEEE arithmetic; a |Δ| that is not finite (a NaN or infinite
  // operand) enters neither a maximum, nor the sum of squares, nor the tolerance test.
  // The cross-check judgement: its non-finite pixels are judged by interval, not by size.
  Skip,
  // |Δ| = fabs(expected - actual) in IEEE arithmetic; a NaN |Δ| enters nothing (it never exceeds a
  // maximum); an infinite one is the channel's maximum, fails the tolerance and makes the sum of
  // squares infinite (so the MSE is +inf and the PSNR -inf). The golden check's report.
  Ieee,
  // idiff's rule: a NaN equals a NaN and an infinity equals itself (|Δ| = 0); any other difference
  // that involves a NaN or an infinity is |Δ| = +inf (the channel's maximum), and adds a full-scale
  // error to the sum of squares: peak² (1 with relativeToPeak). `tessera compare`.
  FullScale,
};

struct ImageDiffRules {
  NonFiniteRule nonFinite = NonFiniteRule::Skip;
  // Full scale of one channel value: the PSNR's peak and FullScale's error. 255 for 8-bit unorm,
  // 1 for floats (the cross-check uses 1 for every non-unorm format, R32UI included).
  double peak = 255.0;
  // false: square |Δ| in channel units; PSNR = 10 log10(peak² / MSE).
  // true: square |Δ| / peak (each channel's own peak, see ImageDiffAccumulator); the MSE is then a
  // fraction of full scale and PSNR = 10 log10(1 / MSE). `tessera compare` does this because the
  // channels of one image file may have different types and so different peaks. The two are not the
  // same bits: (Δ / p)² rounds differently from Δ² / p².
  bool relativeToPeak = false;
  // A pixel is within tolerance when its largest counted |Δ| is <= tolerance (channel units).
  double tolerance = 0.0;
};

// The statistics of one comparison.
struct ImageDiff {
  uint64_t pixels = 0;
  uint64_t differingPixels = 0;        // as the caller (or diffPixels: the bytes) decided
  uint64_t pixelsWithinTolerance = 0;  // largest counted |Δ| <= rules.tolerance
  int channels = 0;                    // counted per pixel
  std::vector<double> maxAbsDelta;     // per counted channel; 0 where every value is equal
  double sumOfSquares = 0.0;           // of |Δ| or |Δ| / peak, see ImageDiffRules
  double peak = 255.0;                 // the PSNR's: rules.peak, or 1 with relativeToPeak

  // The largest |Δ| over every channel (0 for no channels).
  double maxAbsDeltaOverChannels() const;
  // sumOfSquares / (pixels × channels); 0 when nothing was counted.
  double mse() const;
  // psnrFromMse(mse(), peak).
  double psnr() const;
};

// 10 log10(peak² / mse) in dB; +inf when mse <= 0 (identical images).
double psnrFromMse(double mse, double peak);

// Feeds one image pair's values in order: for every pixel, add() each counted channel (or none when
// the caller already knows the pixel is identical), then endPixel(). Not thread-safe; one per pair.
class ImageDiffAccumulator {
 public:
  // `channels`: channels counted per pixel, the MSE's per-pixel denominator.
  // `channelPeaks`: a peak per channel for channels of different types; only with relativeToPeak
  // (Error otherwise). Empty: rules.peak for every channel.
  ImageDiffAccumulator(int channels, const ImageDiffRules& rules, std::vector<double> channelPeaks = {});

  // Adds channel c (0 <= c < channels) of the current pixel. Returns its |Δ| under the rules: what
  // entered the maximum and the sum, or for Skip and Ieee a non-finite value that did not (Ieee: an
  // infinity did), for the caller's own per-pixel decisions.
  double add(int c, double expected, double actual);
  // Closes the current pixel; `differs` is the caller's judgement of whether it differs at all (bytes,
  // or any |Δ| != 0). A pixel closed without add() counts as |Δ| = 0 in every channel.
  void endPixel(bool differs);

  const ImageDiff& result() const { return diff_; }

 private:
  ImageDiffRules rules_;
  std::vector<double> peaks_;
  ImageDiff diff_;
  double pixelWorst_ = 0.0;  // largest |Δ| of the current pixel that counts for the tolerance
};

// Channel types of raw pixel arrays (little-endian, as the raster formats and image_io.h lay them out).
enum class DiffChannelType : uint8_t { UInt8, UInt32, Float32 };

// Compares two raw arrays of pixels of `channels` interleaved channels of one type. The first
// `channelsCounted` channels of each pixel enter the statistics (0 = all; `mta runs` counts RGB of
// RGBA). A pixel differs when the bytes of its counted channels differ: -0 vs +0 and two NaNs with
// different payloads differ, although their |Δ| is 0 or not finite; equal bytes skip the channels.
// Throws Error when the arrays differ in size or are not whole pixels.
ImageDiff diffPixels(std::span<const uint8_t> expected, std::span<const uint8_t> actual, DiffChannelType type,
                     int channels, const ImageDiffRules& rules, int channelsCounted = 0);

}  // namespace tessera
