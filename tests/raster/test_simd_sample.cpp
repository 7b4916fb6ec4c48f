// The sampler's SIMD kernel (raster/sample_simd.h) on every target this build compiled and this CPU
// runs, against the scalar filter it must equal ("reference": the kernel off): the same bits for
// random and adversarial quads (rounding ties of 256 u, negative and wrapped coordinates, mip blends,
// array layers, the edge of the kernel's coordinate range), the plans it must take and decline, and
// every golden image (the built-in scenes and the railway frames of the atlas tree, batching and RTTA)
// against the manifest with the kernel on each target.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "base/error.h"
#include "golden/golden_run.h"
#include "raster/sample.h"
#include "raster/sample_detail.h"
#include "raster/sample_simd.h"
#include "raster/simd_targets.h"
#include "tests/raster/render_helpers.h"
#include "tools/scenes/scene_goldens.h"

namespace tessera {
namespace {

TextureData simdTestTexture(uint32_t w, uint32_t h, uint32_t layers, uint32_t seed) {
  TextureDesc d;
  d.kind = layers > 1 ? TextureKind::Tex2DArray : TextureKind::Tex2D;
  d.format = Format::RGBA8;
  d.width = w;
  d.height = h;
  d.layers = layers;
  d.levels = 1;
  while (((w > h ? w : h) >> d.levels) > 0) ++d.levels;
  TextureData t(d);
  std::mt19937 rng(seed);
  for (auto& level : t.levels)
    for (auto& b : level) b = uint8_t(rng());
  return t;
}

TexUnit simdTestUnit(const TextureData* t, Filter minF, Filter magF, Wrap ws, Wrap wt) {
  SamplerState s;
  s.minFilter = minF;
  s.magFilter = magF;
  s.wrapS = ws;
  s.wrapT = wt;
  TexUnit u;
  u.tex = t;
  u.sampler = SamplerQ::from(s);
  return u;
}

struct SimdQuad {
  float s[4], t[4], r[4], bias;
};

// Random quads at several scales (magnified to minified), and quads whose 256 u lands exactly on a
// half (ties, to even and to odd), near the kernel's limit |u| = 2^14, and NaN / infinite ones.
std::vector<SimdQuad> simdTestQuads(float w, float h, uint32_t layers) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<float> pos(-4.0f, 4.0f), unit(0.0f, 1.0f);
  std::uniform_int_distribution<int> tie(-3000, 3000);
  std::vector<SimdQuad> qs;
  const float scales[] = {0.002f, 0.02f, 0.1f, 0.5f};
  for (int i = 0; i < 4000; ++i) {
    SimdQuad q{};
    const float step = scales[i % 4] * unit(rng);
    float s0 = pos(rng), t0 = pos(rng);
    if (i % 5 == 1) {  // 256 u = k + 1/2 exactly (w, h are powers of two in the tie cases)
      s0 = (float(tie(rng)) + 0.5f) / (256.0f * w);
      t0 = (float(tie(rng)) + 0.5f) / (256.0f * h);
    } else if (i % 5 == 2) {  // near |u| = 2^14, both sides
      s0 = (16384.0f + float(tie(rng) % 4)) / w * (i % 2 ? 1.0f : -1.0f);
    }
    const float dx = i % 5 == 1 ? 0.0f : step, dy = i % 7 == 0 ? step : 0.5f * step;
    q.s[0] = s0, q.s[1] = s0 + dx, q.s[2] = s0, q.s[3] = s0 + dx;
    q.t[0] = t0, q.t[1] = t0 + 0.25f * dx, q.t[2] = t0 + dy, q.t[3] = t0 + dy + 0.25f * dx;
    const float layer = float(i % int(layers)) + (i % 3 == 0 ? 0.4f : 0.0f);
    for (int k = 0; k < 4; ++k) q.r[k] = i % 11 == 0 ? float(k % int(layers)) : layer;  // mixed layers too
    q.bias = float(i % 9) * 0.37f - 1.0f;
    qs.push_back(q);
  }
  SimdQuad bad{};
  for (int k = 0; k < 4; ++k) bad.s[k] = bad.t[k] = 0.5f;
  bad.s[2] = std::numeric_limits<float>::quiet_NaN();
  qs.push_back(bad);
  bad.s[2] = std::numeric_limits<float>::infinity();
  qs.push_back(bad);
  return qs;
}

std::vector<std::array<uint32_t, 16>> simdTestLookups(const TexUnit& u, const std::vector<SimdQuad>& qs) {
  std::vector<std::array<uint32_t, 16>> bits;
  for (const SimdQuad& q : qs) {
    float out[4][4];
    if (u.tex->desc.layers > 1) {
      sampleQuad2DArray(u, q.s, q.t, q.r, q.bias, out);
    } else {
      sampleQuad2D(u, q.s, q.t, q.bias, out);
    }
    std::array<uint32_t, 16> b{};
    std::memcpy(b.data(), out, sizeof out);
    bits.push_back(b);
  }
  return bits;
}

struct SimdCase {
  const char* name;
  uint32_t w, h, layers;
  Filter minF, magF;
  Wrap ws, wt;
};

TEST(SimdSample, EveryTargetGivesTheReferenceBitsOnRandomAndTieQuads) {
  const testing::SimdTargetGuard guard;
  const SimdCase cases[] = {
      {"trilinear repeat 64x32", 64, 32, 1, Filter::LinearMipmapLinear, Filter::Linear, Wrap::Repeat, Wrap::Repeat},
      {"bilinear repeat 16x128", 16, 128, 1, Filter::Linear, Filter::Linear, Wrap::Repeat, Wrap::Repeat},
      {"trilinear clamp 37x23", 37, 23, 1, Filter::LinearMipmapLinear, Filter::Linear, Wrap::ClampToEdge,
       Wrap::ClampToEdge},
      {"repeat s, clamp t 32x8", 32, 8, 1, Filter::LinearMipmapNearest, Filter::Linear, Wrap::Repeat,
       Wrap::ClampToEdge},
      {"array trilinear repeat 32x32x5", 32, 32, 5, Filter::LinearMipmapLinear, Filter::Linear, Wrap::Repeat,
       Wrap::Repeat},
      // Declined by the kernel (the scalar filter runs on every target): still the same bits.
      {"repeat on 24x24", 24, 24, 1, Filter::LinearMipmapLinear, Filter::Linear, Wrap::Repeat, Wrap::Repeat},
      {"mirrored 32x32", 32, 32, 1, Filter::LinearMipmapLinear, Filter::Linear, Wrap::MirroredRepeat,
       Wrap::MirroredRepeat},
      {"border 32x32", 32, 32, 1, Filter::Linear, Filter::Linear, Wrap::ClampToBorder, Wrap::Repeat},
      {"nearest mag 32x32", 32, 32, 1, Filter::NearestMipmapNearest, Filter::Nearest, Wrap::Repeat, Wrap::Repeat},
  };
  const std::vector<std::string> targets = simd::availableTargets();
  ASSERT_GE(targets.size(), 2u) << "at least one SIMD target and the reference";
  uint32_t seed = 1;
  for (const SimdCase& c : cases) {
    const TextureData tex = simdTestTexture(c.w, c.h, c.layers, seed++);
    const TexUnit u = simdTestUnit(&tex, c.minF, c.magF, c.ws, c.wt);
    const std::vector<SimdQuad> qs = simdTestQuads(float(c.w), float(c.h), c.layers);
    simd::forceTarget("reference");
    const auto expect = simdTestLookups(u, qs);
    for (const std::string& target : targets) {
      simd::forceTarget(target);
      ASSERT_EQ(simd::activeTarget(), target);
      const auto got = simdTestLookups(u, qs);
      for (size_t i = 0; i < qs.size(); ++i)
        ASSERT_EQ(got[i], expect[i]) << c.name << ", target " << target << ", quad " << i << " s0 " << qs[i].s[0]
                                     << " t0 " << qs[i].t[0];
    }
  }
}

// The plan of a 2D lookup at lambda8 (8.8) on unit u.
sample_detail::Plan simdTestPlan(const TexUnit& u, int32_t lambda8) { return sample_detail::makePlan(u, lambda8); }

TEST(SimdSample, TheKernelTakesRepeatOnPowersOfTwoAndClampToEdgeAndDeclinesTheRest) {
  const testing::SimdTargetGuard guard;
  const TextureData pot = simdTestTexture(32, 16, 1, 3), npot = simdTestTexture(24, 20, 1, 4);
  const float s[4] = {0.1f, 0.2f, 0.3f, 0.4f}, t[4] = {0.5f, 0.6f, 0.7f, -0.8f};
  float out[4][4];
  const auto takes = [&](const TextureData& tex, Filter minF, Filter magF, Wrap ws, Wrap wt, const float* ss,
                         int32_t lambda8 = 128) {
    const TexUnit u = simdTestUnit(&tex, minF, magF, ws, wt);
    return sample_simd::sampleQuadRgba8Linear(simdTestPlan(u, lambda8), 0, ss, t, out);
  };
  const Filter tri = Filter::LinearMipmapLinear, lin = Filter::Linear;
  EXPECT_TRUE(takes(pot, tri, lin, Wrap::Repeat, Wrap::Repeat, s));
  EXPECT_TRUE(takes(pot, tri, lin, Wrap::Repeat, Wrap::Repeat, s, -256));  // magnified: one level
  EXPECT_TRUE(takes(npot, tri, lin, Wrap::ClampToEdge, Wrap::ClampToEdge, s));
  EXPECT_TRUE(takes(pot, lin, lin, Wrap::ClampToEdge, Wrap::Repeat, s));
  EXPECT_FALSE(takes(npot, tri, lin, Wrap::Repeat, Wrap::Repeat, s));  // REPEAT on 24: a modulo
  EXPECT_FALSE(takes(pot, tri, lin, Wrap::MirroredRepeat, Wrap::Repeat, s));
  EXPECT_FALSE(takes(pot, Filter::NearestMipmapLinear, lin, Wrap::Repeat, Wrap::Repeat, s));  // NEAREST
  // |s w| <= 2^14 on every level, NaN excluded: 2^14 / 32 = 512.
  const float edge[4] = {512.0f, -512.0f, 0.0f, 0.0f}, over[4] = {512.0f, 0.0f, 512.0625f, 0.0f};
  const float nan[4] = {0.0f, std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f};
  EXPECT_TRUE(takes(pot, lin, lin, Wrap::Repeat, Wrap::Repeat, edge));
  EXPECT_FALSE(takes(pot, lin, lin, Wrap::Repeat, Wrap::Repeat, over));
  EXPECT_FALSE(takes(pot, lin, lin, Wrap::Repeat, Wrap::Repeat, nan));
  simd::forceTarget("reference");
  EXPECT_FALSE(takes(pot, tri, lin, Wrap::Repeat, Wrap::Repeat, s)) << "the reference runs no kernel";
}

TEST(SimdSample, AnUnknownTargetIsAClearErrorNamingTheAvailableOnes) {
  const testing::SimdTargetGuard guard;
  try {
    simd::forceTarget("neon9");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("'neon9'"), std::string::npos) << m;
    EXPECT_NE(m.find("reference"), std::string::npos) << m;
  }
  EXPECT_EQ(simd::activeTarget(), simd::availableTargets().front()) << "the best target still runs";
}

