#include "verify/compare_report.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>

#include "base/error.h"
#include "raster/image_io.h"
#include "base/atomic_file.h"
#include "verify/image_read.h"
#include "verify/report_html.h"

namespace tessera::verify {

namespace {

constexpr Rgba kMagenta{255, 0, 255, 255};

// A distinct, stable colour per integer id; 0xffffffff (the ID frames' background) is black.
Rgba idColor(uint32_t v) {
  if (v == 0xffffffffu) return {0, 0, 0, 255};
  uint32_t h = v * 0x9e3779b1u;  // murmur3's finalizer spreads neighbouring ids apart
  h ^= h >> 16, h *= 0x85ebca6bu, h ^= h >> 13, h *= 0xc2b2ae35u, h ^= h >> 16;
  return {uint8_t(64 + (h & 0xff) % 192), uint8_t(64 + (h >> 8 & 0xff) % 192), uint8_t(64 + (h >> 16 & 0xff) % 192),
          255};
}

uint8_t displayByte(double v, ChannelType t) {
  switch (t) {
    case ChannelType::UInt8:
      return uint8_t(v);
    case ChannelType::Int8:
      return uint8_t(std::clamp(v, 0.0, 127.0) * 2.0);
    case ChannelType::UInt16:
      return uint8_t(std::lround(v / 257.0));
    case ChannelType::Int16:
      return uint8_t(std::clamp(v, 0.0, 32767.0) / 128.5);
    default:
      return uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
  }
}

std::vector<uint8_t> preview(const DecodedImage& img) {
  std::vector<uint8_t> out(img.pixels() * 4);
  const int nc = img.channels();
  const bool ids = nc > 0 && (img.types[0] == ChannelType::UInt32 || img.types[0] == ChannelType::Int32);
  for (size_t p = 0; p < img.pixels(); ++p) {
    Rgba c{0, 0, 0, 255};
    if (ids) {
      c = idColor(uint32_t(int64_t(img.value(p, 0))));
    } else {
      bool nan = false;
      for (int k = 0; k < std::min(nc, 3); ++k) {
        const double v = img.value(p, k);
        nan = nan || std::isnan(v);
        c[size_t(k)] = displayByte(v, img.types[size_t(k)]);
      }
      if (nc == 1) c[1] = c[2] = c[0];
      if (nan) c = kMagenta;
    }
    std::copy(c.begin(), c.end(), out.begin() + std::ptrdiff_t(p) * 4);
  }
  return out;
}

RgbaCanvas heatmap(const CompareResult& r) {
  const int w = r.width, h = r.height;
  constexpr int kSwatches = kHistogramBins + 1;
  const int scale = w >= kSwatches * 64 ? 2 : 1;
  const int legendH = 22 * scale;
  const int width = std::max(w, kSwatches * 30 * scale);
  RgbaCanvas cv(width, h + legendH, {32, 32, 32, 255});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) cv.set(x, y, heatColor(r.images->bin[size_t(y) * size_t(w) + size_t(x)]));
  const int sw = width / kSwatches;
  for (int i = 0; i < kSwatches; ++i) {
    const int x = i * sw;
    cv.fillRect(x + scale, h + 2 * scale, sw - 2 * scale, 10 * scale, heatColor(i));
    const std::string_view label = i < kHistogramBins ? kHistogramLabels[size_t(i)] : "NaN";
    cv.text(x + (sw - RgbaCanvas::textWidth(label, scale)) / 2, h + 14 * scale, label, {230, 230, 230, 255}, scale);
  }
  return cv;
}

}  // namespace

RgbaCanvas histogramChart(const std::array<uint64_t, kHistogramBins>& histogram) {
  constexpr int kSlot = 64, kMargin = 20, kTop = 24, kBase = 240, kScale = 2;
  RgbaCanvas cv(2 * kMargin + kHistogramBins * kSlot, 280, {255, 255, 255, 255});
  uint64_t most = 0;
  for (uint64_t c : histogram) most = std::max(most, c);
  const double top = std::log10(1.0 + double(most));
  for (int i = 0; i < kHistogramBins; ++i) {
    const uint64_t count = histogram[size_t(i)];
    const int x = kMargin + i * kSlot;
    // Log scale: bin 0 (equal pixels) is usually orders of magnitude above the rest.
    int bar = top > 0 ? int(std::lround(double(kBase - kTop) * std::log10(1.0 + double(count)) / top)) : 0;
    if (count > 0) bar = std::max(bar, 1);
    cv.fillRect(x + 6, kBase - bar, kSlot - 12, bar, i == 0 ? Rgba{110, 110, 110, 255} : heatColor(i));
    const std::string n = std::to_string(count);
    const int scale = RgbaCanvas::textWidth(n, kScale) <= kSlot ? kScale : 1;
    cv.text(x + (kSlot - RgbaCanvas::textWidth(n, scale)) / 2, kBase - bar - 6 * scale - 2, n, {0, 0, 0, 255}, scale);
    const std::string_view label = kHistogramLabels[size_t(i)];
    cv.text(x + (kSlot - RgbaCanvas::textWidth(label, kScale)) / 2, kBase + 8, label, {0, 0, 0, 255}, kScale);
  }
  cv.fillRect(kMargin, kBase, kHistogramBins * kSlot, 1, {0, 0, 0, 255});
  cv.text(cv.width() - kMargin - RgbaCanvas::textWidth("LSB", kScale), kBase + 24, "LSB", {90, 90, 90, 255}, kScale);
  return cv;
}

namespace {

void writeCanvas(const std::string& path, const RgbaCanvas& cv) {
  writePngRGBA8(path, cv.width(), cv.height(), cv.data());
}

}  // namespace

Rgba heatColor(int bin) {
  // Black for equal, then a blue-to-red diverging ramp (ColorBrewer RdYlBu, reversed): one step per
  // doubling of the error, so 1 LSB is as visible as 100.
  static constexpr Rgba kRamp[kHistogramBins] = {
      {0, 0, 0, 255},       {49, 54, 149, 255},  {69, 117, 180, 255}, {116, 173, 209, 255}, {171, 217, 233, 255},
      {254, 224, 144, 255}, {253, 174, 97, 255}, {244, 109, 67, 255}, {215, 48, 39, 255},   {165, 0, 38, 255}};
  if (bin >= 0 && bin < kHistogramBins) return kRamp[bin];
  return kMagenta;
}

void writeCompareReport(const CompareResult& result, const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) throw Error(dir + ": cannot create the report directory");
  const std::string base = dir + "/";
  const nlohmann::json report = compareToJson(result);
  writeFileAtomically(base + "report.json", report.dump(2) + "\n");
  if (result.images) {
    const DecodedImage& a = *result.images->a;
    const DecodedImage& b = *result.images->b;
    writePngRGBA8(base + "expected.png", a.width, a.height, preview(a).data());
    writePngRGBA8(base + "actual.png", b.width, b.height, preview(b).data());
    writeCanvas(base + "heatmap.png", heatmap(result));
    writeCanvas(base + "histogram.png", histogramChart(result.histogram));
  }
  writeFileAtomically(base + "index.html", renderReportHtml(result, report));
}

}  // namespace tessera::verify
