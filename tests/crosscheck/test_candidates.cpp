// The candidate-set judgement (docs/crosscheck.md, "Candidate sets"): a pixel where a discrete freedom
// forks the result accepts each whole result, never the values between them; a shared edge accepts
// neither a gap nor a double hit; an id image accepts exactly the candidate ids; a pixel without a
// class must match whatever its interval says. Each test edits the oracle's own image at pixels whose
// legal values follow from the scene's construction, and checks the verdict.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>

#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "tests/crosscheck/find_pixels.h"
#include "tests/crosscheck/provenance_render.h"
#include "tools/scenes/scene_common.h"
#include "tools/scenes/scenes.h"
#include "verify/judge.h"

namespace tessera {

namespace {
ProvenanceRender renderScene(const char* name, uint32_t image = 0) {
  const scenes::SceneInfo* s = scenes::find(name);
  return renderWithProvenance(scenes::build(s->name, s->width, s->height), image);
}

verify::Judgement judgeOf(const ProvenanceRender& r, const std::vector<uint8_t>& other) {
  return verify::judge(*r.tex, r.img.level, r.img.layer, other);
}

// Provenance storage index of top-down pixel i (rows are stored bottom first).
size_t storeIndex(const ProvenanceRender& r, size_t i) { return (r.h - 1 - i / r.w) * r.w + i % r.w; }
uint16_t classesOf(const ProvenanceRender& r, size_t i) { return r.tex->prov->classes[r.img.level][storeIndex(r, i)]; }

using tessera::testing::findPixels;

// One white triangle (flat_color) over black, 64 x 64. Its vertices sit on pixel centres and its
// edges run along (2, 1), (-5, 3) and (-3, -29), so they pass exactly through 28, 10 and 2 centres.
CommandList whiteTriangle() {
  CommandList cl;
  scenes::beginFrame(cl, 64, 64, false, {0, 0, 0, 1});
  scenes::Mesh m;
  m.triangle({{4.5f, 3.5f, 0}, {0, 0, 0, 0}, 0}, {{60.5f, 31.5f, 0}, {0, 0, 0, 0}, 0},
             {{10.5f, 61.5f, 0}, {0, 0, 0, 0}, 0});
  const uint32_t n = scenes::bindMesh(cl, m);
  cl.useProgram(cl.createProgram("flat_color"));
  scenes::setMatrix(cl, 0, scenes::ortho(0, 64, 0, 64, -1, 1));
  scenes::setVec4(cl, 4, {1, 1, 1, 1});
  cl.drawIndexed(0, n);
  return cl;
}

// A 16 x 16 frame filled by one "textured" quad over a 16 x 16 texture with 5 levels: level 0 flat black,
// level 1 flat white, the others grey; NEAREST_MIPMAP_NEAREST, mag NEAREST. s runs from 0 to 2^0.47
// across the quad and t is constant, so every legal rho is |du/dx| = 2^0.47 texels per pixel and lambda =
// 0.47: the oracle takes level 0 (lambda <= 1/2), and with the 1/16 LOD tolerance GL may take level 1.
CommandList twoLevelFrame() {
  CommandList cl;
  scenes::beginFrame(cl, 16, 16, false, {0, 0, 0, 1});
  TextureDesc d;
  d.width = d.height = 16;
  d.levels = 5;
  const ResourceId tex = cl.createTexture(d);
  for (uint32_t l = 0; l < d.levels; ++l) {
    const uint8_t v = l == 0 ? 0 : (l == 1 ? 255 : 100);
    const uint32_t size = 16u >> l;
    cl.uploadTexture(tex, l, 0, scenes::checker(size, size, size, {v, v, v, 255}, {v, v, v, 255}).rgba);
  }
  scenes::Mesh m;
  const float r = 1.385109f;  // 2^0.47
  m.quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0, 0.5f, 0, 0}, {r, 0.5f, 0, 0}, {r, 0.5f, 0, 0},
         {0, 0.5f, 0, 0});
  const uint32_t n = scenes::bindMesh(cl, m);
  cl.useProgram(cl.createProgram("textured"));
  scenes::setMatrix(cl, 0, glm::mat4(1.0f));
  scenes::setTexturedDefaults(cl);
  cl.bindTexture(0, tex);
  SamplerState s;
  s.minFilter = Filter::NearestMipmapNearest;
  s.magFilter = Filter::Nearest;
  cl.bindSampler(0, cl.createSampler(s));
  cl.drawIndexed(0, n);
  return cl;
}
}  // namespace

