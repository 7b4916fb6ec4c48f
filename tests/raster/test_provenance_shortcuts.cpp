// Provenance mode's lookup shortcuts (raster/sample_interval.cpp: skipped trilinear weights, level
// grids shared by a pass's plans, a plan's LINEAR alternatives reduced at once) must give exactly what
// the "reference" SIMD target gives without them: every rendered texture's lower and upper images,
// classes, flags, candidate lists and candidate depths, on every built-in scene.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <variant>
#include <vector>

#include "raster/cpu_backend.h"
#include "raster/provenance.h"
#include "raster/simd_targets.h"
#include "tests/raster/provenance_compare.h"
#include "tests/raster/render_helpers.h"
#include "tools/scenes/scenes.h"

namespace tessera::scenes {
using tessera::testing::expectSameProvenance;
using tessera::testing::SimdTargetGuard;

namespace {

class ProvenanceShortcuts : public ::testing::TestWithParam<std::string> {};

TEST_P(ProvenanceShortcuts, GiveTheReferenceTargetsIntervalsClassesAndCandidates) {
  SimdTargetGuard guard;
  const SceneInfo* info = find(GetParam());
  const CommandList cl = build(info->name, info->width, info->height);
  const RenderOptions options{2, true, {}, 8};  // provenance, judged against 8 sub-pixel bits
  CpuBackend fast(options), reference(options);
  simd::forceTarget("best");
  fast.execute(cl, GetParam());
  simd::forceTarget("reference");
  reference.execute(cl, GetParam());
  int compared = 0;
  for (const Command& c : cl.commands()) {
    const auto* ct = std::get_if<CreateTexture>(&c);
    if (!ct) continue;
    const TextureData *a = fast.texture(ct->id), *b = reference.texture(ct->id);
    ASSERT_TRUE(a && b);
    ASSERT_EQ(a->levels, b->levels) << "texture " << ct->id << ": values differ";
    ASSERT_EQ(bool(a->prov), bool(b->prov)) << "texture " << ct->id;
    if (!a->prov) continue;
    expectSameProvenance(*a->prov, *b->prov, "texture " + std::to_string(ct->id));
    ++compared;
  }
  EXPECT_GT(compared, 0) << "no rendered texture to compare";
  // The reference target takes no shortcut; the best one takes them where the scene has the lookups
  // for them (city_block: trilinear minification, whose level pairs share grids and skip weights).
  EXPECT_EQ(reference.stageTimes().provPlansSkipped, 0u);
  EXPECT_EQ(reference.stageTimes().provGridsShared, 0u);
  if (GetParam() == "city_block") {
    EXPECT_GT(fast.stageTimes().provPlansSkipped, 10000u);
    EXPECT_GT(fast.stageTimes().provGridsShared, 100000u);
  }
}

INSTANTIATE_TEST_SUITE_P(AllScenes, ProvenanceShortcuts, ::testing::ValuesIn([] {
                           std::vector<std::string> names;
                           for (const auto& s : all()) names.emplace_back(s.name);
                           return names;
                         }()),
                         [](const auto& param) { return param.param; });

}  // namespace
}  // namespace tessera::scenes
