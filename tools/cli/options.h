// The option values that several `tessera` commands share, each parsed and bounded in one place.
//
// Implements: --threads (0..kMaxThreads of base/resource_limits.h, 0 = all cores), --size WxH (each
// side 1..kMaxTextureSize of raster/limits.h, digits only, overflow-checked), real-valued options with a
// documented range (NaN and infinities always refused), byte sizes (base/byte_size.h: mta build's
// --max-output and --fit) and --memory-budget (a byte size into ResourceLimits::frameBytes). Each
// add*Option registers the option with a validator that runs while the command line is parsed, so a bad
// value stops the command before any work, with exit status 2 and the message "<option> '<value>':
// <reason>" naming the bound; --help shows each range.
// Does not implement: the options of one command alone (its cmd_*.cpp registers them), or the
// semantic checks of a library (mta::BuildParams::validate and the like re-check what they receive).
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <utility>

#include "base/resource_limits.h"

namespace tessera::cli {

// Worker threads, 0..kMaxThreads (0 = all cores). `help` gets the range appended.
CLI::Option* addThreadsOption(CLI::App* cmd, int& threads, const std::string& help);
CLI::Option* addThreadsOption(CLI::App* cmd, uint32_t& threads, const std::string& help);

// "WxH": two decimal numbers joined by x or X, each in 1..kMaxTextureSize. Throws Error
// "<option> '<text>': ..." otherwise (a side too long for 64 bits included: nothing wraps around).
std::pair<int, int> parseSize(std::string_view text, std::string_view option);
// Registers --size, checked with parseSize while parsing; `help` gets the range appended.
CLI::Option* addSizeOption(CLI::App* cmd, std::string& size, const std::string& help);

// A closed or open interval of finite reals; an infinite bound means "no bound on that side".
struct RealRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool minOpen = false, maxOpen = false;

  bool contains(double v) const;
  // "> 0", ">= 0", "in (0, 180)", "in [0, 1]": what --help and the messages say.
  std::string describe() const;
};
inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr RealRange kPositive{0.0, kInf, true, false};
inline constexpr RealRange kNonNegative{0.0, kInf, false, false};

// Registers a real-valued option whose value must be finite and inside `range`; `help` gets the range
// appended. The value stored is CLI11's conversion of the text, as for any option.
CLI::Option* addRealOption(CLI::App* cmd, const std::string& name, double& value, const std::string& help,
                           const RealRange& range);

// A byte size option (base/byte_size.h: 512MiB, 8GiB, ...), at least 1 byte, parsed while the command line
// is: a bad value exits 2 with "<name> '<text>': <reason>". `help` gets the accepted form appended.
CLI::Option* addByteSizeOption(CLI::App* cmd, const std::string& name, uint64_t& bytes, const std::string& help);

// --memory-budget SIZE: ResourceLimits::frameBytes, at least 1 byte (docs/limits.md).
CLI::Option* addMemoryBudgetOption(CLI::App* cmd, ResourceLimits& limits);

// The budgets of a model load (docs/limits.md), for every command that reads a model file:
// --model-budget-instances N, --model-budget-triangles N, --model-budget-vertices N (whole numbers >= 1)
// and --model-budget-textures SIZE (decoded RGBA8 bytes, a byte size >= 1B). The loaders' messages name
// these options.
void addModelBudgetOptions(CLI::App* cmd, ResourceLimits& limits);

}  // namespace tessera::cli