TEST(Candidates, ADifferingPixelWithoutAClassIsUnexplainedEvenInsideAWideInterval) {
  ProvenanceRender r = renderScene("depth");
  const auto u = findPixels(
      r.w * r.h, 1, [&](size_t i) { return classesOf(r, i) == 0 && r.pixels[i * 4] > 0 && r.pixels[i * 4] < 255; });
  ASSERT_EQ(u.size(), 1u) << "the depth scene has unclassed pixels with a red byte inside 0..255";
  // Widen the stored interval of that pixel to everything; its class stays empty.
  const size_t si = storeIndex(r, u[0]);
  const uint32_t x = uint32_t(si % r.w), y = uint32_t(si / r.w);
  for (int c = 0; c < 4; ++c) {
    r.tex->prov->lo->texel(r.img.level, r.img.layer, x, y)[c] = 0;
    r.tex->prov->hi->texel(r.img.level, r.img.layer, x, y)[c] = 255;
  }
  auto other = r.pixels;
  other[u[0] * 4] = uint8_t(other[u[0] * 4] + 1);
  const verify::Judgement j = judgeOf(r, other);
  EXPECT_EQ(j.unexplained, 1u);
  EXPECT_EQ(j.failMap[u[0]], 2);
}

TEST(Candidates, AnEdgePixelOfAWhiteTriangleOnBlackAcceptsBlackOrWhiteButNoGrey) {
  const ProvenanceRender r = renderWithProvenance(whiteTriangle());
  const auto edge = findPixels(r.w * r.h, 64, [&](size_t i) { return (classesOf(r, i) & kEdgeTie) != 0; });
  ASSERT_GE(edge.size(), 8u) << "the triangle's edges must pass near pixel centres";
  for (size_t i : edge) {
    ASSERT_TRUE(r.pixels[i * 4] == 0 || r.pixels[i * 4] == 255) << "pixel " << i;
    for (uint8_t v : {uint8_t(0), uint8_t(255), uint8_t(128), uint8_t(1), uint8_t(254)}) {
      auto other = r.pixels;
      for (int c = 0; c < 3; ++c) other[i * 4 + c] = v;
      const verify::Judgement j = judgeOf(r, other);
      const bool legal = v == 0 || v == 255;
      EXPECT_EQ(j.unexplained, legal ? 0u : 1u) << "pixel " << i << " value " << int(v);
    }
  }
}

// fill_fan draws fan A (edges through pixel centres) with additive blending of 64 per hit over black:
// inside the fan, a centre on an edge between two of its triangles must read exactly 64.
TEST(Candidates, ASharedEdgeAcceptsNeitherAGapNorADoubleHit) {
  const ProvenanceRender r = renderScene("fill_fan");  // 128 x 128: fan A centred at pixel (32, 64), radius 29
  size_t checked = 0;
  for (size_t i = 0; i < r.w * r.h; ++i) {
    if (!(classesOf(r, i) & kEdgeTie)) continue;
    const int x = int(i % r.w), y = int(r.h - 1 - i / r.w);  // GL window coordinates (y up)
    const int dx = std::abs(x - 32), dy = std::abs(y - 64);
    // Strictly inside the fan's square and away from its centre, where one edge at a time is near.
    if (dx > 26 || dy > 26 || (dx < 4 && dy < 4)) continue;
    ASSERT_EQ(r.pixels[i * 4], 64) << "covered once by the oracle: pixel " << i;
    for (uint8_t v : {uint8_t(0), uint8_t(128)}) {  // a gap, a double hit
      auto other = r.pixels;
      for (int c = 0; c < 3; ++c) other[i * 4 + c] = v;
      EXPECT_EQ(judgeOf(r, other).unexplained, 1u) << "pixel " << i << " value " << int(v);
    }
    ++checked;
  }
  EXPECT_GE(checked, 20u) << "fan A's edges pass through many pixel centres";
}

TEST(Candidates, AnIdImageAcceptsOnlyTheCandidateIdsNeverTheIdsBetween) {
  const ProvenanceRender r = renderScene("city_ids");
  ASSERT_EQ(r.tex->desc.format, Format::R32UI);
  auto word = [&](const std::vector<uint8_t>& v, size_t i) {
    uint32_t x;
    std::memcpy(&x, &v[i * 4], 4);
    return x;
  };
  const auto lo = imagePixels(*r.tex->prov->lo, r.img.level, r.img.layer);
  const auto hi = imagePixels(*r.tex->prov->hi, r.img.level, r.img.layer);
  // Silhouette pixels over the clear value: the hull reaches 0xffffffff from an object's id.
  const auto sil = findPixels(r.w * r.h, 10, [&](size_t i) {
    return classesOf(r, i) != 0 && word(hi, i) == 0xffffffffu && word(lo, i) + 2 < word(hi, i);
  });
  ASSERT_GE(sil.size(), 1u) << "city_ids has object silhouettes over the background";
  for (size_t i : sil) {
    const std::vector<Candidate>& set = r.tex->prov->candidates[r.img.level][storeIndex(r, i)];
    ASSERT_GE(set.size(), 2u) << "pixel " << i;
    // Every candidate is one id; any id inside the hull that no candidate names is unexplained.
    uint32_t between = word(lo, i) + 1;
    auto named = [&](uint32_t id) {
      for (const Candidate& c : set)
        if (c.lo[0] == double(id) && c.hi[0] == double(id)) return true;
      return false;
    };
    for (const Candidate& c : set) EXPECT_EQ(c.lo[0], c.hi[0]) << "pixel " << i;
    while (named(between)) ++between;
    auto other = r.pixels;
    std::memcpy(&other[i * 4], &between, 4);
    EXPECT_EQ(judgeOf(r, other).unexplained, 1u) << "pixel " << i << " id " << between;
    for (const Candidate& c : set) {
      const uint32_t id = uint32_t(c.lo[0]);
      std::memcpy(&other[i * 4], &id, 4);
      EXPECT_EQ(judgeOf(r, other).unexplained, 0u) << "pixel " << i << " candidate " << id;
    }
  }
}

