#include "verify/stability.h"

#include <algorithm>

#include "base/error.h"
#include "verify/crosscheck.h"
#include "verify/html_escape.h"

namespace tessera::verify {

namespace {

// Per image: differing pixels (a pixel = bytes / pixelsPerImage[i] bytes) and differing bytes.
struct Difference {
  bool identical = true;
  nlohmann::json images = nlohmann::json::array();
};

Difference compareRuns(const std::vector<std::vector<uint8_t>>& ref, const std::vector<std::vector<uint8_t>>& other,
                       const std::vector<size_t>& pixelsPerImage) {
  Difference d;
  if (ref.size() != other.size()) {
    d.identical = false;
    d.images.push_back({{"image", "all"}, {"note", "the runs present " + std::to_string(ref.size()) + " and " +
                                                       std::to_string(other.size()) + " images"}});
    return d;
  }
  for (size_t i = 0; i < ref.size(); ++i) {
    uint64_t bytes = 0, pixels = 0;
    const size_t n = i < pixelsPerImage.size() ? pixelsPerImage[i] : 0;
    if (ref[i].size() != other[i].size()) {
      d.identical = false;
      d.images.push_back({{"image", i}, {"note", "sizes differ"}});
      continue;
    }
    const size_t bpp = n && ref[i].size() % n == 0 ? ref[i].size() / n : 1;
    for (size_t p = 0; p * bpp < ref[i].size(); ++p) {
      bool differs = false;
      for (size_t b = p * bpp; b < (p + 1) * bpp && b < ref[i].size(); ++b)
        if (ref[i][b] != other[i][b]) ++bytes, differs = true;
      pixels += differs;
    }
    d.identical = d.identical && bytes == 0;
    d.images.push_back({{"image", i}, {"differing_pixels", pixels}, {"differing_bytes", bytes}});
  }
  return d;
}

// Does the condition change the output of the prefix through draw k?
bool changes(const StabilityCondition& ref, const StabilityCondition& c, const StabilityRenderer& render,
             std::optional<size_t> throughDraw) {
  const GlRuns a = render(c, throughDraw);
  if (c.runs >= 2) return a.size() < 2 || a[0] != a[1];
  const GlRuns r = render(ref, throughDraw);
  return r.empty() || a.empty() || r[0] != a[0];
}

}  // namespace

std::vector<StabilityCondition> stabilityConditions(int cpus) {
  const int n = std::max(cpus, 2);
  std::vector<StabilityCondition> c;
  c.push_back({"reference", "Mesa's defaults in a fresh process", {}, false, false, 1});
  c.push_back({"repeat_in_process", "the frame rendered twice in one process; run 2 against run 1", {}, false, false, 2});
  c.push_back({"another_process", "Mesa's defaults again, in another process", {}, false, false, 1});
  c.push_back({"lp_threads_1", "LP_NUM_THREADS=1: one rasterizer thread", {{"LP_NUM_THREADS", "1"}}, false, false, 1});
  c.push_back({"lp_threads_" + std::to_string(n), "LP_NUM_THREADS=" + std::to_string(n) + ": one rasterizer thread per CPU",
               {{"LP_NUM_THREADS", std::to_string(n)}}, false, false, 1});
  c.push_back({"one_cpu", "one visible CPU (sched_setaffinity before GL starts; llvmpipe then rasterizes on the "
               "calling thread)", {}, false, true, 1});
  c.push_back({"strict", "--strict: LP_PERF=no_rast_linear, GALLIVM_PERF=no_aos_sampling (fast paths off)", {}, true,
               false, 1});
  return c;
}

nlohmann::json checkStability(const CommandList& list, const std::vector<StabilityCondition>& conditions,
                              const StabilityRenderer& render, const std::vector<size_t>& pixelsPerImage,
                              const StabilityOptions& options) {
  if (conditions.empty()) throw Error("stability: no conditions (the first one is the reference)");
  const StabilityCondition& ref = conditions[0];
  const GlRuns reference = render(ref, std::nullopt);
  if (reference.empty()) throw Error("stability: the reference run returned no images");
  std::vector<size_t> draws;
  for (size_t i = 0; i < list.commands().size(); ++i)
    if (std::holds_alternative<Draw>(list.commands()[i])) draws.push_back(i);

  nlohmann::json out;
  out["reference"] = {{"name", ref.name}, {"description", ref.description}};
  nlohmann::json rows = nlohmann::json::array();
  bool stable = true;
  for (size_t c = 1; c < conditions.size(); ++c) {
    const StabilityCondition& cond = conditions[c];
    const GlRuns runs = render(cond, std::nullopt);
    Difference d;
    if (cond.runs >= 2 && runs.size() >= 2) d = compareRuns(runs[0], runs[1], pixelsPerImage);
    else if (!runs.empty()) d = compareRuns(reference[0], runs[0], pixelsPerImage);
    else d.identical = false;
    nlohmann::json env = nlohmann::json::object();
    for (const auto& [k, v] : cond.env) env[k] = v;
    nlohmann::json row = {{"name", cond.name},   {"description", cond.description}, {"env", env},
                          {"strict", cond.strict}, {"one_cpu", cond.oneCpu},         {"runs", cond.runs},
                          {"identical", d.identical}, {"images", d.images}};
    if (!d.identical && options.bisect && !draws.empty()) {
      // Smallest k whose prefix through draw k changes; the whole list is known to change. As in
      // crosscheck.cpp, binary search assumes a prefix that changes stays changed; with a
      // nondeterministic cause the named draw is one that changed in some replay.
      size_t lo = 0, hi = draws.size() - 1;
      uint64_t replays = 0;
      while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        ++replays;
        if (changes(ref, cond, render, mid)) hi = mid;
        else lo = mid + 1;
      }
      row["first_changing_draw"] = {
          {"draw_index", lo}, {"command_index", draws[lo]}, {"replays", replays}, {"state", stateAt(list, draws[lo])}};
    }
    stable = stable && d.identical;
    rows.push_back(row);
  }
  out["stable"] = stable;
  out["verdict"] = stable ? "GL output identical under every condition"
                          : "GL nondeterministic / fast-path dependent";
  out["conditions"] = rows;
  return out;
}

