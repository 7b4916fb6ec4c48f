// Test helper: ghosted-ao judged in two steps on one GL implementation (docs/rtta.md "ghosted-ao").
// atlas_sprite_ao's occlusion and edges are not monotone in the depth they read, so the in-frame
// cross-check gives its fragments the whole range wherever the captured depth carries an interval.
// Step 1 judges the capture alone by the intervals; step 2 reads GL's atlas back, uploads it to both
// renderers (RttaOptions::atlasInput) and cross-checks the composite over it, where every texel is exact:
// (a) with every object drawn by atlas_sprite_ao, only the 8-bit conversion of values within float
// rounding of a half may differ (OUTPUT_ROUNDING, at most 1); (b) the scene's own composite has no
// unexplained pixel. Used by crosscheck_tests (llvmpipe) and gl33_tests (softpipe).
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <vector>

#include "tools/scenes/rtta_five.h"
#include "verify/crosscheck.h"

namespace tessera::testing {

// Top-row-first image rows (crosscheck's layout) to GL's bottom-row-first upload order.
inline std::vector<uint8_t> bottomUp(const std::vector<uint8_t>& topDown, size_t rowBytes) {
  std::vector<uint8_t> out(topDown.size());
  const size_t rows = topDown.size() / rowBytes;
  for (size_t r = 0; r < rows; ++r) std::memcpy(&out[r * rowBytes], &topDown[(rows - 1 - r) * rowBytes], rowBytes);
  return out;
}

inline void judgeGhostedAoOnItsOwnCapture(gl::GlBackend& glb, const char* driver,
                                          const verify::ExpectationSet* expectations) {
  constexpr int kSize = 160;
  // Step 1: the capture alone, judged by the intervals (its atlas colour and depth are presented).
  const rtta::RttaFrame capture = scenes::recordFive(kSize, kSize, rtta::Composite::GhostedAo, true, nullptr);
  verify::CrosscheckOptions o;
  o.threads = 2;
  o.expectations = expectations;
  const verify::CrosscheckResult c = verify::crosscheck(capture.list, "rtta_five_ao_capture", o, &glb);
  ASSERT_TRUE(c.passed) << c.json.dump(1).substr(0, 3000);
  // Step 2: GL's atlas, uploaded, under the composite; the post-process reads only exact texels now.
  rtta::AtlasImages gl;
  const uint32_t w = uint32_t(capture.atlas.width), h = uint32_t(capture.atlas.height);
  for (const verify::ImageVerdict& v : c.images) {
    if (v.image.texture == capture.captureColor) gl.color.push_back(bottomUp(v.other, size_t(w) * 4));
    if (v.image.texture == capture.captureDepth) gl.depth.push_back(bottomUp(v.other, size_t(w) * 8));
  }
  ASSERT_EQ(gl.color.size(), capture.allocatedLayers);
  ASSERT_EQ(gl.depth.size(), capture.allocatedLayers);
  ASSERT_EQ(gl.color[0].size(), size_t(w) * h * 4);
  // 2a: every object drawn by atlas_sprite_ao (no translucent sprite over them): the composite is a
  // function of exact texels only, so GL must produce the oracle's bytes on every pixel.
  const std::vector<uint32_t> all{0, 1, 2, 3, 4};
  const rtta::RttaFrame allAo = scenes::recordFive(kSize, kSize, rtta::Composite::GhostedAo, false, &gl, &all);
  ASSERT_EQ(allAo.important, all);
  const verify::CrosscheckResult a = verify::crosscheck(allAo.list, "rtta_five_ao_all_on_gl_atlas", o, &glb);
  EXPECT_TRUE(a.passed);
  EXPECT_EQ(a.json["unexplained"].get<uint64_t>(), 0u);
  // GL computes the oracle's floats; only their conversion to 8 bits is free where a value lies within
  // float rounding of a half (GL 4.6 §2.3.5.2 allows either neighbour; e.g. factor 1/2 times an odd
  // texel): OUTPUT_ROUNDING, at most 1 apart. Every other pixel is the oracle's byte.
  for (const auto& img : a.json["images"])
    for (const auto& [cls, v] : img["per_class"].items()) {
      const uint64_t n = v["explained_differences"].get<uint64_t>();
      if (n) std::printf("[ ghosted-ao %s ] all objects with occlusion, %s: %llu differences\n", driver, cls.c_str(),
                         static_cast<unsigned long long>(n));
      if (cls != "OUTPUT_ROUNDING") {
        EXPECT_EQ(n, 0u) << cls;
      }
    }
  for (const auto& img : a.json["images"])
    for (const auto& d : img["max_abs_diff"]) EXPECT_LE(d.get<double>(), 1.0);
  // 2b: the scene's composite (the caliper with occlusion, the rest translucent over it).
  const rtta::RttaFrame composite = scenes::recordFive(kSize, kSize, rtta::Composite::GhostedAo, false, &gl);
  const verify::CrosscheckResult r = verify::crosscheck(composite.list, "rtta_five_ao_on_gl_atlas", o, &glb);
  EXPECT_TRUE(r.passed);
  EXPECT_TRUE(r.json["counters"]["equal"].get<bool>());
  EXPECT_EQ(r.json["unexplained"].get<uint64_t>(), 0u) << r.json.dump(1).substr(0, 3000);
  // Its differences are classed by the translucent sprites drawn over the caliper (blending, the
  // diagonal a sprite's two triangles share through pixel centres, ...): printed, not restricted.
  for (const auto& img : r.json["images"])
    for (const auto& [cls, v] : img["per_class"].items())
      if (const uint64_t n = v["explained_differences"].get<uint64_t>())
        std::printf("[ ghosted-ao %s ] %s: %llu differences\n", driver, cls.c_str(), static_cast<unsigned long long>(n));
  std::printf("[ ghosted-ao %s ] capture exact %.3f%%; over GL's atlas: all objects with occlusion exact %.3f%%, the "
              "scene's composite exact %.3f%%, unexplained %llu\n", driver,
              c.json["exact_match_percent"].get<double>(), a.json["exact_match_percent"].get<double>(),
              r.json["exact_match_percent"].get<double>(),
              static_cast<unsigned long long>(r.json["unexplained"].get<uint64_t>()));
}

}  // namespace tessera::testing
