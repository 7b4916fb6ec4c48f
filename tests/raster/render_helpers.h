// Test helpers: render a command list on the oracle and read back its presented images.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <initializer_list>
#include <string>
#include <vector>

#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "raster/simd_targets.h"

namespace tessera::testing {

struct Rendered {
  std::vector<std::vector<uint8_t>> images;  // top-down pixels of each presented image
  std::vector<std::string> hashes;
  detail::PipelineStats stats;
  StageTimes times;  // its skipped-work counts (hierarchical Z)
};

inline Rendered renderList(const CommandList& list, int threads) {
  CpuBackend b(RenderOptions{threads});
  b.execute(list, "test");
  Rendered r;
  for (const PresentedImage& p : b.presented()) {
    const TextureData& t = *b.texture(p.texture);
    r.images.push_back(imagePixels(t, p.level, p.layer));
    r.hashes.push_back(imageSha256(t, p.level, p.layer));
  }
  r.stats = b.stats();
  r.times = b.stageTimes();
  return r;
}

// Restores the best SIMD target when a test ends, whatever it forced.
struct SimdTargetGuard {
  SimdTargetGuard() = default;
  SimdTargetGuard(const SimdTargetGuard&) = delete;
  SimdTargetGuard& operator=(const SimdTargetGuard&) = delete;
  ~SimdTargetGuard() { simd::forceTarget("best"); }
};

// Every pipeline counter of a equals b's; `what` names the comparison in the failure.
inline void expectSameCounters(const detail::PipelineStats& a, const detail::PipelineStats& b, const std::string& what) {
  // Plain integer counters without padding: bytewise equality is field equality.
  static_assert(sizeof(detail::PipelineStats) == 12 * sizeof(uint64_t));
  EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << what << ": the pipeline counters differ";
}

// `list` rendered at each thread count gives `expected`'s image hashes and pipeline counters; `what`
// names the frame in a failure.
inline void expectRendersAs(const CommandList& list, const Rendered& expected, std::initializer_list<int> threads,
                            const std::string& what) {
  for (const int t : threads) {
    const Rendered r = renderList(list, t);
    const std::string at = what + ", " + std::to_string(t) + " threads";
    EXPECT_EQ(r.hashes, expected.hashes) << at;
    expectSameCounters(r.stats, expected.stats, at);
  }
}

// `list` on the best SIMD target, at each thread count, gives the bytes and counters of the scalar
// reference target at one thread, which it returns. Fails where the machine has no SIMD target.
inline Rendered expectBestTargetGivesReferenceFrame(const CommandList& list, std::initializer_list<int> threads,
                                                   const std::string& what) {
  const SimdTargetGuard guard;
  simd::forceTarget("reference");
  const Rendered reference = renderList(list, 1);
  simd::forceTarget("best");
  EXPECT_NE(simd::activeTarget(), "reference") << "this machine has no SIMD target: nothing to compare";
  expectRendersAs(list, reference, threads, what);
  return reference;
}

}  // namespace tessera::testing
