// ghosted-ao judged in two steps (docs/rtta.md "ghosted-ao"): atlas_sprite_ao's occlusion and edges are
// not monotone in the depth they read, so the in-frame cross-check gives its fragments the whole range
// wherever the captured depth carries an interval. The post-process is then judged as an exact
// function of GL's own capture: GL's atlas is read back, uploaded to both renderers, and the composite
// over it must agree pixel for pixel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "tools/scenes/rtta_five.h"
#include "verify/crosscheck.h"

using namespace tessera;

namespace {
gl::GlBackend& glBackend() {
  static std::unique_ptr<gl::GlBackend> b = gl::GlBackend::create({});
  return *b;
}

// Top-row-first image rows (crosscheck's layout) to GL's bottom-row-first upload order.
std::vector<uint8_t> bottomUp(const std::vector<uint8_t>& topDown, size_t rowBytes) {
  std::vector<uint8_t> out(topDown.size());
  const size_t rows = topDown.size() / rowBytes;
  for (size_t r = 0; r < rows; ++r)
    std::memcpy(&out[r * rowBytes], &topDown[(rows - 1 - r) * rowBytes], rowBytes);
  return out;
}
}  // namespace

TEST(RttaGhostedAo, TheOcclusionAndEdgesOverGLsOwnCaptureDifferOnlyByOutputRounding) {
  constexpr int kSize = 160;
  // Step 1: the capture alone, judged by the intervals (its atlas colour and depth are presented).
  const rtta::RttaFrame capture = scenes::recordFive(kSize, kSize, rtta::Composite::GhostedAo, true, nullptr);
  verify::CrosscheckOptions o;
  o.threads = 2;
  const verify::CrosscheckResult c = verify::crosscheck(capture.list, "rtta_five_ao_capture", o, &glBackend());
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
  const verify::CrosscheckResult a = verify::crosscheck(allAo.list, "rtta_five_ao_all_on_gl_atlas", o, &glBackend());
  EXPECT_TRUE(a.passed);
  EXPECT_EQ(a.json["unexplained"].get<uint64_t>(), 0u);
  // GL computes the oracle's floats; only their conversion to 8 bits is free where a value lies within
  // float rounding of a half (GL 4.6 §2.3.5.2 allows either neighbour; e.g. factor 1/2 times an odd
  // texel): OUTPUT_ROUNDING, at most 1 apart. Every other pixel is the oracle's byte.
  for (const auto& img : a.json["images"])
    for (const auto& [cls, v] : img["per_class"].items()) {
      const uint64_t n = v["explained_differences"].get<uint64_t>();
      if (n) std::printf("[ ghosted-ao ] all objects with occlusion, %s: %llu differences\n", cls.c_str(),
                         static_cast<unsigned long long>(n));
      if (cls != "OUTPUT_ROUNDING") EXPECT_EQ(n, 0u) << cls;
    }
  for (const auto& img : a.json["images"])
    for (const auto& d : img["max_abs_diff"]) EXPECT_LE(d.get<double>(), 1.0);
  // 2b: the scene's composite (the caliper with occlusion, the rest translucent over it).
  const rtta::RttaFrame composite = scenes::recordFive(kSize, kSize, rtta::Composite::GhostedAo, false, &gl);
  const verify::CrosscheckResult r = verify::crosscheck(composite.list, "rtta_five_ao_on_gl_atlas", o, &glBackend());
  EXPECT_TRUE(r.passed);
  EXPECT_TRUE(r.json["counters"]["equal"].get<bool>());
  EXPECT_EQ(r.json["unexplained"].get<uint64_t>(), 0u) << r.json.dump(1).substr(0, 3000);
  // Every difference is classed by the translucent sprites drawn over the caliper: their blending
  // (BLEND_PRECISION, OUTPUT_ROUNDING) and the diagonal shared by a sprite's two triangles, which runs
  // through pixel centres (EDGE_TIE).
  uint64_t blendOnly = 0, other = 0;
  for (const auto& img : r.json["images"])
    for (const auto& [cls, v] : img["per_class"].items()) {
      const uint64_t n = v["explained_differences"].get<uint64_t>();
      (cls == "BLEND_PRECISION" || cls == "OUTPUT_ROUNDING" || cls == "EDGE_TIE" ? blendOnly : other) += n;
      if (n) std::printf("[ ghosted-ao ] %s: %llu differences\n", cls.c_str(), static_cast<unsigned long long>(n));
    }
  EXPECT_EQ(other, 0u);
  std::printf("[ ghosted-ao ] capture exact %.3f%%; over GL's atlas: all objects with occlusion exact %.3f%%, the "
              "scene's composite exact %.3f%%, unexplained %llu\n",
              c.json["exact_match_percent"].get<double>(), a.json["exact_match_percent"].get<double>(),
              r.json["exact_match_percent"].get<double>(),
              static_cast<unsigned long long>(r.json["unexplained"].get<uint64_t>()));
}
