// The sampler's plan cache (sample.h, detail::beginPlanCache) is speed only: with it open, every
// implicit-LOD quad lookup gives the bits it gives with it closed, whether the quads repeat rho^2 (the
// cache hits), change it a little (lambda repeats: the plan is reused) or a lot, or alternate between
// units; and a new epoch forgets a unit whose sampler changed in place (the same TexUnit address with
// other contents, as a reused draw state would be). sampleQuads2D, which samples a program's batch in
// runs of quads that share everything but the level weights, gives every quad its own lookup's bits.
#include <gtest/gtest.h>

#include <array>
#include <algorithm>
#include <cstring>
#include <limits>
#include <string>
#include <random>
#include <vector>

#include "raster/sample.h"
#include "raster/simd_targets.h"
#include "tests/raster/render_helpers.h"

namespace tessera {
namespace {

TextureData noisyRgba8(uint32_t size) {
  TextureDesc d;
  d.kind = TextureKind::Tex2D;
  d.format = Format::RGBA8;
  d.width = d.height = size;
  d.levels = 1;
  while ((size >> d.levels) > 0) ++d.levels;
  TextureData t(d);
  std::mt19937 rng(5);
  for (auto& level : t.levels)
    for (auto& b : level) b = uint8_t(rng());
  return t;
}

TexUnit unitOf(const TextureData* t, Filter minF, Wrap wrap) {
  SamplerState s;
  s.minFilter = minF;
  s.magFilter = Filter::Linear;
  s.wrapS = s.wrapT = wrap;
  TexUnit u;
  u.tex = t;
  u.sampler = SamplerQ::from(s);
  return u;
}

struct QuadIn {
  float s[4], t[4], bias;
};

// Quads in runs that share derivatives (an affine mapping: the cache's hits), runs whose derivatives
// drift slightly (perspective: the same lambda) and runs that do not.
std::vector<QuadIn> quads() {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<float> pos(-3.0f, 3.0f), step(-0.05f, 0.05f);
  std::vector<QuadIn> qs;
  for (int run = 0; run < 200; ++run) {
    const float dx = step(rng), dy = step(rng), ex = step(rng), ey = step(rng);
    const float bias = run % 7 == 0 ? 0.5f : 0.0f;
    for (int i = 0; i < 20; ++i) {
      QuadIn q{};
      const float s0 = run % 3 == 0 ? 0.25f : pos(rng), t0 = run % 3 == 0 ? 0.5f : pos(rng);
      // Odd runs share derivatives; every fourth run changes them slightly from quad to quad, as
      // perspective does, so rho^2 changes while lambda mostly repeats (the cache's second level).
      const float ddx = run % 4 == 3 ? dx * (1.0f + 1e-4f * float(i)) : run % 2 ? dx : step(rng);
      q.s[0] = s0, q.s[1] = s0 + ddx, q.s[2] = s0 + ex, q.s[3] = s0 + ddx + ex;
      q.t[0] = t0, q.t[1] = t0 + dy, q.t[2] = t0 + ey, q.t[3] = t0 + dy + ey;
      q.bias = bias;
      qs.push_back(q);
    }
  }
  return qs;
}

std::array<uint32_t, 16> bitsOf(const float (&out)[4][4]) {
  std::array<uint32_t, 16> b{};
  std::memcpy(b.data(), out, sizeof out);
  return b;
}

TEST(PlanCache, OpenGivesTheBitsOfClosedForRepeatedAndChangingDerivativesOnTwoUnits) {
  const TextureData tex = noisyRgba8(64);
  const TexUnit a = unitOf(&tex, Filter::LinearMipmapLinear, Wrap::Repeat);
  const TexUnit b = unitOf(&tex, Filter::NearestMipmapLinear, Wrap::MirroredRepeat);
  const std::vector<QuadIn> qs = quads();
  std::vector<std::array<uint32_t, 16>> closed;
  for (size_t i = 0; i < qs.size(); ++i) {
    float out[4][4];
    sampleQuad2D(i % 5 == 4 ? b : a, qs[i].s, qs[i].t, qs[i].bias, out);
    closed.push_back(bitsOf(out));
  }
  detail::beginPlanCache();
  for (size_t i = 0; i < qs.size(); ++i) {
    float out[4][4];
    sampleQuad2D(i % 5 == 4 ? b : a, qs[i].s, qs[i].t, qs[i].bias, out);
    ASSERT_EQ(bitsOf(out), closed[i]) << "quad " << i;
  }
  detail::endPlanCache();
}

TEST(PlanCache, ANewEpochForgetsAUnitChangedInPlace) {
  const TextureData tex = noisyRgba8(32);
  TexUnit u = unitOf(&tex, Filter::LinearMipmapLinear, Wrap::Repeat);
  const float s[4] = {0.1f, 0.23f, 0.1f, 0.23f}, t[4] = {0.2f, 0.2f, 0.31f, 0.31f};  // lambda about 2
  float expectNearest[4][4], got[4][4];
  {
    TexUnit n = unitOf(&tex, Filter::NearestMipmapNearest, Wrap::ClampToEdge);
    sampleQuad2D(n, s, t, 0.0f, expectNearest);
  }
  detail::beginPlanCache();
  sampleQuad2D(u, s, t, 0.0f, got);  // caches the trilinear plan of u
  u = unitOf(&tex, Filter::NearestMipmapNearest, Wrap::ClampToEdge);  // same address, new sampler
  detail::beginPlanCache();  // what the rasterizer does before the next triangle
  sampleQuad2D(u, s, t, 0.0f, got);
  detail::endPlanCache();
  EXPECT_EQ(bitsOf(got), bitsOf(expectNearest));
  float trilinear[4][4];
  sampleQuad2D(unitOf(&tex, Filter::LinearMipmapLinear, Wrap::Repeat), s, t, 0.0f, trilinear);
  EXPECT_NE(bitsOf(trilinear), bitsOf(expectNearest));  // the two samplers do differ here
}

TEST(PlanCache, IsClosedOutsideATile) {
  // After endPlanCache a changed unit at the same address is seen without a new epoch.
  const TextureData tex = noisyRgba8(32);
  TexUnit u = unitOf(&tex, Filter::LinearMipmapLinear, Wrap::Repeat);
  const float s[4] = {0.1f, 0.23f, 0.1f, 0.23f}, t[4] = {0.2f, 0.2f, 0.31f, 0.31f};  // lambda about 2
  float first[4][4], expect[4][4], got[4][4];
  detail::beginPlanCache();
  sampleQuad2D(u, s, t, 0.0f, first);
  detail::endPlanCache();
  u = unitOf(&tex, Filter::NearestMipmapNearest, Wrap::ClampToEdge);
  sampleQuad2D(u, s, t, 0.0f, got);
  TexUnit n = unitOf(&tex, Filter::NearestMipmapNearest, Wrap::ClampToEdge);
  sampleQuad2D(n, s, t, 0.0f, expect);
  EXPECT_EQ(bitsOf(got), bitsOf(expect));
  EXPECT_NE(bitsOf(first), bitsOf(expect));  // the two samplers do differ here
}

// Runs of quads whose derivatives grow by 4 % from quad to quad (strong perspective): lambda changes at
// every quad and crosses from one level pair to the next within a run; with a NaN and a coordinate
// beyond the kernel's range (|s w| > 2^14) here and there, which the kernel declines.
std::vector<QuadIn> perspectiveQuads() {
  std::mt19937_64 rng(33);
  std::uniform_real_distribution<float> pos(-2.0f, 2.0f), step(0.002f, 0.03f);
  std::vector<QuadIn> qs;
  for (int run = 0; run < 100; ++run) {
    const float dx = step(rng), dy = step(rng) * 0.3f;
    const float s0 = pos(rng), t0 = pos(rng);
    for (int i = 0; i < 37; ++i) {
      const float g = 1.0f + 0.04f * float(i);
      QuadIn q{};
      const float x = s0 + 0.01f * float(i);
      q.s[0] = x, q.s[1] = x + dx * g, q.s[2] = x + dy * g, q.s[3] = x + (dx + dy) * g;
      q.t[0] = t0, q.t[1] = t0 + dy * g, q.t[2] = t0 + dx * g, q.t[3] = t0 + (dx + dy) * g;
      if (run % 9 == 4 && i == 11) q.s[2] = std::numeric_limits<float>::quiet_NaN();
      if (run % 11 == 5 && i == 20) q.t[3] = 600.0f;  // 600 * 64 > 2^14
      qs.push_back(q);
    }
  }
  return qs;
}

TEST(SampleQuads, ABatchGivesEveryQuadTheBitsOfItsOwnLookupOnEveryTarget) {
  const testing::SimdTargetGuard guard;
  const TextureData tex = noisyRgba8(64);
  const TexUnit units[] = {unitOf(&tex, Filter::LinearMipmapLinear, Wrap::Repeat),
                           unitOf(&tex, Filter::LinearMipmapLinear, Wrap::ClampToEdge),
                           unitOf(&tex, Filter::LinearMipmapNearest, Wrap::MirroredRepeat)};
  std::vector<QuadIn> qs = perspectiveQuads();
  for (const QuadIn& q : quads()) qs.push_back(q);
  for (const std::string& target : simd::availableTargets()) {
    simd::forceTarget(target);
    for (const TexUnit& u : units)
      for (const float bias : {0.0f, 0.7f}) {
        // Batches of up to 64 quads, as the rasterizer's; with the plan cache open (the batched path)
        // and closed (quad by quad).
        for (const bool open : {true, false})
          for (size_t first = 0; first < qs.size(); first += 64) {
            const size_t n = std::min<size_t>(64, qs.size() - first);
            float s[64][4], t[64][4], got[64][4][4];
            for (size_t i = 0; i < n; ++i)
              for (int p = 0; p < 4; ++p) s[i][p] = qs[first + i].s[p], t[i][p] = qs[first + i].t[p];
            if (open) detail::beginPlanCache();
            sampleQuads2D(u, n, s, t, bias, got);
            if (open) detail::endPlanCache();
            for (size_t i = 0; i < n; ++i) {
              float expect[4][4];
              sampleQuad2D(u, s[i], t[i], bias, expect);  // the cache is closed: each quad alone
              ASSERT_EQ(bitsOf(got[i]), bitsOf(expect))
                  << target << ", unit " << (&u - units) << ", bias " << bias << ", quad " << first + i
                  << (open ? ", batched" : ", cache closed");
            }
          }
      }
  }
}

}  // namespace
}  // namespace tessera
