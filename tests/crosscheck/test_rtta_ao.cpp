// ghosted-ao judged in two steps on llvmpipe (tests/crosscheck/ao_two_step.h, docs/rtta.md "ghosted-ao").
#include <gtest/gtest.h>

#include <memory>

#include "tests/crosscheck/ao_two_step.h"

namespace tessera {

TEST(RttaGhostedAo, TheOcclusionAndEdgesOverGLsOwnCaptureDifferOnlyByOutputRounding) {
  static std::unique_ptr<gl::GlBackend> b = gl::GlBackend::create({});
  tessera::testing::judgeGhostedAoOnItsOwnCapture(*b, "llvmpipe", nullptr);
}

}  // namespace tessera
