// The golden manifest, golden/manifest.json: test name -> one image file with its pixel hash, format,
// size and provenance (docs: README.md "Layout", CONTRIBUTING.md "Golden bytes are sacred").
//
// Implements: reading it with validation and writing it back. A test name maps to one image:
// "<scene>" = attachment 0 (layer 0), "<scene>.a<N>" = attachment N, "<scene>.l<N>" = layer N, and
// "mta_railway.fNNN" = frame NNN of the atlas tree goldens (railway_frames.h). The file is
//   { "tests": { "<name>": { "attachment", "command", "file", "format", "height", "image_sha256",
//                            "layer", "scene", "width" }, ... }, "version": 1 }
// written as nlohmann::json's dump(2) plus a newline (keys sorted), so reading a manifest and writing
// it back reproduces its bytes.
// Validation: every field must be present with its type (strings, unsigned integers; image_sha256 is
// 64 lower-case hex digits, format a known format name, width and height at least 1, file a relative
// path without ".."); unknown fields are refused, since writing the manifest back would drop them.
// Each failure is an Error naming the file and the field ("golden/manifest.json: tests["blend"].width:
// missing"). Does not implement: the images themselves (golden_diff.h, golden_run.h).
#pragma once

#include <cstdint>
#include <map>
#include <string>

namespace tessera::golden {

struct ManifestEntry {
  std::string file;         // relative to the golden directory: "images/<name>.png" or ".exr"
  std::string imageSha256;  // SHA-256 of the decoded pixels (raster/image_io.h image_sha256)
  std::string format;       // formatName() of the image's format: "RGBA8", "R32UI", ...
  uint32_t width = 0, height = 0;
  std::string scene;  // the built-in scene, or "mta_railway" for the atlas tree frames
  uint32_t attachment = 0, layer = 0;
  std::string command;  // the CLI command that reproduces the image

  bool operator==(const ManifestEntry&) const = default;
};

struct Manifest {
  int version = 1;
  std::map<std::string, ManifestEntry> tests;  // by test name
};

// Parses manifest text; `path` only names the file in errors. Throws Error naming path and field.
Manifest parseManifest(const std::string& text, const std::string& path);
// Reads and validates the file. Throws Error naming the file when it cannot be read or is malformed.
Manifest readManifest(const std::string& path);
// <dir>/manifest.json; a directory without one holds an empty manifest (check then fails every image,
// update creates the file). Other errors as readManifest.
Manifest loadManifest(const std::string& dir);

// The bytes of the file (dump(2) of the JSON, then "\n").
std::string manifestText(const Manifest& m);
// Writes manifestText(m) atomically (base/atomic_file.h). Throws Error naming the path.
void writeManifest(const std::string& path, const Manifest& m);

}  // namespace tessera::golden
