// `tessera texel FRAME.tframe [--against B.tframe]`: the texel-per-pixel analysis of any recorded frame,
// from the oracle's own sampler (raster/lod_probe.h): per pixel and lookup, rho and lambda; texel.json,
// a lambda heat map with a colour bar, a histogram, a raw lambda file, and with --against the per-pixel
// comparison of two frames (verify/lod_compare.h). docs/texel.md describes every output.
#include "tools/cli/texel_frame.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>

#include "base/atomic_file.h"
#include "base/error.h"
#include "raster/lod_probe.h"
#include "raster/sample.h"
#include "raster/serialize.h"
#include "tools/cli/frame_job.h"
#include "tools/cli/mta_path_run.h"
#include "tools/cli/output_directory.h"
#include "verify/lod_compare.h"
#include "verify/rgba_canvas.h"

namespace tessera::cli {

namespace fs = std::filesystem;

namespace {

// Histogram bins over levels (lambda, or log2 rho): bin 0 below kBinLo (and -inf), then half-level bins
// [kBinLo + k/2, kBinLo + (k+1)/2), the last at or above kBinHi.
constexpr int kBinLo = -4, kBinHi = 8;
constexpr int kLevelBins = (kBinHi - kBinLo) * 2 + 2;

// Bin of an 8.8 level value (integer arithmetic: 128 units per half level).
int levelBin(int64_t v8) {
  if (v8 < int64_t(kBinLo) * 256) return 0;
  if (v8 >= int64_t(kBinHi) * 256) return kLevelBins - 1;
  return 1 + int((v8 - int64_t(kBinLo) * 256) / 128);
}
double levelBinLower(int bin) { return bin == 0 ? -INFINITY : kBinLo + 0.5 * (bin - 1); }

// 256 log2(rho) from rho^2 (log2Fixed: integer arithmetic, round half to even); kLodMinusInf for 0,
// kLodMax for NaN / Inf, as the sampler's lambda_base.
int64_t log2Rho8(double rho2) {
  if (!std::isfinite(rho2)) return kLodMax;
  if (rho2 <= 0.0) return kLodMinusInf;
  return log2Fixed(rho2, 7);
}

struct FrameStats {
  std::string name;
  int32_t width = 0, height = 0;
  uint64_t pixelsWithLookup = 0, lookups = 0, lookupsComplete = 0, lookupsTruncated = 0;
  std::array<uint64_t, kLevelBins> lambdaHist{}, rhoHist{};
  std::map<int, uint64_t> perUnit, perCount;
  std::map<std::string, uint64_t> perSize;
  int32_t lambdaMin = 0, lambdaMax = 0;
  int64_t lambdaSum = 0;
  double rhoMin = 0.0, rhoMax = 0.0, rhoSum = 0.0;
};

FrameStats frameStats(const std::string& name, const LodMap& m) {
  FrameStats s;
  s.name = name;
  s.width = m.width, s.height = m.height;
  bool first = true;
  for (const LodPixel& px : m.pixels) {  // pixel order: the sums are the same bytes on every run
    if (px.count == 0) continue;
    ++s.pixelsWithLookup;
    s.lookups += px.count;
    s.lookupsTruncated += uint64_t(px.count - px.recorded());
    ++s.perCount[px.count];
    for (int i = 0; i < px.recorded(); ++i) {
      const LodLookup& l = px.look[size_t(i)];
      ++s.perUnit[l.unit];
      ++s.perSize[std::to_string(l.width) + "x" + std::to_string(l.height)];
      if (l.levels == 0) continue;  // incomplete: no LOD
      ++s.lookupsComplete;
      ++s.lambdaHist[size_t(levelBin(l.lambda8))];
      ++s.rhoHist[size_t(levelBin(log2Rho8(l.rho2)))];
      const double rho = std::sqrt(l.rho2);
      if (first) s.lambdaMin = s.lambdaMax = l.lambda8, s.rhoMin = s.rhoMax = rho, first = false;
      s.lambdaMin = std::min(s.lambdaMin, l.lambda8), s.lambdaMax = std::max(s.lambdaMax, l.lambda8);
      s.rhoMin = std::min(s.rhoMin, rho), s.rhoMax = std::max(s.rhoMax, rho);
      s.lambdaSum += l.lambda8;
      s.rhoSum += rho;
    }
  }
  return s;
}

// JSON has no infinity: a level of -inf (rho == 0) or +inf is written as null.
nlohmann::json level8(int64_t v8) {
  if (v8 <= kLodMinusInf || v8 >= kLodMax) return nullptr;
  return double(v8) / 256.0;
}
nlohmann::json finite(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json toJson(const FrameStats& s) {
  nlohmann::json lh = nlohmann::json::array(), rh = nlohmann::json::array();
  for (int b = 0; b < kLevelBins; ++b) {
    lh.push_back({{"lambda_at_least", finite(levelBinLower(b))}, {"lookups", s.lambdaHist[size_t(b)]}});
    rh.push_back({{"log2_rho_at_least", finite(levelBinLower(b))}, {"lookups", s.rhoHist[size_t(b)]}});
  }
  nlohmann::json units = nlohmann::json::object(), counts = nlohmann::json::object(), sizes = nlohmann::json::object();
  for (const auto& [u, n] : s.perUnit) units[std::to_string(u)] = n;
  for (const auto& [c, n] : s.perCount) counts[std::to_string(c)] = n;
  for (const auto& [z, n] : s.perSize) sizes[z] = n;
  const bool any = s.lookupsComplete > 0;
  const double n = double(s.lookupsComplete);
  return {{"frame", s.name},
          {"width", s.width},
          {"height", s.height},
          {"pixels", uint64_t(s.width) * uint64_t(s.height)},
          {"pixels_with_lookup", s.pixelsWithLookup},
          {"lookups", s.lookups},
          {"lookups_with_lod", s.lookupsComplete},
          {"lookups_not_recorded", s.lookupsTruncated},
          {"pixels_by_lookup_count", counts},
          {"lookups_by_unit", units},
          {"lookups_by_texture_size", sizes},
          {"lambda", {{"min", any ? level8(s.lambdaMin) : nullptr},
                      {"mean", any ? finite(double(s.lambdaSum) / 256.0 / n) : nullptr},
                      {"max", any ? level8(s.lambdaMax) : nullptr}}},
          {"rho", {{"min", any ? finite(s.rhoMin) : nullptr},
                   {"mean", any ? finite(s.rhoSum / n) : nullptr},
                   {"max", any ? finite(s.rhoMax) : nullptr}}},
          {"lambda_histogram", lh},
          {"log2_rho_histogram", rh}};
}

// The heat-map ramp over lambda in [kBinLo, kBinHi]: blue (magnified) .. green (lambda 0) .. yellow ..
// red (most minified).
verify::Rgba ramp(double lambda) {
  struct Stop { double at; verify::Rgba c; };
  static constexpr Stop kStops[] = {{-4, {20, 30, 120, 255}}, {-2, {40, 90, 210, 255}}, {0, {30, 170, 70, 255}},
                                    {2, {235, 215, 40, 255}}, {4, {240, 130, 20, 255}}, {8, {200, 30, 30, 255}}};
  if (!(lambda > kStops[0].at)) return kStops[0].c;
  for (size_t i = 1; i < std::size(kStops); ++i) {
    if (lambda > kStops[i].at) continue;
    const double f = (lambda - kStops[i - 1].at) / (kStops[i].at - kStops[i - 1].at);
    auto mix = [&](uint8_t x, uint8_t y) { return uint8_t(std::lround(x + (y - x) * f)); };
    const verify::Rgba a = kStops[i - 1].c, b = kStops[i].c;
    return {mix(a[0], b[0]), mix(a[1], b[1]), mix(a[2], b[2]), 255};
  }
  return kStops[std::size(kStops) - 1].c;
}

constexpr verify::Rgba kNoLookup{128, 128, 128, 255}, kIncomplete{60, 60, 60, 255}, kBlack{0, 0, 0, 255},
    kWhite{255, 255, 255, 255};

// The lambda of each pixel's first lookup as colours, with a colour bar and its scale underneath.
verify::RgbaCanvas heatMap(const LodMap& m, const std::string& title) {
  const int barH = 16, legend = 84;
  const int w = std::max(m.width, 360);
  verify::RgbaCanvas c(w, m.height + legend, kWhite);
  for (int32_t y = 0; y < m.height; ++y)
    for (int32_t x = 0; x < m.width; ++x) {
      const LodPixel& px = m.at(x, y);
      verify::Rgba col = kNoLookup;
      if (px.count > 0) col = px.look[0].levels == 0 ? kIncomplete : ramp(double(px.look[0].lambda8) / 256.0);
      c.set(x, m.height - 1 - y, col);  // rows bottom first -> image rows top first
    }
  const int top = m.height + 6, left = 10, barW = w - 2 * left;
  for (int i = 0; i < barW; ++i)
    c.fillRect(left + i, top, 1, barH, ramp(kBinLo + (kBinHi - kBinLo) * (i + 0.5) / barW));
  for (int v = kBinLo; v <= kBinHi; v += 2) {
    const int x = left + int(double(barW) * (v - kBinLo) / (kBinHi - kBinLo));
    c.fillRect(x, top + barH, 1, 4, kBlack);
    const std::string label = std::to_string(v);
    c.text(std::clamp(x - verify::RgbaCanvas::textWidth(label, 2) / 2, 0, w - 12), top + barH + 6, label, kBlack, 2);
  }
  c.text(left, top + barH + 24, "lambda (8.8, after bias and clamps) of the first lookup", kBlack, 1);
  c.text(left, top + barH + 36, "grey: no lookup  dark grey: incomplete texture  " + title, kBlack, 1);
  return c;
}

verify::RgbaCanvas lambdaHistogramPng(const FrameStats& s) {
  const int barW = 22, chartH = 200, left = 20, top = 30;
  verify::RgbaCanvas c(left * 2 + barW * kLevelBins, chartH + top + 60, kWhite);
  c.text(left, 8, "lookups by lambda (levels, half-level bins)", kBlack, 2);
  uint64_t mx = 1;
  for (uint64_t v : s.lambdaHist) mx = std::max(mx, v);
  for (int b = 0; b < kLevelBins; ++b) {
    const int bh = int(double(chartH) * double(s.lambdaHist[size_t(b)]) / double(mx));
    const double lo = levelBinLower(b);
    c.fillRect(left + b * barW + 2, top + chartH - bh, barW - 4, bh, ramp(b == 0 ? kBinLo : lo + 0.25));
    if (b % 2 == 1) c.text(left + b * barW, top + chartH + 6, std::to_string(int(std::floor(lo))), kBlack, 1);
  }
  c.text(left, top + chartH + 6 + 14, "<" + std::to_string(kBinLo) + " at the left, >=" + std::to_string(kBinHi) +
                                          " at the right; tallest bar " + std::to_string(mx) + " lookups",
         kBlack, 1);
  return c;
}

// Colour of a comparison reason in the difference map (and its legend).
verify::Rgba diffColour(verify::LodDiff d, bool hasLookup) {
  switch (d) {
    case verify::LodDiff::Same: return hasLookup ? verify::Rgba{225, 225, 225, 255} : verify::Rgba{255, 255, 255, 255};
    case verify::LodDiff::OnlyInA: return {40, 90, 210, 255};
    case verify::LodDiff::OnlyInB: return {30, 170, 200, 255};
    case verify::LodDiff::LookupCount: return {140, 60, 170, 255};
    case verify::LodDiff::Completeness: return {90, 60, 30, 255};
    case verify::LodDiff::TextureSize: return {240, 130, 20, 255};
    case verify::LodDiff::Lambda: return {210, 40, 40, 255};
  }
  return kBlack;
}

verify::RgbaCanvas diffMap(const verify::LodComparison& cmp, const LodMap& a, const LodMap& b) {
  const int w = std::max(cmp.width, 360), legend = 14 * verify::kLodDiffKinds + 10;
  verify::RgbaCanvas c(w, cmp.height + legend, kWhite);
  for (int32_t y = 0; y < cmp.height; ++y)
    for (int32_t x = 0; x < cmp.width; ++x) {
      const size_t i = size_t(y) * size_t(cmp.width) + size_t(x);
      c.set(x, cmp.height - 1 - y, diffColour(cmp.reason[i], a.pixels[i].count != 0 || b.pixels[i].count != 0));
    }
  for (int k = 0; k < verify::kLodDiffKinds; ++k) {
    const int y = cmp.height + 6 + 14 * k;
    c.fillRect(10, y, 10, 10, diffColour(verify::LodDiff(k), true));
    c.text(26, y + 1, std::string(verify::lodDiffName(verify::LodDiff(k))) + ": " + std::to_string(cmp.count[k]) +
                          " px", kBlack, 1);
  }
  return c;
}

// The raw file: int32 little-endian per pixel, rows bottom first: lambda (8.8) of the first lookup,
// INT32_MIN where there is none, kLodMinusInf for rho == 0, INT32_MIN + 1 for an incomplete texture.
void writeLambdaRaw(const std::string& path, const LodMap& m) {
  std::vector<uint8_t> bytes(m.pixels.size() * 4);
  for (size_t i = 0; i < m.pixels.size(); ++i) {
    const LodPixel& px = m.pixels[i];
    int32_t v = INT32_MIN;
    if (px.count > 0) v = px.look[0].levels == 0 ? INT32_MIN + 1 : px.look[0].lambda8;
    const uint32_t u = uint32_t(v);
    for (int k = 0; k < 4; ++k) bytes[i * 4 + size_t(k)] = uint8_t(u >> (8 * k));
  }
  writeFileAtomically(path, std::span<const uint8_t>(bytes));
}

LodMap probeFile(const std::string& path, int threads) {
  if (!fs::is_regular_file(path)) throw Error(path + ": not a readable file");
  const CommandList list = readFrame(path);  // a truncated or corrupt file is an Error naming it
  return lodMap(list, threads, path);
}

void writeFrameOutputs(const std::string& dir, const std::string& suffix, const LodMap& m, const FrameStats& s) {
  writeChartPng((fs::path(dir) / ("lambda" + suffix + ".png")).string(), heatMap(m, s.name));
  writeChartPng((fs::path(dir) / ("histogram" + suffix + ".png")).string(), lambdaHistogramPng(s));
  writeLambdaRaw((fs::path(dir) / ("lambda" + suffix + ".i32")).string(), m);
}

}  // namespace

nlohmann::json runTexelFrame(const TexelFrameArgs& a) {
  // Read and probe everything before writing anything, so bad input leaves no output behind.
  const LodMap ma = probeFile(a.input, a.threads);
  LodMap mb;
  verify::LodComparison cmp;
  if (!a.against.empty()) {
    mb = probeFile(a.against, a.threads);
    cmp = verify::compareLodMaps(ma, mb, a.input, a.against);
  }
  prepareOutputDirectory(a.out, "-o");
  const FrameStats sa = frameStats(a.input, ma);
  writeFrameOutputs(a.out, "", ma, sa);
  nlohmann::json frames = nlohmann::json::array({toJson(sa)});
  nlohmann::json summary = {{"frame", a.input},
                            {"pixels_with_lookup", sa.pixelsWithLookup},
                            {"lambda", frames[0]["lambda"]}};
  if (!a.against.empty()) {
    const FrameStats sb = frameStats(a.against, mb);
    writeFrameOutputs(a.out, "_against", mb, sb);
    frames.push_back(toJson(sb));
    writeChartPng((fs::path(a.out) / "lod_diff.png").string(), diffMap(cmp, ma, mb));
    nlohmann::json reasons = nlohmann::json::object();
    for (int k = 1; k < verify::kLodDiffKinds; ++k) reasons[std::string(verify::lodDiffName(verify::LodDiff(k)))] = cmp.count[k];
    summary = {{"frame", a.input},
               {"against", a.against},
               {"pixels_with_lookup", cmp.pixelsWithLookups},
               {"pixels_differing", cmp.differing},
               {"differing_by_reason", reasons},
               {"pixels_same_except_unit", cmp.unitDiffers},
               {"max_abs_lambda_difference", double(cmp.maxAbsDelta8) / 256.0},
               {"identical_lambda", cmp.differing == 0}};
  }
  const nlohmann::json doc = {{"summary", summary}, {"frames", frames}};
  writeTextFile((fs::path(a.out) / "texel.json").string(), doc.dump(1) + "\n");
  return summary;
}

}  // namespace tessera::cli
