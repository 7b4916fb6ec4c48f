#include "verify/judge.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "base/image_diff.h"
#include "raster/image_io.h"

namespace tessera::verify {

namespace {

inline double channelValue(Format f, const uint8_t* texel, int c) {
  if (isUnorm(f)) return texel[c];
  if (isFloat(f)) {
    float v;
    std::memcpy(&v, texel + 4 * c, 4);
    return v;
  }
  uint32_t u;
  std::memcpy(&u, texel + 4 * c, 4);
  return u;
}

inline int histogramBin(double d) {
  if (d <= 0) return 0;
  if (d <= 1) return 1;
  if (d <= 2) return 2;
  int bin = 3;
  for (double edge = 4; bin < 9 && d > edge; edge *= 2) ++bin;
  return bin;
}

// NaN-safe equality and containment: a NaN equals only a NaN (bit patterns may differ).
inline bool sameValue(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }
inline bool inside(double v, double lo, double hi) { return (v >= lo && v <= hi) || (std::isnan(v) && std::isnan(lo)); }

}  // namespace

double Judgement::psnr() const { return psnrFromMse(mse, isUnorm(format) ? 255.0 : 1.0); }

Judgement judge(const TextureData& tex, uint32_t level, uint32_t layer, const std::vector<uint8_t>& other) {
  if (!tex.prov) throw Error("judge: the oracle image was not rendered in provenance mode");
  Judgement j;
  j.format = tex.desc.format;
  j.width = int(levelWidth(tex.desc, level));
  j.height = int(levelHeight(tex.desc, level));
  j.channels = channelCount(j.format);
  const auto val = imagePixels(tex, level, layer);
  const auto lo = imagePixels(*tex.prov->lo, level, layer);
  const auto hi = imagePixels(*tex.prov->hi, level, layer);
  if (other.size() != val.size())
    throw Error("judge: the other image has " + std::to_string(other.size()) + " bytes, the oracle's " +
                std::to_string(val.size()));
  const size_t bpt = texelBytes(j.format);
  j.pixels = uint64_t(j.width) * uint64_t(j.height);
  j.classMap.resize(j.pixels);
  j.failMap.resize(j.pixels);
  const auto& cls = tex.prov->classes[level];
  const auto& flags = tex.prov->flags[level];
  const auto& cands = tex.prov->candidates[level];
  // The size of the differences (max |Δ| per channel, MSE) in channel units, in pixel order
  // (base/image_diff.h). Non-finite differences are left out: their pixels are judged by interval.
  ImageDiffRules rules;
  rules.nonFinite = NonFiniteRule::Skip;
  rules.peak = isUnorm(j.format) ? 255.0 : 1.0;
  ImageDiffAccumulator diff(j.channels, rules);
  for (int y = 0; y < j.height; ++y) {
    for (int x = 0; x < j.width; ++x) {
      const size_t i = size_t(y) * size_t(j.width) + size_t(x);
      // Provenance classes are stored bottom row first (GL order); images are top row first.
      const size_t si = (size_t(layer) * size_t(j.height) + size_t(j.height - 1 - y)) * size_t(j.width) + x;
      const uint16_t classes = cls[si];
      const std::vector<Candidate>& set = cands[si];
      const bool fallback = flags[si] & kFallback;
      j.classMap[i] = classes;
      if (classes) ++j.classed;
      if (fallback) ++j.fallbacks;
      const bool lookupFallback = flags[si] & kLookupFallback;
      if (lookupFallback) ++j.lookupFallbacks;
      if (flags[si] & kLookupForked) ++j.lookupForked;
      if (set.size() > 1) ++j.multiCandidate;
      for (int b = 0; b < kClassCount; ++b)
        if (classes >> b & 1) {
          ++j.classPixels[size_t(b)];
          ClassStats& st = j.classStats[size_t(b)];
          ++st.pixels;
          for (int c = 0; c < j.channels; ++c) {
            const double w = channelValue(j.format, &hi[i * bpt], c) - channelValue(j.format, &lo[i * bpt], c);
            const double width = std::isnan(w) ? std::numeric_limits<double>::infinity() : w;
            st.widthSum[size_t(c)] += width;
            st.widthMax[size_t(c)] = std::max(st.widthMax[size_t(c)], width);
          }
          const uint64_t n = set.empty() ? 1u : set.size();
          st.candidateSum += n;
          st.candidateMax = std::max(st.candidateMax, n);
          if (fallback) ++st.fallbacks;
          if (lookupFallback) ++st.lookupFallbacks;
        }
      const uint8_t* pv = &val[i * bpt];
      const uint8_t* po = &other[i * bpt];
      if (std::memcmp(pv, po, bpt) == 0) {
        ++j.exact;
        ++j.histogram[0];
        diff.endPixel(false);
        continue;
      }
      // A differing pixel is explained only by a class, and only inside one candidate's box (the
      // hull's box when the pixel keeps no set).
      bool withinHull = true;
      double worst = 0.0;
      PixelRecord rec{x, y, {}, {}, {}, {}, classes};
      for (int c = 0; c < j.channels; ++c) {
        const double v = channelValue(j.format, pv, c), o = channelValue(j.format, po, c);
        const double l = channelValue(j.format, &lo[i * bpt], c), h = channelValue(j.format, &hi[i * bpt], c);
        rec.oracle[size_t(c)] = v, rec.other[size_t(c)] = o, rec.lo[size_t(c)] = l, rec.hi[size_t(c)] = h;
        if (!sameValue(v, o) && !inside(o, l, h)) withinHull = false;
        const double d = diff.add(c, v, o);
        if (std::isfinite(d)) worst = std::max(worst, d);
      }
      bool within = classes != 0 && withinHull;
      if (within && !set.empty()) {
        within = false;
        for (const Candidate& cand : set) {
          bool in = true;
          for (int c = 0; c < j.channels && in; ++c)
            in = inside(channelValue(j.format, po, c), cand.lo[size_t(c)], cand.hi[size_t(c)]);
          if (in) {
            within = true;
            break;
          }
        }
      }
      diff.endPixel(true);
      ++j.histogram[size_t(histogramBin(worst))];
      if (within) {
        ++j.explained;
        j.failMap[i] = 1;
        for (int b = 0; b < kClassCount; ++b)
          if (classes >> b & 1) ++j.classExplained[size_t(b)];
      } else {
        ++j.unexplained;
        j.failMap[i] = 2;
        if (j.firstUnexplained.size() < Judgement::kMaxRecords) j.firstUnexplained.push_back(rec);
      }
    }
  }
  const ImageDiff& d = diff.result();
  for (int c = 0; c < j.channels; ++c) j.maxAbsDiff[size_t(c)] = d.maxAbsDelta[size_t(c)];
  j.mse = d.mse();
  return j;
}

nlohmann::json toJson(const Judgement& j) {
  nlohmann::json perClass = nlohmann::json::object();
  // Widths may be infinite (a blended float target): JSON has no infinity, so it is written "inf".
  auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json("inf"); };
  for (int b = 0; b < kClassCount; ++b) {
    const ClassStats& st = j.classStats[size_t(b)];
    nlohmann::json meanW = nlohmann::json::array(), maxW = nlohmann::json::array();
    for (int c = 0; c < j.channels; ++c) {
      meanW.push_back(number(st.pixels ? st.widthSum[size_t(c)] / double(st.pixels) : 0.0));
      maxW.push_back(number(st.widthMax[size_t(c)]));
    }
    perClass[std::string(ambiguityClassName(b))] = {
        {"pixels", j.classPixels[size_t(b)]},
        {"explained_differences", j.classExplained[size_t(b)]},
        {"fraction", j.pixels ? double(st.pixels) / double(j.pixels) : 0.0},
        {"mean_width", meanW},
        {"max_width", maxW},
        {"mean_candidates", st.pixels ? double(st.candidateSum) / double(st.pixels) : 0.0},
        {"max_candidates", st.candidateMax},
        {"fallbacks", st.fallbacks},
        {"lookup_fallbacks", st.lookupFallbacks}};
  }
  nlohmann::json first = nlohmann::json::array();
  for (const PixelRecord& r : j.firstUnexplained) {
    nlohmann::json classes = nlohmann::json::array();
    for (int b = 0; b < kClassCount; ++b)
      if (r.classes >> b & 1) classes.push_back(std::string(ambiguityClassName(b)));
    auto arr = [&](const std::array<double, 4>& a) {
      return std::vector<double>(a.begin(), a.begin() + j.channels);
    };
    first.push_back({{"x", r.x}, {"y", r.y}, {"oracle", arr(r.oracle)}, {"other", arr(r.other)},
                     {"lo", arr(r.lo)}, {"hi", arr(r.hi)}, {"classes", classes}});
  }
  const double psnr = j.psnr();
  return {{"format", std::string(formatName(j.format))},
          {"width", j.width},
          {"height", j.height},
          {"pixels", j.pixels},
          {"exact", j.exact},
          {"exact_match_percent", j.exactPercent()},
          {"classed", j.classed},
          {"explained", j.explained},
          {"unexplained", j.unexplained},
          {"passed", j.passed()},
          {"per_class", perClass},
          {"candidate_fallbacks", j.fallbacks},
          {"multi_candidate_pixels", j.multiCandidate},
          {"max_candidates", kMaxCandidates},
          {"lookup_forked_pixels", j.lookupForked},
          {"lookup_fallbacks", j.lookupFallbacks},
          {"max_lookup_candidates", kMaxLookupCandidates},
          {"max_abs_diff", std::vector<double>(j.maxAbsDiff.begin(), j.maxAbsDiff.begin() + j.channels)},
          {"histogram_bins", {"0", "1", "2", "3-4", "5-8", "9-16", "17-32", "33-64", "65-128", "129+"}},
          {"histogram", j.histogram},
          {"psnr_db", std::isinf(psnr) ? nlohmann::json("inf") : nlohmann::json(psnr)},
          {"first_unexplained", first}};
}

}  // namespace tessera::verify
