#include "base/byte_size.h"

#include <charconv>
#include <cmath>
#include <string>

#include "base/error.h"
#include "base/resource_limits.h"

namespace tessera {

namespace {

struct Unit {
  std::string_view name;
  uint64_t bytes;
};
constexpr Unit kUnits[] = {{"", 1},     {"B", 1},      {"KiB", kKiB}, {"k", kKiB},          {"MiB", kMiB},
                           {"M", kMiB}, {"GiB", kGiB}, {"G", kGiB},   {"TiB", 1024 * kGiB}, {"T", 1024 * kGiB}};

const Unit* findUnit(std::string_view unit) {
  for (const Unit& u : kUnits)
    if (u.name == unit) return &u;
  return nullptr;
}

[[noreturn]] void fail(std::string_view text, std::string_view what, std::string_view why) {
  throw Error(std::string(what) + " '" + std::string(text) + "': " + std::string(why));
}

}  // namespace

bool isByteUnit(std::string_view unit) { return findUnit(unit) != nullptr; }

uint64_t parseByteSize(std::string_view text, std::string_view what) {
  constexpr std::string_view kExpected =
      "not a byte size: expected a number with an optional unit B, KiB, MiB, GiB or TiB (e.g. 512MiB, 8GiB)";
  const char* const begin = text.data();
  const char* const end = begin + text.size();
  // A whole number first, multiplied exactly; a fraction or exponent makes it a real number.
  uint64_t whole = 0;
  auto [p, ec] = std::from_chars(begin, end, whole);
  const bool real = p == begin || (p != end && (*p == '.' || *p == 'e' || *p == 'E'));
  double value = 0.0;
  if (real) {
    auto [q, ecReal] = std::from_chars(begin, end, value);
    if (ecReal == std::errc::result_out_of_range) fail(text, what, "out of range");
    if (ecReal != std::errc() || !std::isfinite(value) || value < 0.0 || std::signbit(value))
      fail(text, what, kExpected);
    p = q;
  } else if (ec == std::errc::result_out_of_range) {
    fail(text, what, "more than 2^64 - 1 bytes");
  } else if (ec != std::errc()) {
    fail(text, what, kExpected);
  }
  const std::string_view unitName(p, size_t(end - p));
  const Unit* unit = findUnit(unitName);
  if (!unit) fail(text, what, "unknown unit '" + std::string(unitName) + "' (use B, KiB, MiB, GiB or TiB)");
  if (!real) {
    const std::optional<uint64_t> bytes = checkedMul(whole, unit->bytes);
    if (!bytes) fail(text, what, "more than 2^64 - 1 bytes");
    return *bytes;
  }
  // Units are powers of two, so the product is exact unless it leaves double's range; 2^64 itself is
  // the first value that no longer fits.
  const double bytes = value * double(unit->bytes);
  if (!(bytes < 18446744073709551616.0)) fail(text, what, "more than 2^64 - 1 bytes");
  return uint64_t(bytes);
}

}  // namespace tessera
