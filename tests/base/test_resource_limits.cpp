// Resource limits: overflow-checked arithmetic and the one over-limit message.
#include <gtest/gtest.h>

#include "base/resource_limits.h"

namespace tessera {
namespace {

TEST(ResourceLimits, CheckedArithmeticReportsOverflowInsteadOfWrapping) {
  EXPECT_EQ(checkedMul(1u << 20, 1u << 20), uint64_t(1) << 40);
  EXPECT_FALSE(checkedMul(uint64_t(1) << 32, uint64_t(1) << 32).has_value());
  EXPECT_EQ(checkedMul(0, UINT64_MAX), 0u);
  EXPECT_EQ(checkedAdd(UINT64_MAX - 1, 1), UINT64_MAX);
  EXPECT_FALSE(checkedAdd(UINT64_MAX, 1).has_value());
}

TEST(ResourceLimits, BytesAreWrittenInBinaryUnitsWithOneDecimal) {
  EXPECT_EQ(formatBytes(0), "0 B");
  EXPECT_EQ(formatBytes(1023), "1023 B");
  EXPECT_EQ(formatBytes(1536), "1.5 KiB");
  EXPECT_EQ(formatBytes(4 * kGiB), "4.0 GiB");
  // 16384 x 16384 x 2048 layers x 16 bytes (RGBA32F) = 8 TiB: the fuzz campaign's render target.
  EXPECT_EQ(formatBytes(uint64_t(16384) * 16384 * 2048 * 16), "8.0 TiB");
}

TEST(ResourceLimits, TheMessageSaysWhatHowMuchTheLimitTheExcessAndTheOption) {
  EXPECT_EQ(overLimitMessage("f.tframe", "of textures, buffers and render targets", 6 * kGiB, 4 * kGiB,
                             "--memory-budget", true),
            "f.tframe: needs 6.0 GiB of textures, buffers and render targets, over the limit of 4.0 GiB by 2.0 GiB "
            "(raise it with --memory-budget)");
  EXPECT_EQ(overLimitMessage("m.gltf", "mesh instances", std::nullopt, 1000000, "", false),
            "m.gltf: needs more than 2^64 mesh instances, over the limit of 1000000");
}

}  // namespace
}  // namespace tessera
