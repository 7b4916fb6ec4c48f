// `tessera texel` on a recorded frame (.tframe): the arguments and the run (cmd_texel_frame.cpp).
// Does not implement: the atlas-tree analysis of `tessera texel tree.mta` (cmd_texel.cpp).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace tessera::cli {

struct TexelFrameArgs {
  std::string input;    // A.tframe
  std::string against;  // B.tframe, or empty
  std::string out;      // -o DIR
  int threads = 0;
};

// Probes the frame(s), writes texel.json, lambda*.png, histogram*.png, lambda*.i32 (and lod_diff.png
// with --against) into a.out, and returns the summary. Throws Error (exit 2) for unreadable, corrupt or
// invalid frames and for frames of different sizes, before writing anything.
nlohmann::json runTexelFrame(const TexelFrameArgs& a);

}  // namespace tessera::cli
