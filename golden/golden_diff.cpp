#include "golden/golden_diff.h"

#include <fmt/format.h>

#include "base/error.h"
#include "base/image_diff.h"
#include "base/sha256.h"
#include "raster/image_io.h"

namespace tessera::golden {

namespace {

DiffChannelType channelType(Format f) {
  if (isUnorm(f)) return DiffChannelType::UInt8;
  if (isFloat(f)) return DiffChannelType::Float32;
  return DiffChannelType::UInt32;
}

}  // namespace

GoldenDiff diffAgainstGolden(const std::string& dir, const ManifestEntry* entry, std::span<const uint8_t> pixels,
                             Format format) {
  GoldenDiff d;
  d.sha256 = sha256Hex(pixels);
  if (!entry) {
    d.reason = "no golden entry";
    return d;
  }
  std::vector<uint8_t> golden;
  try {
    golden = readImage(dir + "/" + entry->file).pixels;
  } catch (const Error& err) {
    d.reason = err.what();
    return d;
  }
  if (golden.size() != pixels.size()) {
    d.shapeDiffers = true;
    d.reason = "golden image has another size or format";
    return d;
  }
  ImageDiffRules rules;
  rules.nonFinite = NonFiniteRule::Ieee;
  const ImageDiff diff = diffPixels(golden, pixels, channelType(format), channelCount(format), rules);
  d.differingPixels = diff.differingPixels;
  d.maxAbsDelta = diff.maxAbsDeltaOverChannels();
  if (d.differingPixels)
    d.reason = fmt::format("{} pixels differ from {} (max |delta| {})", d.differingPixels, entry->file, d.maxAbsDelta);
  else if (entry->imageSha256 != d.sha256)
    d.reason = "manifest hash differs from the image";
  return d;
}

}  // namespace tessera::golden