// Every golden image, with the kernel on each target in turn (issue 13 section 4): the built-in scenes
// and the railway frames, whose SHA-256 the manifest holds.
class SimdGoldens : public ::testing::TestWithParam<std::string> {};

TEST_P(SimdGoldens, EveryGoldenImageIsReproducedBitExactly) {
  const testing::SimdTargetGuard guard;
  simd::forceTarget(GetParam());
  golden::GoldenOptions o;
  o.sceneImages = scenes::allSceneImages();
  o.dir = std::string(TESSERA_SOURCE_DIR) + "/golden";
  o.railway = std::string(TESSERA_SOURCE_DIR) + "/data/railway.glb";
  const golden::GoldenReport r = golden::checkGoldens(o);
  for (const golden::GoldenFailure& f : r.failed) ADD_FAILURE() << f.test << ": " << f.reason;
  EXPECT_TRUE(r.stale.empty());
  EXPECT_GE(r.tests, 50u);
  EXPECT_EQ(r.passed, r.tests);
}

// Under the sanitizers, the one-lane scalar target only: there each golden check takes about a minute,
// ASan's own golden tests run the best target, and the random quads above run every target already.
#if defined(__SANITIZE_ADDRESS__)
const std::vector<std::string> kGoldenTargets = {"scalar"};
#else
const std::vector<std::string> kGoldenTargets = simd::availableTargets();
#endif

INSTANTIATE_TEST_SUITE_P(EveryTarget, SimdGoldens, ::testing::ValuesIn(kGoldenTargets),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });

}  // namespace
}  // namespace tessera
