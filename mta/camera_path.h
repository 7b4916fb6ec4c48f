// Camera paths for the atlas tree renderer: the built-in paths laid out over a scene's bounding box, and
// the camera path file (docs/mta-camera-path.md).
//
// Implements: "thesis" (an imitation of the 300-frame Berlin animation of Buchholz's thesis §4.7.1:
// rapid changes between pedestrian views and a full overview), "orbit" and "street"; reading and writing
// path files, whose reader treats its input as hostile: bounded reading (file, line and frame limits of
// base/resource_limits.h), text only (UTF-8, no control characters), every number range-checked.
// Everything is computed with + - * / sqrt and detSin/detCos (base/det_math.h) only, so a path has the
// same bits on every machine.
// Does not implement: the camera itself (camera.h), rendering along a path (tree_renderer.h).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "mta/camera.h"
#include "mta/paging_file.h"

namespace tessera::mta {

// The largest magnitude of a number in a path file (eye, target, up, near, far): with it and tan_half_fov in
// [kMinTanHalfFov, kMaxTanHalfFov] (params.h), the float view-projection of every frame stays finite.
constexpr double kMaxPathCoordinate = 1e15;

struct CameraPath {
  std::string name;
  std::vector<Camera> frames;
};

// Names of the built-in paths, for --help: "thesis" (300 frames), "orbit" (120), "street" (120).
std::vector<std::string> builtinPathNames();

// A built-in path laid out over a scene's bounding box {min x, y, z, max x, y, z} (+y is up, the ground is
// taken to be at min y). Every frame has up = (0, 1, 0), the default tanHalfFovX (60 degrees), near =
// 1e-4 · D and far = 4 · D with D the box diagonal (callers may override these afterwards).
// frames = 0 gives the path's default count; any other count resamples the same path (frame i of n sits
// at path time i / (n - 1)).
// Throws Error for an unknown name (listing the known ones), more than kMaxPathFrames frames
// (base/resource_limits.h), or non-finite or inverted bounds.
CameraPath builtinPath(std::string_view name, const std::array<float, 6>& sceneBounds, uint32_t frames = 0);
// builtinPath over the union of the root bounds of an atlas tree's trees, with the build's field of view on
// every frame (so that minDistance needs no rescaling for it): what `mta render --path <name>` lays out,
// and the golden frames too. Throws Error when the tree has no triangles.
CameraPath builtinPathOverTree(std::string_view name, const MtaMeta& meta, uint32_t frames = 0);

// Reads a camera path file. The path's name is the file's `name` directive, else the file name without
// its extension (bytes that are not UTF-8 replaced by '?'). Throws Error("<file>:<line>: <reason>") for any
// malformed line, invalid camera, number out of range, non-text byte, or a file, line or frame count over
// its limit (docs/mta-camera-path.md).
CameraPath readPathFile(const std::string& path);

// Writes `p` so that readPathFile gives back exactly the same bits (shortest round-trip decimal numbers;
// tan_half_fov / near / far / up directives are written whenever they change). Written to
// path.tmp-<pid>, then renamed. Throws Error naming the file for anything the reader would refuse: a frame
// that is invalid or out of range, a name that cannot be represented (control characters, '#', surrounding
// spaces, not UTF-8, too long), too many frames or bytes; or if the file cannot be written.
void writePathFile(const CameraPath& p, const std::string& path);

}  // namespace tessera::mta
