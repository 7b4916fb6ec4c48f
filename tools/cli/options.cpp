#include "tools/cli/options.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "base/byte_size.h"
#include "base/error.h"
#include "raster/limits.h"

namespace tessera::cli {

namespace {

[[noreturn]] void refuse(std::string_view option, std::string_view text, std::string_view why) {
  throw Error(fmt::format("{} '{}': {}", option, text, why));
}

// A validator that throws Error (the message names the option) rather than returning CLI11's text, so
// that every bound of this file reads the same way; main() turns the Error into exit status 2.
CLI::Validator checker(std::string description, std::function<void(const std::string&)> check) {
  return CLI::Validator(
      [check = std::move(check)](std::string& text) {
        check(text);
        return std::string();
      },
      std::move(description));
}

// The whole of `text` as a decimal number without sign; nullopt for anything else, or when it does not
// fit in 64 bits.
std::optional<uint64_t> decimal(std::string_view text) {
  uint64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return v;
}

const std::string kThreadsRange = fmt::format("0..{}, 0 = all cores", kMaxThreads);

template <class T>
CLI::Option* addThreads(CLI::App* cmd, T& threads, const std::string& help) {
  // Transforms as well as checks: the text CLI11 converts is then the plain decimal that was checked
  // (its own conversion would read "010" as octal).
  return cmd->add_option("--threads", threads, help + " (" + kThreadsRange + ")")
      ->transform(CLI::Validator(
          [](std::string& text) {
            const std::optional<uint64_t> n = decimal(text);
            if (!n) refuse("--threads", text, "not a whole number (" + kThreadsRange + ")");
            if (*n > uint64_t(kMaxThreads))
              refuse(
                  "--threads", text,
                  fmt::format("more than the limit of {} worker threads (0 = all cores; docs/limits.md)", kMaxThreads));
            text = std::to_string(*n);
            return std::string();
          },
          fmt::format("0..{}", kMaxThreads)));
}

}  // namespace

CLI::Option* addThreadsOption(CLI::App* cmd, int& threads, const std::string& help) {
  return addThreads(cmd, threads, help);
}
CLI::Option* addThreadsOption(CLI::App* cmd, uint32_t& threads, const std::string& help) {
  return addThreads(cmd, threads, help);
}

std::pair<int, int> parseSize(std::string_view text, std::string_view option) {
  const std::string expected = fmt::format("expected WxH with 1 <= W, H <= {}, e.g. 640x480", kMaxTextureSize);
  const size_t x = text.find_first_of("xX");
  if (x == std::string_view::npos) refuse(option, text, expected);
  const std::optional<uint64_t> w = decimal(text.substr(0, x)), h = decimal(text.substr(x + 1));
  if (!w || !h) refuse(option, text, expected);
  for (const auto& [side, v] : {std::pair{"width", *w}, std::pair{"height", *h}})
    if (v < 1 || v > uint64_t(kMaxTextureSize))
      refuse(option, text, fmt::format("the {} {} is outside 1..{} ({})", side, v, kMaxTextureSize, expected));
  return {int(*w), int(*h)};
}

CLI::Option* addSizeOption(CLI::App* cmd, std::string& size, const std::string& help) {
  return cmd->add_option("--size", size, fmt::format("{} (each side 1..{})", help, kMaxTextureSize))
      ->check(
          checker(fmt::format("WxH, 1..{}", kMaxTextureSize), [](const std::string& t) { parseSize(t, "--size"); }));
}

bool RealRange::contains(double v) const {
  if (!std::isfinite(v)) return false;
  const bool aboveMin = minOpen ? v > min : v >= min;
  const bool belowMax = maxOpen ? v < max : v <= max;
  return aboveMin && belowMax;
}

std::string RealRange::describe() const {
  const bool hasMin = std::isfinite(min), hasMax = std::isfinite(max);
  if (hasMin && hasMax) return fmt::format("in {}{}, {}{}", minOpen ? "(" : "[", min, max, maxOpen ? ")" : "]");
  if (hasMin) return fmt::format("{} {}", minOpen ? ">" : ">=", min);
  if (hasMax) return fmt::format("{} {}", maxOpen ? "<" : "<=", max);
  return "finite";
}

CLI::Option* addRealOption(CLI::App* cmd, const std::string& name, double& value, const std::string& help,
                           const RealRange& range) {
  const std::string what = "a finite number " + range.describe();
  return cmd->add_option(name, value, help + " (" + what + ")")
      ->check(checker(range.describe(), [name, what, range](const std::string& text) {
        double v = 0.0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec != std::errc() || end != text.data() + text.size() || !range.contains(v))
          refuse(name, text, "expected " + what);
      }));
}

