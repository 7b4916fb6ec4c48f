// Writing report files atomically: to `path.tmp-<pid>`, then renamed into place, so a reader never
// sees a half-written report (CONTRIBUTING.md "Outputs are written atomically").
// Images go through raster/image_io.h's writePngRGBA8, which follows the same rule.
// Does not implement: fsync (a crash may lose the file, but never leaves a torn one in its place).
#pragma once

#include <string>
#include <string_view>

namespace tessera::verify {

// Throws Error naming `path` when the file cannot be written or renamed; never leaves the temporary.
void writeTextAtomically(const std::string& path, std::string_view content);

}  // namespace tessera::verify
