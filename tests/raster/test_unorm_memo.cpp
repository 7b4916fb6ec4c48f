// The colour write's memo of its last unorm8 conversion (raster/rast.h, RastScratch::UnormMemo): a
// hit must give the bytes a conversion would, so every value of the 16 must take part in the
// comparison, bit for bit. Near misses: each value replaced by its neighbouring float (chosen at a
// rounding tie, so the bytes differ), by -0 for +0 and by another NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "raster/fragops.h"
#include "raster/fragops_simd.h"
#include "raster/rast.h"

namespace tessera::detail {
namespace {

int g_calls = 0;
void countingUnorm8(const float* in, uint8_t* out) {
  ++g_calls;
  for (int i = 0; i < 16; ++i) out[i] = toUnorm8(in[i]);
}

// The float nearest below the tie (k + 1/2) / 255 whose neighbour above converts to the next byte.
float belowTie(int k) {
  float f = float((k + 0.5) / 255.0);
  while (toUnorm8(f) != uint8_t(k)) f = std::nextafter(f, 0.0f);
  return f;
}

TEST(UnormMemo, AHitGivesTheConversionsBytesAndEveryValueTakesPartInTheComparison) {
  RastScratch::UnormMemo memo;
  float base[16];
  for (int i = 0; i < 16; ++i) base[i] = belowTie(10 * i + 3);
  uint8_t expect[16], got[16];
  countingUnorm8(base, expect);

  bool ask = true;
  g_calls = 0;
  memo.convert(&countingUnorm8, base, got, ask);  // a miss: converted and entered
  EXPECT_EQ(g_calls, 1);
  EXPECT_FALSE(ask);
  EXPECT_EQ(std::memcmp(got, expect, 16), 0);
  ask = true;
  memo.convert(&countingUnorm8, base, got, ask);  // a hit
  EXPECT_EQ(g_calls, 1);
  EXPECT_TRUE(ask);
  EXPECT_EQ(std::memcmp(got, expect, 16), 0);

  for (int i = 0; i < 16; ++i) {
    float near[16];
    std::memcpy(near, base, sizeof near);
    near[i] = std::nextafter(base[i], 1.0f);  // across the tie: one byte more
    uint8_t nearExpect[16];
    countingUnorm8(near, nearExpect);
    ASSERT_NE(nearExpect[i], expect[i]) << i;
    memo.convert(&countingUnorm8, base, got, ask);  // the memo holds base again
    ask = true;
    const int before = g_calls;
    memo.convert(&countingUnorm8, near, got, ask);
    EXPECT_EQ(g_calls, before + 1) << "value " << i << " was not compared";
    EXPECT_FALSE(ask) << i;
    EXPECT_EQ(std::memcmp(got, nearExpect, 16), 0) << i;
  }
}

TEST(UnormMemo, ComparesBitsNotValues) {
  RastScratch::UnormMemo memo;  // holds sixteen +0 values: the initial state is an entry
  float zeros[16] = {};
  uint8_t got[16];
  bool ask = true;
  g_calls = 0;
  memo.convert(&countingUnorm8, zeros, got, ask);
  EXPECT_EQ(g_calls, 0);  // a hit on the initial entry
  for (int i = 0; i < 16; ++i) EXPECT_EQ(got[i], 0) << i;
  float negZero[16] = {};
  negZero[5] = -0.0f;  // equal as a value, different bits
  memo.convert(&countingUnorm8, negZero, got, ask);
  EXPECT_EQ(g_calls, 1);
  float nan[16] = {};
  nan[9] = std::numeric_limits<float>::quiet_NaN();
  memo.convert(&countingUnorm8, nan, got, ask);
  memo.convert(&countingUnorm8, nan, got, ask);  // the same NaN bits: a hit
  EXPECT_EQ(g_calls, 2);
  uint32_t bits;
  std::memcpy(&bits, &nan[9], sizeof bits);
  bits ^= 1;  // another NaN
  std::memcpy(&nan[9], &bits, sizeof bits);
  memo.convert(&countingUnorm8, nan, got, ask);
  EXPECT_EQ(g_calls, 3);
}

}  // namespace
}  // namespace tessera::detail
