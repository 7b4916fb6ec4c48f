// Where the CLI finds the files that ship in the repository (data/railway.glb, golden/).
//
// Implements: resolving a repository-relative default such as "data/railway.glb". The path is used as
// given when it exists relative to the working directory (the README runs everything from the
// clone's root); otherwise it is looked up relative to the clone that holds the running executable
// (build/tessera → the folder above build/), so `cd build && ./tessera demo` finds it too.
// Does not implement: search paths or environment variables; an explicit option always wins.
#pragma once

#include <string>

namespace tessera::cli {

// `rel` itself if it exists, else <clone>/<rel> if that exists, else `rel` unchanged (so the error
// that follows names the path the user sees in --help).
std::string repoPath(const std::string& rel);

}  // namespace tessera::cli
