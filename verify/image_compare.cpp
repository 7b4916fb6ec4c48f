#include "verify/image_compare.h"

#include <cmath>
#include <limits>

#include "base/image_diff.h"
#include "verify/image_read.h"
#include "verify/json_number.h"

namespace tessera::verify {

const std::array<const char*, kHistogramBins> kHistogramLabels = {"0",    "1",     "2",     "3-4",    "5-8",
                                                                  "9-16", "17-32", "33-64", "65-128", "129-255"};

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Upper bounds (inclusive) of the histogram bins, in histogram units rounded up.
int histogramBin(double units) {
  if (units == 0.0) return 0;
  const double k = std::ceil(units);
  static constexpr double upper[kHistogramBins - 1] = {0, 1, 2, 4, 8, 16, 32, 64, 128};
  for (int i = 1; i < kHistogramBins - 1; ++i)
    if (k <= upper[i]) return i;
  return kHistogramBins - 1;
}

std::string describeFormat(const DecodedImage& img) {
  std::string s = std::to_string(img.width) + "x" + std::to_string(img.height) + ", " + std::to_string(img.channels()) +
                  " channel(s)";
  for (int c = 0; c < img.channels(); ++c) s += std::string(c ? "/" : " ") + channelTypeName(img.types[size_t(c)]);
  if (img.originX || img.originY) s += ", origin " + std::to_string(img.originX) + "," + std::to_string(img.originY);
  return s;
}

std::string percent(uint64_t n, uint64_t total) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4g%%", total ? 100.0 * double(n) / double(total) : 0.0);
  return buf;
}

}  // namespace

const char* compareStatusName(CompareStatus s) {
  switch (s) {
    case CompareStatus::Pass:
      return "pass";
    case CompareStatus::Warn:
      return "warn";
    case CompareStatus::Fail:
      return "fail";
    case CompareStatus::Mismatch:
      return "mismatch";
    case CompareStatus::IoError:
      return "io_error";
  }
  return "?";
}

CompareResult compareImages(const std::string& pathA, const std::string& pathB, const CompareOptions& options) {
  CompareResult r;
  r.pathA = pathA, r.pathB = pathB;
  r.options = options;
  r.warnThreshold = options.warnThreshold.value_or(options.failThreshold);

  ReadOutcome ra = readImage(pathA), rb = readImage(pathB);
  // I/O errors first (4), naming every unreadable file; then refusals (3).
  if (!ra.image && !ra.unsupported) r.message = ra.error;
  if (!rb.image && !rb.unsupported) r.message += (r.message.empty() ? "" : "; ") + rb.error;
  if (!r.message.empty()) return r;
  r.status = CompareStatus::Mismatch;
  if (ra.unsupported || rb.unsupported) {
    r.message = ra.unsupported ? ra.error : rb.error;
    return r;
  }
  auto a = std::make_shared<DecodedImage>(std::move(*ra.image));
  auto b = std::make_shared<DecodedImage>(std::move(*rb.image));
  if (a->width != b->width || a->height != b->height || a->originX != b->originX || a->originY != b->originY ||
      a->types != b->types) {
    r.message = "images differ in size or format: '" + pathA + "' is " + describeFormat(*a) + ", '" + pathB + "' is " +
                describeFormat(*b);
    return r;
  }

  const int nc = a->channels();
  const size_t n = a->pixels();
  r.width = a->width, r.height = a->height, r.channels = nc;
  r.pixels = n;
  const size_t ch = size_t(nc);
  std::vector<double> histUnit(ch), peak(ch), sumAbs(ch, 0.0);
  std::vector<uint64_t> finite(ch, 0);
  for (int c = 0; c < nc; ++c) {
    const ChannelType t = a->types[size_t(c)];
    r.channelNames.push_back(a->names[size_t(c)]);
    r.channelTypes.push_back(channelTypeName(t));
    r.channelUnits.push_back(isIntegerChannel(t) ? "lsb" : "abs");
    histUnit[size_t(c)] = isIntegerChannel(t) ? 1.0 : 1.0 / 255.0;
    peak[size_t(c)] = channelPeak(t);
  }
  auto images = std::make_shared<CompareResult::Images>();
  images->bin.assign(n, 0);
  // |Δ|, the maxima, the differing pixels and the PSNR with idiff's NaN rules, squares relative to each
  // channel's peak, in pixel order (base/image_diff.h).
  ImageDiffRules rules;
  rules.nonFinite = NonFiniteRule::FullScale;
  rules.relativeToPeak = true;
  ImageDiffAccumulator diff(nc, rules, peak);
  double largest = -1.0;

  std::vector<double> va(ch), vb(ch);
  for (size_t p = 0; p < n; ++p) {
    bool differs = false, fails = false, warns = false, nonfinite = false;
    double units = 0.0;
    for (int c = 0; c < nc; ++c) {
      va[size_t(c)] = a->value(p, c), vb[size_t(c)] = b->value(p, c);
      const double d = diff.add(c, va[size_t(c)], vb[size_t(c)]);
      if (d == 0.0) {
        ++finite[size_t(c)];
        continue;
      }
      differs = true;
      fails = fails || d > options.failThreshold;
      warns = warns || d > r.warnThreshold;
      if (d > largest) {
        largest = d;
        r.maxX = int32_t(p % size_t(r.width)), r.maxY = int32_t(p / size_t(r.width)), r.maxChannel = c;
      }
      if (std::isinf(d)) {
        nonfinite = true;
        units = kInf;
        continue;
      }
      ++finite[size_t(c)];
      sumAbs[size_t(c)] += d;
      units = std::max(units, d / histUnit[size_t(c)]);
    }
    diff.endPixel(differs);
    const int bin = histogramBin(units);
    ++r.histogram[size_t(bin)];
    images->bin[p] = nonfinite ? CompareResult::kNonFiniteBin : uint8_t(bin);
    if (!differs) continue;
    r.failingPixels += fails;
    r.warningPixels += warns;
    r.nonfiniteMismatches += nonfinite;
    if (r.firstDifferences.size() < options.maxListed)
      r.firstDifferences.push_back(
          {int32_t(p % size_t(r.width)) + a->originX, int32_t(p / size_t(r.width)) + a->originY, va, vb});
  }
  r.maxX += a->originX, r.maxY += a->originY;
  for (int c = 0; c < nc; ++c)
    r.meanAbsDiff.push_back(finite[size_t(c)] ? sumAbs[size_t(c)] / double(finite[size_t(c)]) : 0.0);
  r.differingPixels = diff.result().differingPixels;
  r.maxAbsDiff = diff.result().maxAbsDelta;
  r.psnr = diff.result().psnr();
  r.exactMatchPercent = n ? 100.0 * double(n - r.differingPixels) / double(n) : 100.0;

  if (double(r.failingPixels) > options.failPercent / 100.0 * double(n)) {
    r.status = CompareStatus::Fail;
    r.message = "FAILURE: " + std::to_string(r.failingPixels) + " pixels (" + percent(r.failingPixels, n) +
                ") over the fail threshold";
  } else if (double(r.warningPixels) > options.warnPercent / 100.0 * double(n)) {
    r.status = CompareStatus::Warn;
    r.message = "WARNING: " + std::to_string(r.warningPixels) + " pixels (" + percent(r.warningPixels, n) +
                ") over the warn threshold";
  } else {
    r.status = CompareStatus::Pass;
    r.message = r.differingPixels ? "PASS: " + std::to_string(r.differingPixels) + " pixels differ within tolerance"
                                  : "PASS: identical";
  }
  images->a = std::move(a);
  images->b = std::move(b);
  r.images = std::move(images);
  return r;
}

