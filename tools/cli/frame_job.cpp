#include "tools/cli/frame_job.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>

#include "raster/counters.h"
#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "raster/serialize.h"
#include "base/atomic_file.h"

namespace tessera::cli {

void writeTextFile(const std::string& path, const std::string& text) { writeFileAtomically(path, text); }

namespace {

std::string suffixed(const std::string& path, const std::string& suffix, const std::string& ext) {
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of('/');
  const std::string stem = (dot != std::string::npos && (slash == std::string::npos || dot > slash)) ? path.substr(0, dot) : path;
  return stem + suffix + ext;
}

}  // namespace

nlohmann::json runFrame(const CommandList& list, const FrameJob& job) {
  using Clock = std::chrono::steady_clock;
  nlohmann::json out;
  out["frame"] = job.name;
  out["threads"] = job.threads;
  out["counters"] = toJson(countCommands(list));

  CpuBackend backend(RenderOptions{job.threads, false, job.limits});
  const auto t0 = Clock::now();
  backend.execute(list, job.name);
  const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();

  const auto& s = backend.stats();
  out["pipeline"] = {{"primitives_assembled", s.primitives_assembled},
                     {"primitives_dropped_by_program", s.primitives_dropped_by_program},
                     {"primitives_culled", s.primitives_culled},
                     {"primitives_clipped", s.primitives_clipped},
                     {"triangles_binned", s.triangles_binned},
                     {"quads_shaded", s.quads_shaded},
                     {"fragments_shaded", s.fragments_shaded},
                     {"helper_invocations", s.helper_invocations},
                     {"fragments_depth_failed", s.fragments_depth_failed},
                     {"fragments_discarded", s.fragments_discarded},
                     {"pixels_written", s.pixels_written},
                     {"tiles_rasterized", s.tiles_rasterized}};

  nlohmann::json images = nlohmann::json::array();
  bool first = true;
  for (const PresentedImage& img : backend.presented()) {
    const TextureData& tex = *backend.texture(img.texture);
    nlohmann::json e;
    e["attachment"] = img.attachment;
    e["level"] = img.level;
    e["layer"] = img.layer;
    e["format"] = std::string(formatName(tex.desc.format));
    e["width"] = levelWidth(tex.desc, img.level);
    e["height"] = levelHeight(tex.desc, img.level);
    e["image_sha256"] = imageSha256(tex, img.level, img.layer);
    if (!job.imagePath.empty()) {
      std::string suffix;
      if (img.attachment) suffix += ".a" + std::to_string(img.attachment);
      if (img.layer && tex.desc.layers > 1) suffix += ".l" + std::to_string(img.layer);
      const std::string ext = imageExtension(tex.desc.format);
      const std::string path = first && ext == ".png" ? job.imagePath : suffixed(job.imagePath, suffix, ext);
      writeImage(tex, img.level, img.layer, path);
      e["file"] = path;
    }
    if (first) out["image_sha256"] = e["image_sha256"];
    first = false;
    images.push_back(e);
  }
  out["images"] = images;
  out["timing"] = {{"oracle_ms", ms}};
  if (!job.recordPath.empty()) writeFrame(list, job.recordPath);
  if (!job.statsPath.empty()) writeTextFile(job.statsPath, out.dump(2) + "\n");
  return out;
}

}  // namespace tessera::cli