TEST(Candidates, TheReportCountsClassesWidthsAndCandidateSetSizes) {
  const ProvenanceRender r = renderWithProvenance(whiteTriangle());
  const verify::Judgement j = judgeOf(r, r.pixels);
  const nlohmann::json js = verify::toJson(j);
  const nlohmann::json& edge = js["per_class"]["EDGE_TIE"];
  const uint64_t n = edge["pixels"].get<uint64_t>();
  ASSERT_GT(n, 0u);
  EXPECT_DOUBLE_EQ(edge["fraction"].get<double>(), double(n) / (64.0 * 64.0));
  // Each edge pixel's hull is black..white in r, g, b (two candidates: 0 and 255).
  EXPECT_DOUBLE_EQ(edge["max_width"][0].get<double>(), 255.0);
  EXPECT_DOUBLE_EQ(edge["mean_width"][0].get<double>(), 255.0);
  EXPECT_EQ(edge["max_candidates"].get<uint64_t>(), 2u);
  EXPECT_DOUBLE_EQ(edge["mean_candidates"].get<double>(), 2.0);
  EXPECT_EQ(edge["fallbacks"].get<uint64_t>(), 0u);
  EXPECT_EQ(js["candidate_fallbacks"].get<uint64_t>(), 0u);
}

TEST(Candidates, APixelBetweenTwoLegalLodLevelsAcceptsEitherLevelButNoValueBetweenThem) {
  const ProvenanceRender r = renderWithProvenance(twoLevelFrame());
  for (size_t i = 0; i < r.w * r.h; ++i) {
    ASSERT_EQ(r.pixels[i * 4], 0) << "the oracle takes level 0 (black): pixel " << i;
    ASSERT_NE(classesOf(r, i) & kLodNearSwitch, 0) << "pixel " << i;
    // Level 0 (0), level 1 (255), and values between that only the hull of the two would allow.
    for (uint8_t v : {uint8_t(0), uint8_t(255), uint8_t(1), uint8_t(128), uint8_t(254)}) {
      auto other = r.pixels;
      for (int c = 0; c < 3; ++c) other[i * 4 + c] = v;
      const bool legal = v == 0 || v == 255;
      EXPECT_EQ(judgeOf(r, other).unexplained, legal ? 0u : 1u) << "pixel " << i << " value " << int(v);
    }
  }
  const nlohmann::json js = verify::toJson(judgeOf(r, r.pixels));
  EXPECT_EQ(js["lookup_forked_pixels"].get<uint64_t>(), 16u * 16u);
  EXPECT_EQ(js["lookup_fallbacks"].get<uint64_t>(), 0u);
  EXPECT_GE(js["per_class"]["LOD_NEAR_SWITCH"]["max_candidates"].get<uint64_t>(), 2u);
}

TEST(Candidates, APixelWhoseLookupsFellBackToTheirHullIsCountedInTheReport) {
  // rast_provenance.cpp flags kLookupFallback where a fragment had two lookups with several candidates
  // (or a lookup with more than kMaxLookupCandidates); the report counts such pixels per image and per
  // class, as it counts kFallback.
  ProvenanceRender r = renderWithProvenance(twoLevelFrame());
  r.tex->prov->flags[r.img.level][storeIndex(r, 5)] |= kLookupFallback;
  r.tex->prov->flags[r.img.level][storeIndex(r, 9)] |= kLookupFallback;
  const nlohmann::json js = verify::toJson(judgeOf(r, r.pixels));
  EXPECT_EQ(js["lookup_fallbacks"].get<uint64_t>(), 2u);
  EXPECT_EQ(js["per_class"]["LOD_NEAR_SWITCH"]["lookup_fallbacks"].get<uint64_t>(), 2u);
  EXPECT_EQ(js["candidate_fallbacks"].get<uint64_t>(), 0u);
}

}  // namespace tessera
