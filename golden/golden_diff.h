// One rendered image against its golden file, bit for bit.
//
// Implements: the verdict of `tessera golden check` for one image. It matches when the golden file's
// decoded pixels are the rendered bytes and the manifest's image_sha256 is their hash. Otherwise the
// reason says what differs, in this order of precedence: no manifest entry; the file cannot be read
// (the reader's message, naming the file); another size or format (another byte count); how many pixels
// differ and the largest |delta| of a channel (base/image_diff.h: a pixel differs when its bytes do;
// NonFiniteRule::Ieee, so a NaN delta never is the largest and an infinite one is); the manifest's hash.
// Does not implement: rendering (golden_images.h), rewriting the file (golden_run.h).
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "golden/manifest.h"
#include "raster/types.h"

namespace tessera::golden {

struct GoldenDiff {
  std::string sha256;            // of the rendered pixels
  std::string reason;            // empty: the image matches its golden
  bool shapeDiffers = false;     // the golden file holds another number of bytes
  uint64_t differingPixels = 0;  // 0 unless both images were read and have the same shape
  double maxAbsDelta = 0.0;      // over every channel of the differing pixels, channel units

  bool matches() const { return reason.empty(); }
};

// `pixels`: the rendered image as imagePixels() lays it out (top row first) in `format`. `entry` is the
// manifest's entry of this image (nullptr: none); its file is read relative to `dir`.
GoldenDiff diffAgainstGolden(const std::string& dir, const ManifestEntry* entry, std::span<const uint8_t> pixels,
                             Format format);

}  // namespace tessera::golden
