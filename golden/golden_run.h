// `tessera golden check | update` as a library: the golden images under golden/ (Filament-style
// workflow; README.md, CONTRIBUTING.md "Golden bytes are sacred").
//
// Implements: check (render every golden image: options.sceneImages, then the railway frames, and demand that each matches its
// golden file bit-exactly, golden_diff.h; an entry that no image has any more is stale) and update
// (the same, then rewrite the image file and the manifest entry of every rendered image, or with
// onlyFailing of every image that did not match; stale entries are removed; the report lists every
// image whose hash changed). The report's JSON is the CLI's output.
// Does not implement: option parsing or the default paths (tools/cli/cmd_golden.cpp resolves them).
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "golden/golden_images.h"

namespace tessera::golden {

struct GoldenOptions {
  // The built-in scenes' images (tools/scenes/scene_goldens.h); empty: none (their entries are stale).
  ImageSource sceneImages;
  std::string dir = "golden";                // holds manifest.json and images/
  std::string railway = "data/railway.glb";  // "": the built-in scenes only (mta_railway entries are left alone)
  bool onlyFailing = false;                  // update: rewrite only the images that do not match
};

struct GoldenFailure {
  std::string test, reason;
};

struct GoldenChange {
  std::string test;
  std::string oldSha256;  // "" when the image had no entry
  std::string newSha256;
  int64_t pixelsChanged = 0;  // -1 when the old file had another size or format
  double maxAbsDelta = 0.0;
};

struct GoldenReport {
  bool update = false;
  size_t tests = 0, passed = 0;
  std::vector<GoldenFailure> failed;  // check: what failed; update: what needed an update
  std::vector<GoldenChange> changed;  // update only
  std::vector<std::string> stale;     // entries without an image, in name order

  // check's verdict: every image matches and no entry is stale (the CLI exits 1 otherwise).
  bool passedAll() const { return failed.empty() && stale.empty(); }
  // {"tests", "passed", "failed" (check) or "needed_update" and "changed" (update), "stale_entries"}.
  nlohmann::json toJson() const;
};

// Throws Error for a malformed manifest (manifest.h) or a missing railway.glb.
GoldenReport checkGoldens(const GoldenOptions& options);
// As check, and writes images and manifest atomically. Throws Error naming a file that cannot be written.
GoldenReport updateGoldens(const GoldenOptions& options);

}  // namespace tessera::golden
