// Summary of a paging file for `tessera mta info` (docs/mta-format.md).
//
// Implements: the JSON description (depth, nodes, leaves, per-level node counts, atlas coverage
// mean/min over leaves, file size, block counts/bytes by kind, d_min, critical triangles, parameters)
// and optionally the verification of every block checksum.
// Does not implement: reading (paging_file.h).
#pragma once

#include <nlohmann/json.hpp>

#include "mta/paging_file.h"

namespace tessera::mta {

// verifyBlocks: read every block and check its SHA-256 (Error on the first mismatch).
nlohmann::json describe(const PagingFile& f, bool verifyBlocks = false);

}  // namespace tessera::mta
