// The error type of the whole project.
//
// Implements: `tessera::Error`, thrown for every user-facing failure (bad input, unwritable output).
// Its message already names the file, the command index or field, and the reason, so callers print
// it as it is; the CLI turns it into exit status 2.
// Does not implement: error codes or categories; internal bugs are not Errors.
#pragma once

#include <stdexcept>

namespace tessera {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace tessera
