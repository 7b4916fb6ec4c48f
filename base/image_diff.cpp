#include "base/image_diff.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "base/error.h"

namespace tessera {

double ImageDiff::maxAbsDeltaOverChannels() const {
  double m = 0.0;
  for (double d : maxAbsDelta) m = std::max(m, d);
  return m;
}

double ImageDiff::mse() const { return pixels && channels ? sumOfSquares / double(pixels * uint64_t(channels)) : 0.0; }

double ImageDiff::psnr() const { return psnrFromMse(mse(), peak); }

double psnrFromMse(double mse, double peak) {
  if (mse <= 0.0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(peak * peak / mse);
}

ImageDiffAccumulator::ImageDiffAccumulator(int channels, const ImageDiffRules& rules, std::vector<double> channelPeaks)
    : rules_(rules), peaks_(std::move(channelPeaks)) {
  if (channels < 0) throw Error("image diff: negative channel count " + std::to_string(channels));
  if (peaks_.empty()) {
    peaks_.assign(size_t(channels), rules.peak);
  } else if (peaks_.size() != size_t(channels)) {
    throw Error("image diff: " + std::to_string(peaks_.size()) + " channel peaks for " + std::to_string(channels) +
                " channels");
  } else if (!rules.relativeToPeak) {
    // In channel units the sum of squares of channels with different peaks has no single PSNR peak.
    throw Error("image diff: per-channel peaks need relativeToPeak");
  }
  diff_.channels = channels;
  diff_.maxAbsDelta.assign(size_t(channels), 0.0);
  diff_.peak = rules.relativeToPeak ? 1.0 : rules.peak;
}

double ImageDiffAccumulator::add(int c, double expected, double actual) {
  const size_t k = size_t(c);
  double d;
  if (rules_.nonFinite == NonFiniteRule::FullScale) {
    const bool ne = std::isnan(expected), na = std::isnan(actual);
    if (ne || na)
      d = ne && na ? 0.0 : std::numeric_limits<double>::infinity();
    else if (expected == actual)
      d = 0.0;  // also +inf == +inf
    else
      d = std::fabs(expected - actual);  // +inf when either is infinite
    if (std::isinf(d)) {
      diff_.maxAbsDelta[k] = d;
      diff_.sumOfSquares += rules_.relativeToPeak ? 1.0 : peaks_[k] * peaks_[k];
      pixelWorst_ = d;
      return d;
    }
  } else {
    d = std::fabs(expected - actual);
    if (std::isnan(d) || (rules_.nonFinite == NonFiniteRule::Skip && std::isinf(d))) return d;
  }
  diff_.maxAbsDelta[k] = std::max(diff_.maxAbsDelta[k], d);
  const double s = rules_.relativeToPeak ? d / peaks_[k] : d;
  diff_.sumOfSquares += s * s;
  pixelWorst_ = std::max(pixelWorst_, d);
  return d;
}

void ImageDiffAccumulator::endPixel(bool differs) {
  ++diff_.pixels;
  diff_.differingPixels += differs ? 1 : 0;
  diff_.pixelsWithinTolerance += pixelWorst_ <= rules_.tolerance ? 1 : 0;
  pixelWorst_ = 0.0;
}

namespace {

double channelValue(DiffChannelType type, const uint8_t* pixel, int c) {
  switch (type) {
    case DiffChannelType::UInt8:
      return pixel[c];
    case DiffChannelType::UInt32: {
      uint32_t u;
      std::memcpy(&u, pixel + 4 * c, 4);
      return u;
    }
    case DiffChannelType::Float32: {
      float f;
      std::memcpy(&f, pixel + 4 * c, 4);
      return f;
    }
  }
  return 0.0;
}

}  // namespace

ImageDiff diffPixels(std::span<const uint8_t> expected, std::span<const uint8_t> actual, DiffChannelType type,
                     int channels, const ImageDiffRules& rules, int channelsCounted) {
  if (channels < 1) throw Error("image diff: " + std::to_string(channels) + " channels per pixel");
  const int counted = channelsCounted ? channelsCounted : channels;
  if (counted < 1 || counted > channels)
    throw Error("image diff: " + std::to_string(channelsCounted) + " channels counted of " + std::to_string(channels));
  const size_t channelBytes = type == DiffChannelType::UInt8 ? 1 : 4;
  const size_t pixelBytes = channelBytes * size_t(channels), countedBytes = channelBytes * size_t(counted);
  if (expected.size() != actual.size())
    throw Error("image diff: the images have " + std::to_string(expected.size()) + " and " +
                std::to_string(actual.size()) + " bytes");
  if (expected.size() % pixelBytes)
    throw Error("image diff: " + std::to_string(expected.size()) + " bytes are not whole pixels of " +
                std::to_string(pixelBytes) + " bytes");
  ImageDiffAccumulator acc(counted, rules);
  for (size_t i = 0; i < expected.size(); i += pixelBytes) {
    const uint8_t* e = expected.data() + i;
    const uint8_t* a = actual.data() + i;
    if (std::memcmp(e, a, countedBytes) == 0) {
      acc.endPixel(false);
      continue;
    }
    for (int c = 0; c < counted; ++c) acc.add(c, channelValue(type, e, c), channelValue(type, a, c));
    acc.endPixel(true);
  }
  return acc.result();
}

}  // namespace tessera
