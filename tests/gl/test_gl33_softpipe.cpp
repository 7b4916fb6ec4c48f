// The GL backend's OpenGL 3.3 core path on Mesa softpipe, a rasterizer independent of llvmpipe
// (docs/gl-backend.md, "The 3.3 core path", "Drivers"): the context is what was asked for, every
// twin compiles as GLSL 3.30, and a frame in which the oracle finds no freedom is reproduced exactly
// and judged exact. Its own executable: Mesa picks the driver once per process (GALLIUM_DRIVER is
// read when the EGL display initialises), and gl_tests keeps llvmpipe.
//
// Skipped (GTEST_SKIP, with the reason) only when this Mesa has no softpipe: GALLIUM_DRIVER=softpipe
// then gives another driver, which the backend reports as "asked for softpipe, the context reports
// ...". Any other failure to create the context fails the tests.
//
// Also the GLSL 3.30 rewrite of the twins (glsl_dialect.h) on hand-written inputs, which needs no GL.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "gl/gl_backend.h"
#include "gl/glsl_dialect.h"
#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "raster/program.h"
#include "tests/crosscheck/ao_two_step.h"
#include "tests/gl/no_freedom_frame.h"
#include "verify/judge.h"

namespace tessera::gl {
namespace {

struct Shared {
  std::unique_ptr<GlBackend> gl;
  std::string error;
  bool absent = false;  // this Mesa has no softpipe
};
Shared& shared() {
  static Shared s = [] {
    Shared r;
    GlOptions o;
    o.driver = "softpipe";
    o.glVersion = 33;
    try {
      r.gl = GlBackend::create(o);
    } catch (const std::exception& e) {
      r.error = e.what();
      r.absent = r.error.find("was asked for") != std::string::npos;
    }
    return r;
  }();
  return s;
}

#define REQUIRE_SOFTPIPE()                                                                          \
  do {                                                                                              \
    if (shared().absent) GTEST_SKIP() << "Mesa softpipe is not available here: " << shared().error; \
    ASSERT_TRUE(shared().gl) << "the softpipe GL 3.3 context could not be created: " << shared().error; \
  } while (0)

GlBackend& gl() { return *shared().gl; }

TEST(Gl33Softpipe, TheContextIsSoftpipeOnTheOpenGl33CorePathAndReportsItsSubpixelBits) {
  REQUIRE_SOFTPIPE();
  const GlInfo& i = gl().info();
  EXPECT_EQ(i.driver, "softpipe") << i.renderer;
  EXPECT_EQ(i.requestedDriver, "softpipe");
  EXPECT_EQ(i.contextVersion, 33);
  EXPECT_EQ(i.glslDialect, "330 core");
  // GL 4.6 §14.5 (and GL 3.3 §3.5): at least 4 sub-pixel bits; softpipe has exactly GL's minimum.
  EXPECT_GE(i.limits.subpixelBits, 4);
  const auto j = i.toJson();
  EXPECT_EQ(j.at("context_version"), "3.3");
  EXPECT_EQ(j.at("driver"), "softpipe");
  EXPECT_EQ(j.at("limits").at("subpixel_bits"), i.limits.subpixelBits);
  std::printf("[ context  ] %s\n", j.dump().c_str());
}

TEST(Gl33Softpipe, EveryBuiltInProgramsTwinCompilesAndLinksAsGlsl330) {
  REQUIRE_SOFTPIPE();
  CommandList cl;
  for (std::string_view name : programNames()) cl.createProgram(name);
  EXPECT_NO_THROW(gl().execute(cl, "programs"));
}

TEST(Gl33Softpipe, AFrameInWhichTheOracleFindsNoFreedomIsReproducedExactlyAndJudgedExact) {
  REQUIRE_SOFTPIPE();
  const NoFreedomOracle o;
  ASSERT_EQ(o.classed, 0u) << "the oracle finds a freedom in a frame built to have none";

  gl().execute(noFreedomFrame(), "no freedom");
  const auto images = gl().presented();
  ASSERT_EQ(images.size(), 1u);
  const auto px = gl().readImage(images[0]);
  ASSERT_EQ(px.size(), o.pixels.size());
  const verify::Judgement j = verify::judge(*o.tex, o.presented.level, o.presented.layer, px);
  EXPECT_EQ(j.pixels, 32u * 32u);
  EXPECT_EQ(j.exact, j.pixels) << "softpipe differs from the oracle where GL allows one value";
  EXPECT_EQ(px, o.pixels);
  // Spot values worked out from the frame (as in gl_tests): the clear, flat red, flat green, a texel.
  auto at = [&](int x, int y) { return noFreedomPixel(px, x, y); };
  EXPECT_EQ(at(0, 0), (std::vector<uint8_t>{51, 102, 153, 255}));
  EXPECT_EQ(at(2, 2), (std::vector<uint8_t>{255, 0, 0, 255}));
  EXPECT_EQ(at(29, 11), (std::vector<uint8_t>{0, 255, 0, 255}));
  EXPECT_EQ(at(21, 23), (std::vector<uint8_t>{50, 120, 170, 255}));
}

// ghosted-ao's two-step judgement (tests/crosscheck/ao_two_step.h) on a second, independent GL
// implementation: softpipe must also compute atlas_sprite_ao's floats over its own capture.
TEST(Gl33Softpipe, GhostedAoOverItsOwnCaptureDiffersFromTheOracleOnlyByOutputRounding) {
  REQUIRE_SOFTPIPE();
  static const verify::ExpectationSet e =
      verify::loadExpectations(std::string(TESSERA_SOURCE_DIR) + "/tests/expectations/gl-deviations.json");
  tessera::testing::judgeGhostedAoOnItsOwnCapture(gl(), "softpipe", &e);
}

TEST(Gl33Softpipe, ASecondBackendAskingForAnotherDriverIsAnErrorNamingBoth) {
  REQUIRE_SOFTPIPE();
  // The display of this process runs softpipe; llvmpipe cannot be had any more.
  GlOptions o;
  o.driver = "llvmpipe";
  try {
    GlBackend::create(o);
    FAIL() << "a backend asking for llvmpipe was created on softpipe's display";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("llvmpipe was asked for"), std::string::npos) << m;
    EXPECT_NE(m.find("(driver softpipe)"), std::string::npos) << m;
  }
}

// The rewrite itself: what GLSL 3.30 lacks, line for line.
const char* const kTwin =
    "#version 450 core\n"
    "layout(location = 0) uniform vec4 u[64];\n"
    "#ifdef TESSERA_VERTEX_SHADER\n"
    "layout(location = 1) in vec4 a_texcoord;\n"
    "out gl_PerVertex {\n"
    "  vec4 gl_Position;\n"
    "  float gl_ClipDistance[8];\n"
    "};\n"
    "layout(location = 0) flat out uint v_id;\n"
    "void main() {\n"
    "  const float s = a_texcoord.x;\n"
    "  precise float t = s * 2.0;\n"
    "}\n"
    "#endif\n"
    "#ifdef TESSERA_FRAGMENT_SHADER\n"
    "layout(binding = 3) uniform sampler2DArray TA2;  // unit 3\n"
    "layout(location = 0) flat in uint v_id;\n"
    "layout(location = 1) out uvec4 o_id;\n"
    "void main() { vec2 d = dFdxCoarse(vec2(1.0)); }\n"
    "#endif";

TEST(GlslDialect, The450DialectLeavesTheTwinUntouched) {
  const RewrittenTwin r = rewriteTwin("t.glsl", kTwin, GlslDialect{});
  EXPECT_EQ(r.text, kTwin);
  EXPECT_TRUE(r.samplerUnits.empty());
}

TEST(GlslDialect, The330RewriteKeepsEveryLineInPlaceAndReplacesWhatGlsl330Lacks) {
  GlslDialect d;
  d.core450 = false;  // no extension at all: every fallback
  const RewrittenTwin r = rewriteTwin("t.glsl", kTwin, d);
  const std::string expected =
      "#version 330 core\n"
      "uniform vec4 u[64];\n"
      "#ifdef TESSERA_VERTEX_SHADER\n"
      "layout(location = 1) in vec4 a_texcoord;\n"  // vertex inputs keep their locations
      "\n"
      "\n"
      "\n"
      "out float gl_ClipDistance[8]; \n"  // the block's members but gl_Position, on its last line
      "flat out uint v_id;\n"             // varyings are matched by name
      "void main() {\n"
      "  float s = a_texcoord.x;\n"
      "  float t = s * 2.0;\n"
      "}\n"
      "#endif\n"
      "#ifdef TESSERA_FRAGMENT_SHADER\n"
      "uniform sampler2DArray TA2;  // unit 3\n"
      "flat in uint v_id;\n"
      "layout(location = 1) out uvec4 o_id;\n"  // fragment outputs keep theirs
      "void main() { vec2 d = dFdx(vec2(1.0)); }\n"
      "#endif";
  EXPECT_EQ(r.text, expected);
  ASSERT_EQ(r.samplerUnits.size(), 1u);
  EXPECT_EQ(r.samplerUnits[0].first, "TA2");
  EXPECT_EQ(r.samplerUnits[0].second, 3);
  EXPECT_EQ(d.fallbacks().size(), 3u);
}

TEST(GlslDialect, ExtensionsTheContextReportsKeepPreciseCoarseDerivativesAndConstLocals) {
  GlslDialect d;
  d.core450 = false;
  d.gpuShader5 = d.derivativeControl = d.languagePack420 = true;
  const RewrittenTwin r = rewriteTwin("t.glsl", kTwin, d);
  EXPECT_EQ(r.text.rfind("#version 330 core\n#extension GL_ARB_gpu_shader5 : require\n"
                         "#extension GL_ARB_derivative_control : require\n"
                         "#extension GL_ARB_shading_language_420pack : require\nuniform vec4 u[64];\n",
                         0),
            0u)
      << r.text;
  EXPECT_NE(r.text.find("  const float s = a_texcoord.x;\n  precise float t"), std::string::npos) << r.text;
  EXPECT_NE(r.text.find("dFdxCoarse"), std::string::npos);
}

TEST(GlslDialect, DoubleWithoutGpuShaderFp64IsAnErrorNamingTheFile) {
  GlslDialect d;
  d.core450 = false;
  try {
    rewriteTwin("raster/programs/x.glsl", "#version 450 core\nvoid main() { double z = 0.5lf; }\n", d);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("raster/programs/x.glsl"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("GL_ARB_gpu_shader_fp64"), std::string::npos) << e.what();
  }
}

TEST(GlInfo, TheDriverIsTheFirstWordOfGlRenderer) {
  EXPECT_EQ(parseDriver("llvmpipe (LLVM 15.0.6, 256 bits)"), "llvmpipe");
  EXPECT_EQ(parseDriver("softpipe"), "softpipe");
  EXPECT_EQ(parseDriver("zink (lavapipe (LLVM 15.0.6, 256 bits))"), "zink");
  EXPECT_EQ(parseDriver(""), "");
}

}  // namespace
}  // namespace tessera::gl