std::string stabilityHtml(const nlohmann::json& s, const std::string& frame) {
  std::string h = "<!doctype html><meta charset=utf-8><title>GL stability: " + escapeHtml(frame) +
                  "</title><style>body{font-family:sans-serif}td,th{border:1px solid #999;padding:2px 6px}"
                  "table{border-collapse:collapse}.bad{background:#fcc}</style><h1>GL stability: " +
                  escapeHtml(frame) + "</h1><p><b>" + escapeHtml(s.value("verdict", "")) +
                  "</b></p><table><tr><th>condition</th><th>what differs</th><th>identical</th><th>differing "
                  "pixels</th><th>first changing draw</th></tr>";
  for (const auto& row : s["conditions"]) {
    uint64_t pixels = 0;
    for (const auto& img : row["images"]) pixels += img.value("differing_pixels", uint64_t(0));
    const bool same = row["identical"].get<bool>();
    std::string draw = "";
    if (row.contains("first_changing_draw"))
      draw = "draw " + std::to_string(row["first_changing_draw"]["draw_index"].get<size_t>()) + " (command " +
             std::to_string(row["first_changing_draw"]["command_index"].get<size_t>()) + ")";
    h += std::string("<tr") + (same ? "" : " class=bad") + "><td>" + escapeHtml(row["name"].get<std::string>()) +
         "</td><td>" + escapeHtml(row["description"].get<std::string>()) + "</td><td>" + (same ? "yes" : "no") +
         "</td><td>" + std::to_string(pixels) + "</td><td>" + escapeHtml(draw) + "</td></tr>";
  }
  return h + "</table>\n";
}

}  // namespace tessera::verify
