// JSON cannot hold NaN or infinities (nlohmann writes them as null, which reads back as "missing").
// Reports therefore write non-finite numbers as the strings "nan", "inf" and "-inf".
// Implements: that one conversion, used by every JSON writer in verify/.
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>

namespace tessera::verify {

inline nlohmann::json jsonNumber(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return v;
}

}  // namespace tessera::verify