CLI::Option* addByteSizeOption(CLI::App* cmd, const std::string& name, uint64_t& bytes, const std::string& help) {
  return cmd
      ->add_option_function<std::string>(
          name, [&bytes, name](const std::string& text) { bytes = parseByteSize(text, name); },
          help + " (a size such as 512MiB or 16GiB, at least 1B)")
      ->check(checker("SIZE >= 1B", [name](const std::string& text) {
        if (parseByteSize(text, name) == 0) refuse(name, text, "must be at least 1 byte");
      }));
}

CLI::Option* addMemoryBudgetOption(CLI::App* cmd, ResourceLimits& limits) {
  const std::string help = fmt::format(
      "Memory a frame may create: every texture level and layer, buffer and render target, summed and checked "
      "before anything is allocated (a size such as 512MiB or 16GiB, at least 1B; default {}; docs/limits.md)",
      formatBytes(ResourceLimits{}.frameBytes));
  return cmd
      ->add_option_function<std::string>(
          "--memory-budget",
          [&limits](const std::string& text) { limits.frameBytes = parseByteSize(text, "--memory-budget"); }, help)
      ->check(checker("SIZE >= 1B", [](const std::string& text) {
        if (parseByteSize(text, "--memory-budget") == 0)
          refuse("--memory-budget", text, "a frame budget must be at least 1 byte");
      }));
}

namespace {

void addCountBudget(CLI::App* cmd, const std::string& name, uint64_t& limit, const std::string& what) {
  cmd->add_option_function<std::string>(
         name, [&limit, name](const std::string& text) { limit = *decimal(text); },
         fmt::format("Most {} a model may describe, checked before its geometry is read (default {}; docs/limits.md)",
                     what, limit))
      ->check(checker("N >= 1", [name](const std::string& text) {
        const std::optional<uint64_t> n = decimal(text);
        if (!n || *n == 0) refuse(name, text, "expected a whole number >= 1");
      }));
}

}  // namespace

void addModelBudgetOptions(CLI::App* cmd, ResourceLimits& limits) {
  addCountBudget(cmd, "--model-budget-instances", limits.modelInstances,
                 "instances (nodes reached through the scene graph)");
  addCountBudget(cmd, "--model-budget-triangles", limits.modelTriangles, "triangles over all instances");
  addCountBudget(cmd, "--model-budget-vertices", limits.modelVertices, "vertices over all instances");
  cmd->add_option_function<std::string>(
         "--model-budget-textures",
         [&limits](const std::string& text) {
           limits.modelTextureBytes = parseByteSize(text, "--model-budget-textures");
         },
         fmt::format("Decoded RGBA8 bytes of all of a model's textures, from their headers, before any is decoded "
                     "(a size such as 2GiB, at least 1B; default {}; docs/limits.md)",
                     formatBytes(ResourceLimits{}.modelTextureBytes)))
      ->check(checker("SIZE >= 1B", [](const std::string& text) {
        if (parseByteSize(text, "--model-budget-textures") == 0)
          refuse("--model-budget-textures", text, "a texture budget must be at least 1 byte");
      }));
}

}  // namespace tessera::cli
