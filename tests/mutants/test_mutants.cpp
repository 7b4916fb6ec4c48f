// Mutation testing (docs/mutants.md): the catalogue of gl/gl_mutation.h is well formed, every source
// edit changes its twin, and a fast subset of `tessera mutants` shows the verdict killing mutants on
// the scenes that exercise them while the unmodified backend stays clean. The full table is the
// command, not a test (it takes minutes).
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <set>
#include <string>

#include "gl/gl_backend.h"
#include "gl/gl_mutation.h"
#include "gl/glsl_sources.h"
#include "raster/image_io.h"
#include "tools/scenes/scenes.h"
#include "verify/mutants.h"

namespace tessera {
namespace {

// One GL backend for the binary (llvmpipe reads its environment once per process). Strict mode, as
// the full table is run: the default fast path of llvmpipe has a known, machine-dependent divergence
// on wrap_filter (docs/mutants.md), and no scene here should depend on it.
gl::GlBackend& glBackend() {
  static std::unique_ptr<gl::GlBackend> b = [] {
    gl::GlOptions o;
    o.strict = true;
    return gl::GlBackend::create(o);
  }();
  return *b;
}

verify::MutantFrame frame(const std::string& name) {
  const scenes::SceneInfo* s = scenes::find(name);
  EXPECT_NE(s, nullptr) << name;
  return {name, scenes::build(name, s->width, s->height)};
}

TEST(MutationCatalogue, HoldsAtLeastTwentyNamedMutantsEachSayingWhatItImitates) {
  const auto& c = gl::mutationCatalogue();
  EXPECT_GE(c.size(), 20u);
  std::set<std::string_view> names;
  for (const gl::Mutation& m : c) {
    EXPECT_TRUE(names.insert(m.name).second) << "duplicate " << m.name;
    EXPECT_FALSE(m.imitates.empty()) << m.name;
    EXPECT_FALSE(m.change.empty()) << m.name;
    EXPECT_TRUE(m.kind == "source" || m.kind == "state") << m.name;
    // A source mutant changes a twin, a state mutant changes GL state: never neither.
    EXPECT_EQ(m.kind == "source", !m.edits.empty()) << m.name;
    EXPECT_EQ(m.kind == "state", m.state != gl::StateFault::None) << m.name;
    EXPECT_EQ(gl::findMutation(m.name), &m);
  }
  EXPECT_EQ(gl::findMutation("no_such_mutant"), nullptr);
}

TEST(MutationCatalogue, OnlyAnEquivalentMutantNamesADocumentedPin) {
  for (const gl::Mutation& m : gl::mutationCatalogue()) {
    if (m.pin.empty()) continue;
    EXPECT_FALSE(m.equivalent.empty()) << m.name << ": a pin excuses only a kill of a conforming mutant";
  }
  ASSERT_NE(gl::findMutation("unorm_truncate"), nullptr);
  EXPECT_NE(gl::findMutation("unorm_truncate")->pin.find("OUTPUT_ROUNDING"), std::string_view::npos);
}

TEST(MutantsResult, AnEquivalentMutantKilledFailsTheRunUnlessItNamesThePinThatKillsIt) {
  gl::Mutation pinned, unpinned;
  pinned.equivalent = unpinned.equivalent = "GL allows it";
  pinned.pin = "a documented choice";
  verify::MutantsResult r;
  r.falseAlarms = {0};
  verify::MutantRow row;
  row.status = "equivalent";
  row.verdictTooStrict = true;
  row.killedByPin = true;
  row.mutation = &pinned;
  r.rows = {row};
  EXPECT_TRUE(r.passed());
  r.rows[0].killedByPin = false;
  r.rows[0].mutation = &unpinned;
  EXPECT_FALSE(r.passed()) << "a verdict stricter than GL without a documented pin";
  r.rows[0].verdictTooStrict = false;
  r.falseAlarms = {1};
  EXPECT_FALSE(r.passed()) << "a false alarm of the unmodified backend";
}

TEST(MutationCatalogue, EverySourceEditChangesTheTwinItNames) {
  for (const gl::Mutation& m : gl::mutationCatalogue()) {
    std::set<std::string_view> programs;
    for (const gl::SourceEdit& e : m.edits) programs.insert(e.program);
    for (std::string_view p : programs) {
      const std::string_view text = gl::glslSource(p);
      ASSERT_FALSE(text.empty()) << m.name << ": no twin " << p;
      std::string mutated;
      ASSERT_NO_THROW(mutated = m.applyToSource(p, text)) << m.name << " on " << p;
      EXPECT_NE(mutated, text) << m.name << " leaves " << p << " unchanged";
    }
    // A twin the mutant does not name is left exactly as it is.
    const std::string_view flat = gl::glslSource("flat_color");
    if (!programs.count("flat_color")) {
      EXPECT_EQ(m.applyToSource("flat_color", flat), flat) << m.name;
    }
  }
}

TEST(MutationCatalogue, AnEditWhosePatternIsMissingIsAnErrorNotASilentSurvivor) {
  gl::Mutation m{"broken",
                 "nothing",
                 "source",
                 "replaces a string no twin contains",
                 "",
                 {{"flat_color", "this text is in no twin", "x"}},
                 gl::StateFault::None};
  EXPECT_THROW(m.applyToSource("flat_color", gl::glslSource("flat_color")), Error);
}

TEST(MutationCatalogue, StateMutantsChangeOnlyTheSamplerFieldTheyAreAbout) {
  SamplerState s;
  s.wrapS = Wrap::Repeat;
  s.wrapT = Wrap::ClampToEdge;
  s.minFilter = Filter::LinearMipmapLinear;
  s.magFilter = Filter::Nearest;
  s.lodBias = 0.5f;
  s.borderColor = {1, 0, 1, 1};
  SamplerState r = gl::findMutation("wrap_repeat_mirrored")->applyToState(s);
  EXPECT_EQ(r.wrapS, Wrap::MirroredRepeat);
  EXPECT_EQ(r.wrapT, Wrap::ClampToEdge);
  r = gl::findMutation("wrap_edge_border")->applyToState(s);
  EXPECT_EQ(r.wrapS, Wrap::Repeat);
  EXPECT_EQ(r.wrapT, Wrap::ClampToBorder);
  r = gl::findMutation("filter_nearest_linear")->applyToState(s);
  EXPECT_EQ(r.magFilter, Filter::Linear);
  EXPECT_EQ(r.minFilter, Filter::NearestMipmapLinear);
  r = gl::findMutation("mipmap_linear_as_nearest")->applyToState(s);
  EXPECT_EQ(r.minFilter, Filter::LinearMipmapNearest);
  EXPECT_EQ(gl::findMutation("sampler_lod_bias_ignored")->applyToState(s).lodBias, 0.0f);
  r = gl::findMutation("border_color_ignored")->applyToState(s);
  EXPECT_EQ(r.borderColor, (std::array<float, 4>{0, 0, 0, 0}));
  r.borderColor = s.borderColor;
  EXPECT_EQ(r, s);
  // Source mutants leave samplers alone.
  EXPECT_EQ(gl::findMutation("lod_bias_plus_1_8")->applyToState(s), s);
}

TEST(MutationCatalogue, Bc1EndpointsSwappedExchangesTheTwoEndpointsOfEveryBc1BlockAndTouchesNothingElse) {
  const gl::Mutation* m = gl::findMutation("bc1_endpoints_swapped");
  ASSERT_NE(m, nullptr);
  TextureDesc d;
  d.width = d.height = 4;
  d.compression = BcFormat::BC1;
  // Two blocks: (color0, color1, codes) = (0x0821, 0x0000, E4 00 00 00) and (0xF800, 0x001F, 55 55 55 55).
  const std::vector<uint8_t> blocks = {0x21, 0x08, 0x00, 0x00, 0xE4, 0, 0, 0, 0x00, 0xF8, 0x1F, 0x00, 0x55, 0x55, 0x55, 0x55};
  const std::vector<uint8_t> swapped = {0x00, 0x00, 0x21, 0x08, 0xE4, 0, 0, 0, 0x1F, 0x00, 0x00, 0xF8, 0x55, 0x55, 0x55, 0x55};
  EXPECT_EQ(m->applyToUpload(d, blocks), swapped);
  d.compression = BcFormat::BC3;  // BC3 and raw uploads pass unchanged (empty: no corruption)
  EXPECT_TRUE(m->applyToUpload(d, blocks).empty());
  d.compression = BcFormat::None;
  EXPECT_TRUE(m->applyToUpload(d, blocks).empty());
  d.compression = BcFormat::BC1;
  EXPECT_TRUE(gl::findMutation("border_color_ignored")->applyToUpload(d, blocks).empty());
}

// The fast subset: small scenes that each exercise one rule, and the mutants that break exactly
// that rule. Each expected killer is worked out from the scene's construction (its header comment),
// not from an earlier run: e.g. array_layers samples layers 0.7, 1.8 and 2.7, which floor(r) and
// floor(r + 1/2) put in different layers of different colours.
TEST(Mutants, EachMutantOfTheFastSubsetIsKilledByTheSceneThatExercisesItAndTheUnmodifiedBackendIsClean) {
  std::vector<verify::MutantFrame> frames;
  for (const char* s :
       {"provoking_vertex", "array_layers", "atlas_clip", "lod_levels", "blend", "depth_ties", "rtta_five_ao_post", "light_map"})
    frames.push_back(frame(s));
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"provoking_vertex_first", "provoking_vertex"},  // every triangle's three ids differ
      {"layer_floor", "array_layers"},                 // layers 0.7, 1.8, 2.7 round up
      {"clip_from_displaced", "atlas_clip"},           // x' in [-0.3, 0) survives the displaced clip
      {"lod_bias_plus_1_8", "lod_levels"},             // trilinear weights move by 1/8 between tints
      {"lambda_truncated", "lod_levels"},              // nearest-mip lambda 0.75 and 1.7 drop a level
      {"mag_min_switch_0_5", "lod_levels"},            // lambda 0.25 under LINEAR_MIPMAP_LINEAR
      {"blend_subtract_swapped", "blend"},             // the SUBTRACT and REVERSE_SUBTRACT columns
      {"depth_strict_swapped", "depth_ties"},          // redraws tie exactly: LESS fails, LEQUAL passes
      {"ao_crease_sign_flipped", "rtta_five_ao_post"}, // every convex box edge turns into an occluding crease
      {"layer_texcoord_swapped", "light_map"},         // the light map stretched once is read 8 times repeated
  };
  std::vector<const gl::Mutation*> mutations;
  for (const auto& [name, scene] : expected) {
    mutations.push_back(gl::findMutation(name));
    ASSERT_NE(mutations.back(), nullptr) << name;
  }
  const verify::MutantsResult r = verify::runMutants(frames, mutations, glBackend(), {});
  ASSERT_EQ(r.falseAlarms.size(), frames.size());
  for (size_t f = 0; f < frames.size(); ++f) EXPECT_EQ(r.falseAlarms[f], 0u) << frames[f].name;
  ASSERT_EQ(r.rows.size(), expected.size());
  for (size_t k = 0; k < expected.size(); ++k) {
    const verify::MutantRow& row = r.rows[k];
    EXPECT_EQ(row.status, "killed") << expected[k].first;
    EXPECT_NE(std::find(row.killedBy.begin(), row.killedBy.end(), expected[k].second), row.killedBy.end())
        << expected[k].first << " is not killed by " << expected[k].second;
  }
  // A mutant of a twin a scene does not use cannot change that scene: provoking_vertex draws only
  // object_id, which none of the source mutants of textured / texarray_batch / atlas_displace touch.
  for (size_t k = 1; k < 6; ++k) EXPECT_EQ(r.rows[k].unexplained[0], 0u) << expected[k].first;
  EXPECT_TRUE(r.passed());
  EXPECT_DOUBLE_EQ(r.killedPercent, 100.0);
  EXPECT_EQ(r.json["mutants"].size(), expected.size());
  EXPECT_EQ(r.json["false_alarms"]["blend"], 0);
}

TEST(Mutants, ClearingTheMutationRestoresTheUnmodifiedImageByteForByte) {
  const verify::MutantFrame f = frame("provoking_vertex");
  gl::GlBackend& gl = glBackend();
  auto render = [&] {
    gl.execute(f.list, f.name);
    return gl.readImage(gl.presented().at(0));
  };
  gl.setMutation(nullptr);
  const std::vector<uint8_t> before = render();
  gl.setMutation(gl::findMutation("provoking_vertex_first"));  // a pinned state of the context
  const std::vector<uint8_t> mutated = render();
  gl.setMutation(gl::findMutation("subpixel_bits_4"));  // recompiled twins
  render();
  gl.setMutation(nullptr);
  EXPECT_NE(mutated, before);  // the mutant did change something, so the restore below is a real test
  EXPECT_EQ(render(), before);
}

}  // namespace
}  // namespace tessera
