// The atlas tree build (thesis §4.5): from a scene to a paging file, out of core.
//
// Implements: d_min from the parameters (absolute or D / divisor), critical-triangle handling, the RGB
// and the RGBA tree, leaf atlases for every layer (§5.1.3: layers >= 1 reuse layer 0's layout; each
// area is filled through the affine map of the first triangle of that texture in the leaf), inner
// atlases by 2x downsampling (post-order, as children complete), original images stored once each in
// blocks of about atlas size, all streamed into the paging file in a fixed order. Images are decoded
// one batch of leaves at a time through an LRU cache that evicts before it decodes. Memory is bounded
// by construction: before the atlases, the cache budget is set to what BuildParams::memoryLimit leaves
// after the resident set at that point and the atlas working set (batch, open inner atlases, decoding
// buffers per thread), minus a quarter as allocator slack, at most limit / 8 (64 MiB .. 1 GiB); if
// one batch's images do not fit that, the build stops with an Error before writing any atlas. VmRSS is
// still checked after each phase, after decoding each batch and after each batch, as a safety net.
// The bytes depend only on the scene and the parameters (never on threads or timing). Before the output
// file exists, the build has planned the whole tree and knows the file's exact size (output_size.h); an
// OutputGuard refuses a plan over a limit, or chooses d_min to fit a size (output_budget.h).
// Does not implement: rendering / paging at runtime.
#pragma once

#include <cstdint>
#include <string>

#include "mta/output_budget.h"
#include "mta/output_size.h"
#include "mta/params.h"
#include "mta/scene.h"

namespace tessera::mta {

struct BuildReport {
  double seconds = 0.0;          // wall time
  uint64_t peakResidentBytes = 0;  // max VmRSS seen at the checkpoints (see above)
  uint64_t fileBytes = 0;
  uint64_t imagesDecoded = 0;    // decodes incl. re-decodes after cache eviction
  OutputEstimate estimate;       // of the plan, before anything was written (equals fileBytes)
  double planSeconds = 0.0;      // from the start until the output was created (plans, estimate, --fit)
  double fitDMin = 0.0;          // OutputGuard::fitBytes: the d_min chosen (else 0)
  uint32_t fitPlans = 0;         // plans the search evaluated
  double fitFinerDMin = 0.0;     // the next finer candidate, which does not fit
  uint64_t fitFinerBytes = 0;    // its planned size
};

// Plans the build (build_plan.h) and its exact size (output_size.h) before the output exists; with
// guard.fitBytes, chooses d_min first (output_budget.h: fitDMin); with guard.maxBytes, refuses a plan
// larger than that (refuseIfTooBig) without creating any file. Then writes.
// Throws Error (parameters, scene, output limit, memory limit, I/O); never leaves a partial file under outPath.
BuildReport buildMta(const Scene& scene, const BuildParams& params, const std::string& outPath,
                     const OutputGuard& guard = {});

// Resident set size of this process from /proc/self/status (0 if unavailable).
uint64_t residentBytes();

}  // namespace tessera::mta
