#include "tools/cli/output_directory.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "base/error.h"

namespace tessera::cli {

namespace fs = std::filesystem;

namespace {

// The deepest existing path among `path` and its parents ("" when none exists, as for a relative path
// whose first component is missing: then the working directory is the one that exists).
fs::path deepestExisting(const fs::path& path) {
  std::error_code ec;
  for (fs::path p = path; !p.empty(); p = p.parent_path()) {
    if (fs::exists(fs::symlink_status(p, ec))) return p;
    if (p == p.parent_path()) break;
  }
  return {};
}

}  // namespace

void prepareOutputDirectory(const std::string& path, std::string_view option) {
  auto refuse = [&](const std::string& reason) {
    throw Error(fmt::format("{}: {} ({} names the output directory)", path, reason, option));
  };
  if (path.empty()) throw Error(fmt::format("{}: an empty path is not a directory", option));
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (fs::is_directory(st)) {
    // Files are created inside it: writing and searching it are both needed.
    if (::access(path.c_str(), W_OK | X_OK) != 0) refuse(fmt::format("cannot write into it: {}", std::strerror(errno)));
    return;
  }
  if (fs::exists(st)) refuse("exists and is not a directory");
  if (fs::create_directories(path, ec); !ec) return;
  const std::string reason = ec.message();
  // Name the component in the way when there is one; otherwise the system's reason (no permission,
  // read-only file system, ...).
  const fs::path existing = deepestExisting(fs::path(path).parent_path());
  if (!existing.empty() && !fs::is_directory(existing, ec))
    refuse(fmt::format("cannot create the directory: {} is not a directory", existing.string()));
  refuse("cannot create the directory: " + reason);
}

}  // namespace tessera::cli
