// validate()'s frame memory budget (ResourceLimits::frameBytes): every texture level and layer and every
// buffer a frame creates, summed without overflow, refused before a backend allocates any of it.
// (The rest of validate() is tested in test_validate.cpp.)
#include <gtest/gtest.h>

#include <string>

#include "base/error.h"
#include "raster/cpu_backend.h"
#include "raster/validate.h"
#include "tests/raster/validate_test_util.h"

namespace tessera {
namespace {

using testing::dump;

ResourceLimits budget(uint64_t bytes) {
  ResourceLimits l;
  l.frameBytes = bytes;
  return l;
}

// The fuzz campaign's frame: a valid-looking layered render target of 16384 x 16384 x 2048 RGBA32F,
// cleared. One level: 16384 * 16384 texels * 16 bytes * 2048 layers = 2^14 * 2^14 * 2^4 * 2^11 = 2^43 bytes.
CommandList fuzzFrame() {
  CommandList l;
  const ResourceId target = l.createTexture({TextureKind::Tex2DArray, Format::RGBA32F, 16384, 16384, 2048, 1});
  RenderTarget t;
  t.color[0] = target;
  t.layer = kLayered;
  l.setRenderTarget(t);
  l.clearColor(0, {0, 0, 0, 1});
  return l;
}

TEST(Validate, ALayered16384x16384x2048Rgba32fTargetIsOverTheFrameBudget) {
  const CommandList l = fuzzFrame();
  const auto diags = validate(l);
  ASSERT_EQ(diags.size(), 1u) << dump(diags);
  EXPECT_EQ(diags[0].command, 0u);
  // 2^43 - 2^32 bytes over = 8191.99.. GiB, which one decimal writes as 8.0 TiB.
  EXPECT_EQ(diags[0].message,
            "frame: needs 8.0 TiB of textures, buffers and render targets, over the limit of 4.0 GiB by 8.0 TiB "
            "(raise it with --memory-budget)");
  try {
    validateOrThrow(l, "fuzz.tframe");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("fuzz.tframe: 1 problem", 0), 0u) << m;
    EXPECT_NE(m.find("command 0 (CreateTexture): frame: needs 8.0 TiB"), std::string::npos) << m;
  }
  // Nothing else is wrong with it: a budget of exactly 2^43 bytes lets it through.
  EXPECT_TRUE(validate(l, budget(uint64_t(1) << 43)).empty());
}

TEST(Validate, TheCpuBackendRefusesAnOverBudgetFrameBeforeAllocatingIt) {
  // Allocating 8 TiB would throw std::bad_alloc (or be killed), not Error.
  CpuBackend backend;
  EXPECT_THROW(backend.execute(fuzzFrame(), "fuzz.tframe"), Error);
  // The budget the backend checks is the one in its options.
  CpuBackend small(RenderOptions{1, false, budget(1023)});
  CommandList l;
  l.createTexture({TextureKind::Tex2D, Format::RGBA8, 16, 16, 1, 1});  // 16 * 16 * 4 = 1024 bytes
  EXPECT_THROW(small.execute(l, "small"), Error);
  CpuBackend enough(RenderOptions{1, false, budget(1024)});
  EXPECT_NO_THROW(enough.execute(l, "small"));
}

// Worked out by hand:
//   command 0: 4x4 RGBA8, 3 levels: 4*4*4 + 2*2*4 + 1*1*4 = 64 + 16 + 4 = 84 bytes        total  84
//   command 1: 2x2 RGBA32F array, 3 layers, 2 levels: (2*2*16 + 1*1*16) * 3 = 80 * 3 = 240  total 324
//   command 2: a 100-byte texel buffer                                                      total 424
//   command 3: a Buffer texture over it: no storage of its own                              total 424
CommandList budgetFrame() {
  CommandList l;
  l.createTexture({TextureKind::Tex2D, Format::RGBA8, 4, 4, 1, 3});
  l.createTexture({TextureKind::Tex2DArray, Format::RGBA32F, 2, 2, 3, 2});
  const ResourceId buffer = l.createBuffer(BufferKind::Texel, 100);
  l.createTexture({TextureKind::Buffer, Format::RGBA8, 25, 1, 1, 1, buffer});
  return l;
}

TEST(Validate, AFrameExactlyAtTheBudgetPasses) {
  const auto diags = validate(budgetFrame(), budget(424));
  EXPECT_TRUE(diags.empty()) << dump(diags);
}

TEST(Validate, AFrameOneByteOverTheBudgetFailsAtTheCommandThatCrossesIt) {
  auto diags = validate(budgetFrame(), budget(423));
  ASSERT_EQ(diags.size(), 1u) << dump(diags);
  EXPECT_EQ(diags[0].command, 2u);
  EXPECT_EQ(diags[0].message,
            "frame: needs 424 B of textures, buffers and render targets, over the limit of 423 B by 1 B "
            "(raise it with --memory-budget)");
  // The command is the first that crosses; the need is the whole frame's.
  diags = validate(budgetFrame(), budget(323));
  ASSERT_EQ(diags.size(), 1u) << dump(diags);
  EXPECT_EQ(diags[0].command, 1u);
  EXPECT_EQ(diags[0].message,
            "frame: needs 424 B of textures, buffers and render targets, over the limit of 323 B by 101 B "
            "(raise it with --memory-budget)");
}

TEST(Validate, TheBudgetDiagnosticKeepsCommandOrderAmongTheOthers) {
  CommandList l = budgetFrame();  // 424 bytes
  l.bindTexture(99, 1);           // command 4: unit out of range
  l.bindTexture(0, 77);           // command 5: no such texture
  const auto diags = validate(l, budget(100));
  ASSERT_EQ(diags.size(), 3u) << dump(diags);
  EXPECT_EQ(diags[0].command, 1u) << dump(diags);
  EXPECT_NE(diags[0].message.find("over the limit of 100 B by 324 B"), std::string::npos) << dump(diags);
  EXPECT_EQ(diags[1].command, 4u) << dump(diags);
  EXPECT_EQ(diags[2].command, 5u) << dump(diags);
}

TEST(Validate, TwoBuffersWhoseSizesSumPast2To64AreOverTheBudgetInsteadOfWrappingUnderIt) {
  // 2^63 + 2^63 = 2^64 wraps to 0 in 64-bit arithmetic, which would pass any budget.
  CommandList l;
  l.createBuffer(BufferKind::Vertex, uint64_t(1) << 63);
  l.createBuffer(BufferKind::Vertex, uint64_t(1) << 63);
  const std::string overflow =
      "frame: needs more than 16.0 EiB of textures, buffers and render targets, over the limit of 16.0 EiB "
      "(raise it with --memory-budget)";
  // With the largest budget, the first buffer fits and the sum is what crosses it.
  auto diags = validate(l, budget(UINT64_MAX));
  bool found = false;
  for (const Diagnostic& d : diags) {
    // Each buffer is also over the per-buffer limit; that diagnostic is another one.
    if (d.message.find("frame: ") != 0) continue;
    EXPECT_EQ(d.command, 1u) << dump(diags);
    EXPECT_EQ(d.message, overflow) << dump(diags);
    found = true;
  }
  EXPECT_TRUE(found) << dump(diags);
  // With the default budget the first buffer already crosses it, and the need is still "more than 16 EiB".
  diags = validate(l);
  found = false;
  for (const Diagnostic& d : diags) {
    if (d.message.find("frame: ") != 0) continue;
    EXPECT_EQ(d.command, 0u) << dump(diags);
    EXPECT_EQ(d.message,
              "frame: needs more than 16.0 EiB of textures, buffers and render targets, over the limit of 4.0 GiB "
              "(raise it with --memory-budget)")
        << dump(diags);
    found = true;
  }
  EXPECT_TRUE(found) << dump(diags);
}

}  // namespace
}  // namespace tessera
