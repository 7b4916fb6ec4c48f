// The output directory of a command (-o DIR, --report DIR): made ready before any work starts.
//
// Implements: the one place where the CLI creates a directory it will write into, and the reason it
// cannot when it cannot, as bad input (exit status 2): a file in the way (the path itself or one of its
// parents), no permission, a read-only file system. Checking first means a long run never fails at its
// end because of a typo in -o.
// Does not implement: the files inside (they go through base/atomic_file.h, which names its own path on
// failure), or cleaning up a directory it created when the command fails later.
#pragma once

#include <string>
#include <string_view>

namespace tessera::cli {

// Creates `path` and its missing parents, or accepts it as it is when it is a directory this process may
// write into. Throws Error "<path>: <reason> (<option> names the output directory)" otherwise.
void prepareOutputDirectory(const std::string& path, std::string_view option);

}  // namespace tessera::cli
