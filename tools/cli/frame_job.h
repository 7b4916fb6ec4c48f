// Rendering one frame on the oracle and writing what a user keeps: images, the stats JSON and,
// optionally, the recorded frame. Shared by `render`, `replay` and `demo`.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "base/resource_limits.h"
#include "raster/command_list.h"

namespace tessera::cli {

struct FrameJob {
  std::string name;          // scene or frame file name, used in messages and the JSON
  int threads = 0;
  std::string imagePath;     // "" = no images; else the first image's path (others get suffixes)
  std::string statsPath;     // "" = no stats file
  std::string recordPath;    // "" = do not record
  ResourceLimits limits;     // the frame budget (--memory-budget), checked before anything is allocated
};

// Validates (against job.limits) and renders `list`, writes the requested files atomically, and returns the stats JSON:
// { "frame", "threads", "counters" {...}, "pipeline" {...}, "images": [{file, attachment, level,
//   layer, format, width, height, image_sha256}], "image_sha256" (first image), "timing" {...} }.
nlohmann::json runFrame(const CommandList& list, const FrameJob& job);

// Writes text to path atomically (temp file + rename); throws Error naming the path.
void writeTextFile(const std::string& path, const std::string& text);

}  // namespace tessera::cli
