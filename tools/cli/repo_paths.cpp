#include "tools/cli/repo_paths.h"

#include <filesystem>

namespace tessera::cli {

namespace fs = std::filesystem;

std::string repoPath(const std::string& rel) {
  std::error_code ec;
  if (fs::exists(rel, ec) || fs::path(rel).is_absolute()) return rel;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return rel;
  // The executable sits in <clone>/<build dir>/; walk up a few levels to allow nested build trees.
  fs::path dir = exe.parent_path();
  for (int up = 0; up < 3 && !dir.empty(); ++up, dir = dir.parent_path()) {
    const fs::path candidate = dir / rel;
    if (fs::exists(candidate, ec)) return candidate.string();
    if (dir == dir.root_path()) break;
  }
  return rel;
}

}  // namespace tessera::cli
