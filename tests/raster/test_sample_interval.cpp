// Provenance-mode lookups (raster/sample_interval.cpp): the grid lookups (sampleBlendedGrid) against the
// one-point lookup they replace (sampleBlended); the property that lets a pass skip the inner lambdas
// of a trilinear level pair (markInteriorWeights); and that a lookup's interval still holds the
// lookup at every lambda the spec's rho bounds allow.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "raster/provenance.h"
#include "raster/sample.h"
#include "raster/sample_detail.h"
#include "tests/raster/texture_test_util.h"

namespace tessera {
namespace {

using sample_detail::kGridMax;
using sample_detail::makePlan;
using sample_detail::Plan;
using sample_detail::sampleBlended;
using sample_detail::sampleBlendedGrid;
using sample_detail::sampleQuadInterval;

// A mipmapped texture of random bytes with runs of equal texels, so that some lookups weigh only equal
// texels (mask 0) and others differing ones.
TextureData patchyTexture(Format f, uint32_t w, uint32_t h, uint32_t levels, uint32_t layers, std::mt19937& rng) {
  TextureData t(testing::desc2D(f, w, h, levels, layers));
  for (auto& level : t.levels) {
    uint8_t run = 0;
    for (size_t i = 0; i < level.size(); ++i) {
      if (rng() % 3 == 0) run = uint8_t(rng());
      level[i] = run;
    }
  }
  return t;
}

TexUnit intervalUnit(const TextureData& t, Filter minF, Filter magF, Wrap ws, Wrap wt) {
  SamplerState s;
  s.minFilter = minF;
  s.magFilter = magF;
  s.wrapS = ws;
  s.wrapT = wt;
  s.borderColor = {0.25f, 0.5f, 0.75f, 1.0f};
  TexUnit u;
  u.tex = &t;
  u.sampler = SamplerQ::from(s);
  return u;
}

// Coordinates near texel centres and edges of the level pair, beyond the texture, and NaN.
float coordinate(std::mt19937& rng, uint32_t size) {
  switch (rng() % 6) {
    case 0: return std::numeric_limits<float>::quiet_NaN();
    case 1: return float(int(rng() % 9) - 4) + float(rng() % 1000) / 1000.0f;
    case 2: return (float(rng() % (2 * size)) + 0.5f) / float(size) + float(int(rng() % 7) - 3) * 1e-3f;
    default: return float(rng() % 100000) / 100000.0f;
  }
}

bool sameBits(const float a[4], const float b[4]) { return std::memcmp(a, b, 4 * sizeof(float)) == 0; }

TEST(SampleGrid, EveryPointHasTheValueAndMaskOfItsOwnLookup) {
  std::mt19937 rng(20261205);
  const Filter mins[] = {Filter::Nearest,
                         Filter::Linear,
                         Filter::NearestMipmapNearest,
                         Filter::LinearMipmapNearest,
                         Filter::NearestMipmapLinear,
                         Filter::LinearMipmapLinear};
  const Wrap wraps[] = {Wrap::Repeat, Wrap::MirroredRepeat, Wrap::ClampToEdge, Wrap::ClampToBorder};
  const TextureData textures[] = {patchyTexture(Format::RGBA8, 13, 7, 4, 3, rng),
                                  patchyTexture(Format::R8, 16, 16, 5, 1, rng),
                                  patchyTexture(Format::RGBA8, 8, 8, 4, 1, rng)};
  int points = 0, blended = 0;
  for (const TextureData& tex : textures)
    for (Filter minF : mins)
      for (Filter magF : {Filter::Nearest, Filter::Linear})
        for (Wrap ws : wraps) {
          const TexUnit u = intervalUnit(tex, minF, magF, ws, wraps[rng() % 4]);
          for (int trial = 0; trial < 40; ++trial) {
            const int32_t lambda8 = int32_t(rng() % 1400) - 300;
            const Plan p = makePlan(u, lambda8);
            const int ns = 1 + int(rng() % kGridMax), nt = 1 + int(rng() % kGridMax);
            float s[kGridMax], t[kGridMax];
            for (int a = 0; a < ns; ++a) s[a] = coordinate(rng, tex.desc.width);
            for (int b = 0; b < nt; ++b) t[b] = coordinate(rng, tex.desc.height);
            const uint32_t layer = rng() % (tex.desc.layers + 1);  // one past the last: clamped
            float grid[kGridMax * kGridMax][4];
            uint32_t masks[kGridMax * kGridMax];
            sampleBlendedGrid(u, p, s, ns, t, nt, layer, grid, masks);
            for (int a = 0; a < ns; ++a)
              for (int b = 0; b < nt; ++b) {
                float one[4];
                const uint32_t mask = sampleBlended(u, p, s[a], t[b], layer, one);
                ASSERT_TRUE(sameBits(grid[a * nt + b], one))
                    << "lambda8 " << lambda8 << " s " << s[a] << " t " << t[b] << " layer " << layer;
                ASSERT_EQ(masks[a * nt + b], mask) << "lambda8 " << lambda8 << " s " << s[a] << " t " << t[b];
                ++points;
                blended += mask != 0;
              }
          }
        }
  // The comparison covered both kinds of mask.
  EXPECT_GT(blended, points / 10);
  EXPECT_LT(blended, points - points / 10);
}

TEST(SampleGrid, AMemoGivesEveryPlanTheGridItWouldComputeAlone) {
  // A pass's plans share level grids through the memo. Successive lookups differ in one coordinate's
  // last bit, the grid's size, the layer, the level pair's weight or the texel filter, so a memo key
  // missing any of them would hand a plan another plan's grid.
  std::mt19937 rng(11);
  const TextureData tex = patchyTexture(Format::RGBA8, 12, 10, 4, 2, rng);
  const int32_t lambdas[] = {260, 300, 380, 511, 512, 600};  // pair (1, 2) at four weights, level 2, pair (2, 3)
  sample_detail::GridMemo memo;
  memo.begin();
  for (int trial = 0; trial < 1200; ++trial) {
    const Filter minF = rng() % 2 ? Filter::LinearMipmapLinear : Filter::NearestMipmapLinear;
    const TexUnit u = intervalUnit(tex, minF, Filter::Linear, Wrap::Repeat, Wrap::ClampToBorder);
    const Plan p = makePlan(u, lambdas[rng() % 6]);
    const int ns = 2 + int(rng() % 2), nt = 2 + int(rng() % 2);
    float s[kGridMax], t[kGridMax];
    for (int a = 0; a < ns; ++a) s[a] = 0.1f * float(a + 1);
    for (int b = 0; b < nt; ++b) t[b] = 0.13f * float(b + 1);
    if (rng() % 4 == 0) s[rng() % ns] = std::nextafter(s[0], 1.0f);
    if (rng() % 4 == 0) t[rng() % nt] = std::nextafter(t[0], -1.0f);
    const uint32_t layer = rng() % 4 == 0 ? 1 : 0;
    float memoized[kGridMax * kGridMax][4], alone[kGridMax * kGridMax][4];
    uint32_t memoMasks[kGridMax * kGridMax], aloneMasks[kGridMax * kGridMax];
    sampleBlendedGrid(u, p, s, ns, t, nt, layer, memoized, memoMasks, &memo);
    sampleBlendedGrid(u, p, s, ns, t, nt, layer, alone, aloneMasks);
    for (int i = 0; i < ns * nt; ++i) {
      ASSERT_TRUE(sameBits(memoized[i], alone[i])) << "trial " << trial << " point " << i;
      ASSERT_EQ(memoMasks[i], aloneMasks[i]) << "trial " << trial << " point " << i;
    }
  }
  EXPECT_GT(memo.hits, 100u);  // the memo was used, not only filled
}

TEST(SampleGrid, AFloatTextureGridIsItsPointLookups) {
  std::mt19937 rng(7);
  TextureData tex(testing::desc2D(Format::RGBA32F, 4, 4, 3));
  for (auto& level : tex.levels)
    for (size_t i = 0; i + 4 <= level.size(); i += 4) {
      const float v = float(rng() % 1000) / 999.0f;
      std::memcpy(&level[i], &v, sizeof v);
    }
  const TexUnit u = intervalUnit(tex, Filter::LinearMipmapLinear, Filter::Linear, Wrap::Repeat, Wrap::ClampToBorder);
  const Plan p = makePlan(u, 300);
  const float s[3] = {0.1f, 0.37f, -0.6f}, t[2] = {0.9f, 0.45f};
  float grid[6][4];
  uint32_t masks[6];
  sampleBlendedGrid(u, p, s, 3, t, 2, 0, grid, masks);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 2; ++b) {
      float one[4];
      EXPECT_EQ(masks[a * 2 + b], sampleBlended(u, p, s[a], t[b], 0, one));
      EXPECT_TRUE(sameBits(grid[a * 2 + b], one));
    }
}

// What markInteriorWeights relies on: between two lambdas that blend the same level pair, every
// lambda's unorm value lies between theirs in each channel, and every lambda has the same mask.
TEST(SampleGrid, ATrilinearValueIsMonotoneInTheSecondLevelsWeightAndItsMaskDoesNotDependOnIt) {
  std::mt19937 rng(99);
  const TextureData textures[] = {patchyTexture(Format::RGBA8, 16, 8, 5, 1, rng),
                                  patchyTexture(Format::R8, 9, 9, 4, 1, rng)};
  int pairs = 0;
  for (const TextureData& tex : textures)
    for (Filter minF : {Filter::LinearMipmapLinear, Filter::NearestMipmapLinear}) {
      const TexUnit u = intervalUnit(tex, minF, Filter::Linear, Wrap::Repeat, Wrap::MirroredRepeat);
      for (int trial = 0; trial < 300; ++trial) {
        const int32_t k = int32_t(rng() % 3);
        const float s = coordinate(rng, tex.desc.width), t = coordinate(rng, tex.desc.height);
        float first[4], last[4];
        const uint32_t mask = sampleBlended(u, makePlan(u, k * 256 + 1), s, t, 0, first);
        sampleBlended(u, makePlan(u, k * 256 + 255), s, t, 0, last);
        for (int32_t f = 2; f < 255; ++f) {
          const Plan p = makePlan(u, k * 256 + f);
          ASSERT_EQ(p.levelCount, 2);
          float v[4];
          ASSERT_EQ(sampleBlended(u, p, s, t, 0, v), mask) << "f " << f;
          for (int c = 0; c < 4; ++c) {
            const float lo = std::min(first[c], last[c]), hi = std::max(first[c], last[c]);
            ASSERT_TRUE(v[c] >= lo && v[c] <= hi) << "f " << f << " channel " << c;
          }
        }
        ++pairs;
      }
    }
  EXPECT_EQ(pairs, 1200);
}

// GL 4.6 §8.14.1 eq. 8.7 lets rho be anything between max(mu, mv) and mu + mv. A LINEAR_MIPMAP_LINEAR
// lookup's interval (the hull of its candidates) must hold the lookup at every lambda in between,
// including the lambdas between the level pair's ends that a pass does not look up itself.
TEST(SampleInterval, ATrilinearIntervalHoldsTheLookupAtEveryLambdaBetweenTheRhoBounds) {
  std::mt19937 rng(5);
  const TextureData tex = patchyTexture(Format::RGBA8, 64, 64, 7, 1, rng);
  const TexUnit u = intervalUnit(tex, Filter::LinearMipmapLinear, Filter::Linear, Wrap::Repeat, Wrap::Repeat);
  ShadeProvenance& sp = shadeProvenance();
  const ShadeProvenance saved = sp;
  int lambdas = 0;
  for (int trial = 0; trial < 300; ++trial) {
    // Derivatives in base texels per pixel, 1 to 24 on each axis of x and y: lambda 0 to about 5.
    double d[4];
    for (double& v : d) v = (1.0 + double(rng() % 2300) / 100.0) * (rng() % 2 ? 1.0 : -1.0);
    const double grad[4] = {d[0] / 64, d[1] / 64, d[2] / 64, d[3] / 64};
    const float s0 = float(rng() % 4096) / 4096.0f, t0 = float(rng() % 4096) / 4096.0f;
    const float s[4] = {s0, float(s0 + grad[0]), float(s0 + grad[2]), float(s0 + grad[0] + grad[2])};
    const float t[4] = {t0, float(t0 + grad[1]), float(t0 + grad[3]), float(t0 + grad[1] + grad[3])};
    float lo[4][4], hi[4][4];
    sp.active = true;
    sp.resetPixels();
    sp.bound = SampleBound::Lo;
    sampleQuadInterval(u, s, t, nullptr, 0.0f, grad, lo);
    sp.bound = SampleBound::Hi;
    sampleQuadInterval(u, s, t, nullptr, 0.0f, grad, hi);
    sp.active = false;
    sp.bound = SampleBound::Value;
    const double mu = std::max(std::fabs(d[0]), std::fabs(d[2])), mv = std::max(std::fabs(d[1]), std::fabs(d[3]));
    // Strictly inside the bounds' lambdas: the fixed-point log2 rounds, and these must be legal.
    const int32_t from = int32_t(std::ceil(256.0 * std::log2(std::max(mu, mv)))) + 1;
    const int32_t to = int32_t(std::floor(256.0 * std::log2(mu + mv))) - 1;
    for (int32_t lambda8 = from; lambda8 <= to; ++lambda8) {
      float v[4];
      sampleAtLambda(u, s[0], t[0], 0, lambda8, v);
      for (int c = 0; c < 4; ++c)
        ASSERT_TRUE(v[c] >= lo[0][c] && v[c] <= hi[0][c])
            << "trial " << trial << " lambda8 " << lambda8 << " channel " << c << ": " << v[c] * 255 << " not in ["
            << lo[0][c] * 255 << ", " << hi[0][c] * 255 << "]";
      ++lambdas;
    }
  }
  sp = saved;
  EXPECT_GT(lambdas, 300 * 40);
}

}  // namespace
}  // namespace tessera
