// RTTA's lazy layer reallocation (rtta/layer_policy.h, Trapp & Döllner 2010 §4.2).
#include <gtest/gtest.h>

#include "base/error.h"
#include "rtta/layer_policy.h"

namespace tessera::rtta {
namespace {

TEST(RttaLayers, ExactFollowsTheNeedEveryFrame) {
  LayerAllocator a(parseLayerPolicy("exact"));
  EXPECT_EQ(a.frame(3), 3u);
  EXPECT_EQ(a.frame(1), 1u);
  EXPECT_EQ(a.frame(0), 1u) << "an empty atlas still needs one layer";
  EXPECT_EQ(a.frame(4), 4u);
  EXPECT_EQ(a.reallocations(), 3u);  // 0 -> 3 -> 1 -> 4
}

TEST(RttaLayers, LazyGrowsAtOnceAndShrinksOnlyAfterKStableFrames) {
  LayerAllocator a(parseLayerPolicy("lazy:3"));
  EXPECT_EQ(a.frame(4), 4u);
  EXPECT_EQ(a.frame(2), 4u);
  EXPECT_EQ(a.frame(2), 4u);
  EXPECT_EQ(a.frame(3), 4u) << "the need changed: the count starts again";
  EXPECT_EQ(a.frame(3), 4u);
  EXPECT_EQ(a.frame(3), 3u) << "three frames needing 3";
  EXPECT_EQ(a.frame(6), 6u) << "growing never waits";
  EXPECT_EQ(a.reallocations(), 3u);
}

TEST(RttaLayers, BadPoliciesAreErrorsNamingTheOption) {
  for (const char* bad : {"", "lazy", "lazy:", "lazy:0", "lazy:x", "lazy:10001", "Exact", "lazy:3 "}) {
    try {
      parseLayerPolicy(bad);
      FAIL() << "accepted '" << bad << "'";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("--layers"), std::string::npos);
    }
  }
  EXPECT_EQ(parseLayerPolicy("lazy:10000").name(), "lazy:10000");
}

}  // namespace
}  // namespace tessera::rtta