nlohmann::json compareToJson(const CompareResult& r) {
  using nlohmann::json;
  json j;
  j["status"] = int(r.status);
  j["status_name"] = compareStatusName(r.status);
  j["message"] = r.message;
  j["expected"] = r.pathA;
  j["actual"] = r.pathB;
  j["options"] = {{"fail", r.options.failThreshold},
                  {"failpercent", r.options.failPercent},
                  {"warn", r.warnThreshold},
                  {"warnpercent", r.options.warnPercent}};
  if (r.status == CompareStatus::Mismatch || r.status == CompareStatus::IoError) return j;
  j["width"] = r.width;
  j["height"] = r.height;
  json channels = json::array();
  for (int c = 0; c < r.channels; ++c)
    channels.push_back({{"name", r.channelNames[size_t(c)]},
                        {"type", r.channelTypes[size_t(c)]},
                        {"units", r.channelUnits[size_t(c)]},
                        {"max_abs_diff", jsonNumber(r.maxAbsDiff[size_t(c)])},
                        {"mean_abs_diff", r.meanAbsDiff[size_t(c)]}});
  j["channels"] = channels;
  j["pixels"] = r.pixels;
  j["differing_pixels"] = r.differingPixels;
  j["failing_pixels"] = r.failingPixels;
  j["warning_pixels"] = r.warningPixels;
  j["nonfinite_mismatches"] = r.nonfiniteMismatches;
  j["exact_match_percent"] = r.exactMatchPercent;
  json maxes = json::array(), means = json::array();
  for (int c = 0; c < r.channels; ++c) {
    maxes.push_back(jsonNumber(r.maxAbsDiff[size_t(c)]));
    means.push_back(r.meanAbsDiff[size_t(c)]);
  }
  j["max_abs_diff"] = maxes;
  j["mean_abs_diff"] = means;
  if (r.differingPixels) j["max_abs_diff_at"] = {{"x", r.maxX}, {"y", r.maxY}, {"channel", r.maxChannel}};
  j["psnr"] = jsonNumber(r.psnr);
  json labels = json::array(), counts = json::array();
  for (int i = 0; i < kHistogramBins; ++i)
    labels.push_back(kHistogramLabels[size_t(i)]), counts.push_back(r.histogram[size_t(i)]);
  j["histogram"] = {
      {"labels", labels}, {"counts", counts}, {"units", "lsb for integer channels, 1/255 for float channels"}};
  json diffs = json::array();
  for (const PixelDifference& d : r.firstDifferences) {
    json a = json::array(), b = json::array();
    for (double v : d.a) a.push_back(jsonNumber(v));
    for (double v : d.b) b.push_back(jsonNumber(v));
    diffs.push_back({{"x", d.x}, {"y", d.y}, {"expected", a}, {"actual", b}});
  }
  j["first_differences"] = diffs;
  return j;
}

}  // namespace tessera::verify
