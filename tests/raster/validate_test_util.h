// Test helper shared by the validate() tests (test_validate.cpp, test_validate_budget.cpp): diagnostics as
// text, for the failure messages of the assertions.
#pragma once

#include <string>
#include <vector>

#include "raster/validate.h"

namespace tessera::testing {

// One line per diagnostic: "\n  command <index>: <message>".
inline std::string dump(const std::vector<Diagnostic>& diags) {
  std::string s;
  for (const auto& d : diags) s += "\n  command " + std::to_string(d.command) + ": " + d.message;
  return s;
}

}  // namespace tessera::testing
