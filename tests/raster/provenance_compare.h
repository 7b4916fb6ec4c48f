// Test helper: every provenance record of two renders of a texture compared (raster/provenance.h):
// lower and upper images, classes, flags, candidate lists and candidate depths.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "raster/provenance.h"

namespace tessera::testing {

inline bool sameCandidate(const Candidate& a, const Candidate& b) {
  return a.lo == b.lo && a.hi == b.hi && a.tags == b.tags && a.tagCount == b.tagCount && a.depth.lo == b.depth.lo &&
         a.depth.hi == b.depth.hi && a.depth.sig == b.depth.sig && a.depth.epoch == b.depth.epoch;
}

inline bool sameDepth(const CandidateDepth& a, const CandidateDepth& b) {
  return a.lo == b.lo && a.hi == b.hi && a.sig == b.sig && a.epoch == b.epoch;
}

// Every provenance record of texture `name` in a equals b's.
inline void expectSameProvenance(const Provenance& a, const Provenance& b, const std::string& name) {
  ASSERT_EQ(a.lo->levels, b.lo->levels) << name << ": lower images differ";
  ASSERT_EQ(a.hi->levels, b.hi->levels) << name << ": upper images differ";
  ASSERT_EQ(a.classes, b.classes) << name << ": classes differ";
  ASSERT_EQ(a.flags, b.flags) << name << ": flags differ";
  ASSERT_EQ(a.candidates.size(), b.candidates.size()) << name;
  for (size_t l = 0; l < a.candidates.size(); ++l) {
    ASSERT_EQ(a.candidates[l].size(), b.candidates[l].size()) << name << " level " << l;
    for (size_t i = 0; i < a.candidates[l].size(); ++i) {
      const auto &x = a.candidates[l][i], &y = b.candidates[l][i];
      ASSERT_EQ(x.size(), y.size()) << name << " level " << l << " pixel " << i << ": candidate counts differ";
      for (size_t k = 0; k < x.size(); ++k)
        ASSERT_TRUE(sameCandidate(x[k], y[k])) << name << " level " << l << " pixel " << i << " candidate " << k;
    }
  }
  ASSERT_EQ(a.depth.size(), b.depth.size()) << name;
  for (size_t l = 0; l < a.depth.size(); ++l) {
    ASSERT_EQ(a.depth[l].size(), b.depth[l].size()) << name << " level " << l;
    for (size_t i = 0; i < a.depth[l].size(); ++i)
      ASSERT_TRUE(sameDepth(a.depth[l][i], b.depth[l][i])) << name << " level " << l << " pixel " << i;
  }
}

}  // namespace tessera::testing
