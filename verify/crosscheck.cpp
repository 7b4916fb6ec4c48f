#include "verify/crosscheck.h"

#include <chrono>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <type_traits>

#include "raster/counters.h"
#include "raster/cpu_backend.h"
#include "raster/image_io.h"

namespace tessera::verify {

namespace {

using Clock = std::chrono::steady_clock;

std::string imageName(const PresentedImage& p, uint32_t layers) {
  std::string n = "attachment " + std::to_string(p.attachment);
  if (layers > 1) n += ", layer " + std::to_string(p.layer);
  return n;
}

// Renders on both sides and judges every presented image.
struct Side {
  std::unique_ptr<CpuBackend> oracle;
  std::vector<ImageVerdict> images;
  double oracleMs = 0, otherMs = 0;
  bool passed = true;
  std::vector<ExpectationUse> expectations;  // the matched entries and what they covered
};

Side runBoth(const CommandList& list, std::string_view name, const CrosscheckOptions& o, const OtherBackend& other) {
  Side s;
  s.oracle = std::make_unique<CpuBackend>(
      RenderOptions{o.threads, true, o.limits, o.otherSubpixelBits > 0 ? o.otherSubpixelBits : 4});
  const auto t0 = Clock::now();
  s.oracle->execute(list, name);
  s.oracleMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  const std::vector<std::vector<uint8_t>> others = other.render(list, name, s.otherMs);
  const auto presented = s.oracle->presented();
  if (presented.size() != others.size())
    throw Error(std::string(name) + ": the oracle presents " + std::to_string(presented.size()) + " images, " +
                other.name + " " + std::to_string(others.size()));
  for (size_t i = 0; i < presented.size(); ++i) {
    const PresentedImage& p = presented[i];
    const TextureData& tex = *s.oracle->texture(p.texture);
    ImageVerdict v;
    v.name = imageName(p, tex.desc.layers);
    v.image = p;
    v.other = others[i];
    v.judgement = judge(tex, p.level, p.layer, v.other);
    v.oracle = imagePixels(tex, p.level, p.layer);
    v.lo = imagePixels(*tex.prov->lo, p.level, p.layer);
    v.hi = imagePixels(*tex.prov->hi, p.level, p.layer);
    s.images.push_back(std::move(v));
  }
  if (o.expectations && o.condition)
    s.expectations = applyExpectations(s.images, list, o.expectations->matching(*o.condition, name, &list), o.threads, o.limits);
  for (const ImageVerdict& v : s.images) s.passed = s.passed && v.judgement.passed();
  return s;
}

// `firstCalls` keeps the GL call counts of the first (full-frame) run: bisection replays prefixes later.
OtherBackend glOther(gl::GlBackend& gl, std::shared_ptr<std::optional<gl::GlCallCounts>> firstCalls) {
  return {"gl", [&gl, firstCalls](const CommandList& list, std::string_view name, double& ms) {
            gl.execute(list, name);
            ms = gl.lastExecuteMs();
            if (!*firstCalls) *firstCalls = gl.calls();
            std::vector<std::vector<uint8_t>> out;
            for (const PresentedImage& p : gl.presented()) out.push_back(gl.readImage(p));
            return out;
          }};
}

OtherBackend fastPathOther(int threads, const ResourceLimits& limits) {
  return {"cpu", [threads, limits](const CommandList& list, std::string_view name, double& ms) {
            CpuBackend b(RenderOptions{threads, false, limits});
            const auto t0 = Clock::now();
            b.execute(list, name);
            ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
            std::vector<std::vector<uint8_t>> out;
            for (const PresentedImage& p : b.presented()) out.push_back(imagePixels(*b.texture(p.texture), p.level, p.layer));
            return out;
          }};
}

nlohmann::json counterEquality(const CommandList& list, const gl::GlCallCounts& c) {
  const FrameCounters f = countCommands(list);
  const std::pair<const char*, std::pair<uint64_t, uint64_t>> rows[] = {
      {"draw_calls", {f.draw_calls, c.draw_calls}},
      {"texture_binds", {f.texture_binds, c.texture_binds}},
      {"sampler_binds", {f.sampler_binds, c.sampler_binds}},
      {"program_binds", {f.program_binds, c.program_binds}},
      {"vertex_buffer_binds", {f.vertex_buffer_binds, c.vertex_buffer_binds}},
      {"index_buffer_binds", {f.index_buffer_binds, c.index_buffer_binds}},
      {"uniform_updates", {f.uniform_updates, c.uniform_updates}},
      {"framebuffer_binds", {f.render_target_changes + f.redundant_render_target_binds, c.framebuffer_binds}}};
  nlohmann::json j = nlohmann::json::object();
  bool equal = true;
  for (const auto& [name, v] : rows) {
    j[name] = {{"oracle", v.first}, {"gl", v.second}};
    equal = equal && v.first == v.second;
  }
  return {{"equal", equal}, {"counts", j}};
}

}  // namespace

nlohmann::json stateAt(const CommandList& list, size_t index) {
  nlohmann::json units = nlohmann::json::object();
  std::map<ResourceId, std::string> programs;
  std::map<ResourceId, TextureDesc> textures;
  std::string program = "none";
  nlohmann::json blend, depth, raster, viewport, scissor, target;
  auto rect = [](const Rect& r) { return nlohmann::json{r.x, r.y, r.w, r.h}; };
  const auto& cmds = list.commands();
  for (size_t i = 0; i <= index && i < cmds.size(); ++i) {
    std::visit(
        [&](const auto& c) {
          using T = std::decay_t<decltype(c)>;
          if constexpr (std::is_same_v<T, CreateProgram>) programs[c.id] = c.name;
          if constexpr (std::is_same_v<T, CreateTexture>) textures[c.id] = c.desc;
          if constexpr (std::is_same_v<T, UseProgram>) program = programs.count(c.program) ? programs[c.program] : "none";
          if constexpr (std::is_same_v<T, BindTexture>) {
            if (c.texture == kNone) {
              units.erase(std::to_string(c.unit));
            } else {
              const TextureDesc& d = textures[c.texture];
              units[std::to_string(c.unit)] = {{"texture", c.texture},
                                               {"format", std::string(formatName(d.format))},
                                               {"size", {d.width, d.height, d.layers}},
                                               {"levels", d.levels}};
            }
          }
          if constexpr (std::is_same_v<T, SetBlendState>)
            blend = {{"enabled", c.state.enabled}, {"eq_rgb", int(c.state.eqRgb)}, {"src_rgb", int(c.state.srcRgb)},
                     {"dst_rgb", int(c.state.dstRgb)}};
          if constexpr (std::is_same_v<T, SetDepthState>)
            depth = {{"test", c.state.test}, {"write", c.state.write}, {"func", int(c.state.func)}};
          if constexpr (std::is_same_v<T, SetRasterState>)
            raster = {{"cull", int(c.state.cull)}, {"front_ccw", c.state.frontCcw}, {"clip_mask", c.state.clipMask}};
          if constexpr (std::is_same_v<T, SetViewport>) viewport = rect(c.rect);
          if constexpr (std::is_same_v<T, SetScissor>) scissor = {{"enabled", c.state.enabled}, {"rect", rect(c.state.rect)}};
          if constexpr (std::is_same_v<T, SetRenderTarget>)
            target = {{"color", c.target.color}, {"depth", c.target.depth}, {"layer", c.target.layer == kLayered ? -1 : int64_t(c.target.layer)}};
        },
        cmds[i]);
  }
  return {{"command", index},        {"program", program}, {"units", units},   {"blend", blend},
          {"depth", depth},          {"raster", raster},   {"viewport", viewport}, {"scissor", scissor},
          {"render_target", target}};
}

CrosscheckResult crosscheck(const CommandList& list, std::string_view frameName, const CrosscheckOptions& o,
                            gl::GlBackend* gl) {
  if (!gl && !o.selfCheck) throw Error("crosscheck: no GL backend");
  auto firstCalls = std::make_shared<std::optional<gl::GlCallCounts>>();
  CrosscheckOptions opt = o;
  if (gl && o.expectations && !o.condition) opt.condition = runConditionOf(*gl);
  if (opt.otherSubpixelBits <= 0) opt.otherSubpixelBits = gl ? gl->info().limits.subpixelBits : kSubpixelBits;
  CrosscheckResult r = crosscheck(list, frameName, opt, gl ? glOther(*gl, firstCalls) : fastPathOther(o.threads, o.limits));
  r.json["other_subpixel_bits"] = opt.otherSubpixelBits > 0 ? opt.otherSubpixelBits : 4;
  if (gl && *firstCalls) {
    r.json["counters"] = counterEquality(list, **firstCalls);
    r.json["gl_calls"] = (*firstCalls)->toJson();
    r.json["gl_info"] = gl->info().toJson();
    if (!r.json["counters"]["equal"].get<bool>()) r.passed = false, r.json["passed"] = false;
  }
  return r;
}

CrosscheckResult crosscheck(const CommandList& list, std::string_view frameName, const CrosscheckOptions& o,
                            const OtherBackend& other) {
  CrosscheckResult r;
  Side s = runBoth(list, frameName, o, other);
  r.passed = s.passed;
  nlohmann::json images = nlohmann::json::array();
  uint64_t pixels = 0, exact = 0, unexplained = 0, expected = 0;
  for (const ImageVerdict& v : s.images) {
    nlohmann::json j = toJson(v.judgement);
    j["image"] = v.name;
    j["expected_deviation"] = v.expectedDeviation;
    images.push_back(j);
    pixels += v.judgement.pixels, exact += v.judgement.exact, unexplained += v.judgement.unexplained;
    expected += v.expectedDeviation;
  }
  nlohmann::json& out = r.json;
  out["frame"] = std::string(frameName);
  out["backends"] = "cpu," + other.name;
  out["passed"] = r.passed;
  out["pixels"] = pixels;
  out["exact_match_percent"] = pixels ? 100.0 * double(exact) / double(pixels) : 100.0;
  out["unexplained"] = unexplained;
  out["expected_deviation"] = expected;
  if (o.expectations)
    out["expectations"] = {{"file", o.expectations->file},
                           {"condition", o.condition ? o.condition->toJson() : nlohmann::json(nullptr)},
                           {"matched", toJson(s.expectations)}};
  out["images"] = images;
  out["timing"] = {{"oracle_provenance_ms", s.oracleMs}, {"other_ms", s.otherMs}};
  if (!s.passed && o.bisect) {
    // Draw-level bisection: replay growing prefixes on both sides; the first prefix whose images
    // fail names the draw. Binary search assumes that once a prefix fails, longer ones fail too,
    // which holds unless a later draw paints over every unexplained pixel (then the reported draw
    // is still one that diverges, just not necessarily the first).
    std::vector<size_t> draws;
    for (size_t i = 0; i < list.commands().size(); ++i)
      if (std::holds_alternative<Draw>(list.commands()[i])) draws.push_back(i);
    // Smallest k whose prefix (through draw k) fails; the whole list (k = n - 1) is known to fail.
    size_t lo = 0, hi = draws.empty() ? 0 : draws.size() - 1;
    uint64_t replays = 0;
    while (lo < hi) {
      const size_t mid = lo + (hi - lo) / 2;
      CommandList prefix = list;
      prefix.truncate(draws[mid] + 1);
      const Side p = runBoth(prefix, frameName, o, other);
      ++replays;
      if (p.passed) lo = mid + 1;
      else hi = mid;
    }
    const size_t first = lo;
    if (!draws.empty()) {
      out["first_diverging_draw"] = {{"draw_index", first},
                                     {"command_index", draws[first]},
                                     {"replays", replays},
                                     {"state", stateAt(list, draws[first])}};
    }
  }
  r.images = std::move(s.images);
  return r;
}

}  // namespace tessera::verify
