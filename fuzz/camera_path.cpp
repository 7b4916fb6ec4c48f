// Fuzz target `camera_path`: the camera path file reader (mta/camera_path.h, docs/mta-camera-path.md),
// the camera matrices and frustum of every frame it accepts (mta/camera.h), and the writer's promise that
// "reading a written file gives back exactly the same cameras".
//
// The input is one path file, written to the scratch directory as "input.path". For a path that reads,
// each of its first kMaxFrames frames gets its view-projection matrix and frustum; a path of at most
// kMaxFrames frames is written back with writePathFile (as "written/input.path", so that a path without a
// `name` line gets the same default name) and read again, and every field of every camera must come back
// with the same bits, and the name unchanged, else the target reports a finding.
#include "mta/camera_path.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <span>
#include <string>

#include "base/error.h"
#include "fuzz/fuzz_support.h"
#include "mta/camera.h"

namespace {

using namespace tessera;
using namespace tessera::mta;

constexpr size_t kMaxFrames = 256;

bool sameBits(const Camera& a, const Camera& b) {
  auto eq = [](const auto& x, const auto& y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  return eq(a.eye, b.eye) && eq(a.target, b.target) && eq(a.up, b.up) && eq(a.tanHalfFovX, b.tanHalfFovX) &&
         eq(a.nearPlane, b.nearPlane) && eq(a.farPlane, b.farPlane);
}

void run(const uint8_t* data, size_t size) {
  const std::string path = fuzz::writeScratch("input.path", std::span<const uint8_t>(data, size));
  CameraPath p;
  try {
    p = readPathFile(path);
  } catch (const Error& e) {
    fuzz::note("camera_path", e.what());
    return;
  }
  for (size_t i = 0; i < p.frames.size() && i < kMaxFrames; ++i) {
    (void)viewProjection(p.frames[i], 64, 48);
    (void)frustumOf(p.frames[i], 64, 48);
  }
  if (p.frames.size() > kMaxFrames) return;
  // Same file name in another directory, so that a path without a `name` line reads back the same default.
  static const std::filesystem::path dir = [] {
    std::filesystem::create_directories(fuzz::scratchDir() / "written");
    return fuzz::scratchDir() / "written";
  }();
  const std::string again = (dir / "input.path").string();
  try {
    writePathFile(p, again);
  } catch (const Error& e) {
    fuzz::note("camera_path", e.what());  // a name the writer cannot hold: documented
    return;
  }
  CameraPath q;
  try {
    q = readPathFile(again);
  } catch (const Error& e) {
    fuzz::propertyViolated("camera_path", std::string("a written path does not read back: ") + e.what());
  }
  if (q.name != p.name)
    fuzz::propertyViolated("camera_path", "the name '" + p.name + "' reads back as '" + q.name + "'");
  if (q.frames.size() != p.frames.size()) fuzz::propertyViolated("camera_path", "the frame count changes");
  for (size_t i = 0; i < p.frames.size(); ++i)
    if (!sameBits(p.frames[i], q.frames[i]))
      fuzz::propertyViolated("camera_path", "frame " + std::to_string(i) + " does not read back bit-exactly");
  if (fuzz::verbose()) fuzz::note("camera_path", std::to_string(p.frames.size()) + " frame(s), read back bit-exactly");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fuzz::DescriptorCheck descriptors;
  run(data, size);
  descriptors.expectNoLeak("camera_path");
  return 0;
}
