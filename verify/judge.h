// Judging another implementation's image against the oracle's provenance, pixel by pixel.
//
// Implements the cross-check rule of docs/crosscheck.md: a pixel with no ambiguity class must match
// bit for bit (whatever its interval); a classed pixel must lie inside one of its candidates' boxes in
// every channel (provenance.h); anything else is unexplained. Also gathers what a reader needs to see why: counts
// per class, exact-match %, max |delta| per channel in LSBs, an error histogram, PSNR and the first
// unexplained pixels with both values and their provenance. The max |delta| and the MSE / PSNR are
// base/image_diff.h's (NonFiniteRule::Skip, peak 255 for unorm formats, 1 otherwise).
// Does not implement: rendering either image (cpu_backend.h, gl/), or reports on disk (crosscheck_report.h).
#pragma once

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "raster/provenance.h"
#include "raster/texture.h"

namespace tessera::verify {

struct PixelRecord {
  int32_t x, y;  // image coordinates, top row = 0 (as in the files)
  std::array<double, 4> oracle, other, lo, hi;
  uint16_t classes;
};

// How permissive the verdict was for the pixels of one class: the width of their hull per channel
// and the size of their candidate sets.
struct ClassStats {
  uint64_t pixels = 0;
  std::array<double, 4> widthSum{}, widthMax{};  // hi - lo of the hull (LSBs for unorm), per channel
  uint64_t candidateSum = 0;                     // candidates per pixel (1 = the hull alone)
  uint64_t candidateMax = 0;
  uint64_t fallbacks = 0;        // pixels whose set outgrew kMaxCandidates and fell back to the hull
  uint64_t lookupFallbacks = 0;  // pixels whose lookups were used as their hull (kLookupFallback)
};

struct Judgement {
  Format format = Format::RGBA8;
  int width = 0, height = 0, channels = 0;
  uint64_t pixels = 0;
  uint64_t exact = 0;          // identical bytes
  uint64_t classed = 0;        // pixels with at least one ambiguity class
  uint64_t explained = 0;      // differing, inside their interval
  uint64_t unexplained = 0;    // differing, outside their interval (failures)
  std::array<uint64_t, kClassCount> classPixels{};     // pixels carrying each class
  std::array<uint64_t, kClassCount> classExplained{};  // explained pixels carrying each class
  std::array<ClassStats, kClassCount> classStats{};
  uint64_t fallbacks = 0;        // pixels whose candidate set fell back to its hull (kFallback)
  uint64_t multiCandidate = 0;   // pixels with two or more candidates
  uint64_t lookupForked = 0;     // pixels whose candidates came from a lookup's candidates (kLookupForked)
  uint64_t lookupFallbacks = 0;  // pixels whose lookups were used as their hull (kLookupFallback)
  std::array<double, 4> maxAbsDiff{};                  // LSBs for unorm, value units otherwise
  std::array<uint64_t, 10> histogram{};  // same bins as image_compare.h kHistogramBins  // |delta| in LSB: 0, 1, 2, 3-4, 5-8, 9-16, 17-32, 33-64, 65-128, 129+
  double mse = 0.0;                      // mean squared error over channels, in LSB^2 for unorm
  std::vector<PixelRecord> firstUnexplained;  // up to kMaxRecords
  std::vector<uint16_t> classMap;    // per pixel (top-down), for overlays
  std::vector<uint8_t> failMap;      // per pixel: 0 exact, 1 explained, 2 unexplained
  static constexpr size_t kMaxRecords = 20;

  double exactPercent() const { return pixels ? 100.0 * double(exact) / double(pixels) : 100.0; }
  double psnr() const;  // dB over the unorm range (255) or value range 1; +inf when identical
  bool passed() const { return unexplained == 0; }
};

// Judges `other` (pixels laid out as imagePixels(): top row first, the texture's format) against the
// oracle texture `tex` at (level, layer), which must have been rendered in provenance mode.
Judgement judge(const TextureData& tex, uint32_t level, uint32_t layer, const std::vector<uint8_t>& other);

nlohmann::json toJson(const Judgement& j);

}  // namespace tessera::verify
