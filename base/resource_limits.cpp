#include "base/resource_limits.h"

#include <cstdio>

namespace tessera {

std::optional<uint64_t> checkedMul(uint64_t a, uint64_t b) {
  uint64_t r = 0;
  if (__builtin_mul_overflow(a, b, &r)) return std::nullopt;
  return r;
}

std::optional<uint64_t> checkedAdd(uint64_t a, uint64_t b) {
  uint64_t r = 0;
  if (__builtin_add_overflow(a, b, &r)) return std::nullopt;
  return r;
}

std::string formatBytes(uint64_t bytes) {
  static const char* const kUnits[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  if (bytes < 1024) return std::to_string(bytes) + " B";
  int u = 0;
  // Integer steps keep the unit choice exact; the one decimal is for reading only.
  uint64_t whole = bytes;
  while (whole >= 1024 * 1024 && u < 5) whole /= 1024, ++u;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f %s", double(whole) / 1024.0, kUnits[u + 1]);
  return buf;
}

std::string overLimitMessage(std::string_view where, std::string_view what, std::optional<uint64_t> need,
                             uint64_t limit, std::string_view option, bool bytes) {
  auto fmt = [&](uint64_t v) { return bytes ? formatBytes(v) : std::to_string(v); };
  std::string m(where);
  m += ": needs ";
  m += need ? fmt(*need) : std::string(bytes ? "more than 16.0 EiB" : "more than 2^64");
  m += " ";
  m += what;
  m += ", over the limit of " + fmt(limit);
  if (need) m += " by " + fmt(*need - limit);
  if (!option.empty()) {
    m += " (raise it with ";
    m += option;
    m += ")";
  }
  return m;
}

}  // namespace tessera
