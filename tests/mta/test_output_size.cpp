// The size of a build known before it writes (output_size.h), the output limit and --fit
// (output_budget.h): issue 14 §2, "a build that cannot run away".
#include <gtest/gtest.h>

#include <filesystem>

#include "base/error.h"
#include "model/city_gen.h"
#include "mta/build.h"
#include "mta/build_plan.h"
#include "mta/output_budget.h"
#include "mta/output_size.h"
#include "mta/paging_file.h"
#include "mta_test_scene.h"

namespace tessera::mta {
namespace {

using testing::gridScene;
using testing::TempFile;

Scene railway() {
  const std::string path = std::string(TESSERA_SOURCE_DIR) + "/data/railway.glb";
  // data/railway.glb is part of the repository (data/README.md): a missing copy is a failure, not a skip.
  if (!std::filesystem::exists(path)) throw Error(path + " is missing");
  return sceneFromModel(std::make_shared<const model::Model>(model::loadModel(path)));
}

BuildParams outputSizeParams(double dMin) {
  BuildParams p;
  p.atlasSize = 64;
  p.border = 2;
  p.tanHalfFov = 0.5;
  p.screenWidth = 256;
  p.dMin = dMin;
  return p;
}

// Builds, then checks the plan's estimate against the file: its size, and its parts against what the file's
// own block table says (payloads padded to 16 bytes, counted by kind).
void expectEstimateIsTheFile(const Scene& s, const BuildParams& p, const std::string& what) {
  SCOPED_TRACE(what);
  const OutputEstimate planned = estimateOutput(planBuild(s, p));
  TempFile out("tree.mta");
  const BuildReport rep = buildMta(s, p, out.path);
  const uint64_t size = std::filesystem::file_size(out.path);
  EXPECT_EQ(planned.totalBytes, size);
  EXPECT_EQ(rep.estimate.totalBytes, size);
  const PagingFile f(out.path);
  uint64_t atlas = 0, atlasBytes = 0, original = 0, originalBytes = 0;
  for (const BlockInfo& b : f.meta().blocks) {
    const uint64_t padded = (b.size + 15) / 16 * 16;
    if (b.kind == BlockKind::Atlas) ++atlas, atlasBytes += padded;
    if (b.kind == BlockKind::Original) ++original, originalBytes += padded;
  }
  EXPECT_EQ(planned.atlasBlocks, atlas);
  EXPECT_EQ(planned.atlasBytes, atlasBytes);
  EXPECT_EQ(planned.originalBlocks, original);
  EXPECT_EQ(planned.originalBytes, originalBytes);
  EXPECT_EQ(planned.pieces, f.meta().pieces.size());
  EXPECT_EQ(planned.metadataBytes, encodeMetadata(f.meta()).size());
  uint64_t nodes = 0;
  for (const Tree& t : f.meta().trees) nodes += t.nodes.size();
  EXPECT_EQ(planned.nodes, nodes);
}

TEST(OutputSize, TheEstimateIsTheExactFileSizeOfRailwayAtTwoDMinValues) {
  const Scene s = railway();
  for (double d : {5.0, 20.0}) {
    BuildParams p;
    p.dMin = d;
    expectEstimateIsTheFile(s, p, "railway at d_min " + std::to_string(d));
  }
}

TEST(OutputSize, TheEstimateIsTheExactFileSizeOfAGeneratedCity) {
  TempFile dir("city");
  model::CityOptions o;
  o.buildings = 6;
  o.textureSize = 64;
  o.outDir = dir.path;
  o.progress = false;
  const model::CitySummary cs = model::generateCity(o);
  const Scene s = sceneFromModel(std::make_shared<const model::Model>(model::loadModel(cs.gltf)));
  for (double d : {50.0, 200.0}) {
    BuildParams p;
    p.atlasSize = 128;
    p.dMin = d;
    expectEstimateIsTheFile(s, p, "city at d_min " + std::to_string(d));
  }
  std::filesystem::remove_all(dir.path);
}

TEST(OutputSize, TheEstimateCountsBothTreesAndEveryLayer) {
  // An RGB and an RGBA tree (4 bytes per texel) and a second layer (one more atlas per node).
  expectEstimateIsTheFile(gridScene(8, 8, 32, 2.0f, true, true), outputSizeParams(2.0),
                          "grid with alpha and two layers");
}

TEST(OutputSize, MetadataBytesIsTheSizeOfTheEncodedMetadata) {
  const Scene s = gridScene(6, 6, 32, 2.0f, true, true);
  TempFile out("tree.mta");
  buildMta(s, outputSizeParams(2.0), out.path);
  const PagingFile f(out.path);
  EXPECT_EQ(metadataBytes(f.meta(), f.meta().pieces.size(), f.meta().blocks.size()), encodeMetadata(f.meta()).size());
}

TEST(OutputSize, ARowLongerThanTheBlockTargetGetsABlockOfItsOwn) {
  OriginalBlockLayout l(100);
  auto p = l.next(3, 40, true);  // two rows fit (80 of 100)
  EXPECT_EQ(p.rows, 2u);
  EXPECT_EQ(p.closedBlockBytes, 0u);
  p = l.next(1, 40, false);  // the third does not: the block of 80 bytes is closed first
  EXPECT_EQ(p.closedBlockBytes, 80u);
  EXPECT_EQ(p.offset, 0u);
  p = l.next(2, 150, true);  // longer than the target: closes the 40 bytes, then one row alone
  EXPECT_EQ(p.closedBlockBytes, 40u);
  EXPECT_EQ(p.rows, 1u);
  p = l.next(1, 150, false);
  EXPECT_EQ(p.closedBlockBytes, 150u);
  EXPECT_EQ(l.fill(), 150u);
}

TEST(OutputSize, EveryImageStartsABlockOfItsOwnEvenWhenThePreviousBlockHasRoom) {
  OriginalBlockLayout l(100);
  auto p = l.next(2, 10, true);  // a small image: 20 bytes, 80 left in its block
  EXPECT_EQ(p.rows, 2u);
  EXPECT_EQ(p.closedBlockBytes, 0u);
  p = l.next(3, 10, true);  // the next image would fit, but starts a block of its own
  EXPECT_EQ(p.closedBlockBytes, 20u);
  EXPECT_EQ(p.offset, 0u);
  EXPECT_EQ(p.rows, 3u);
  EXPECT_EQ(l.fill(), 30u);
}

TEST(DMinGrid, ValuesHaveTwoSignificantDigitsAndRiseByAtMostTenPercent) {
  EXPECT_EQ(dMinGridValue(0), 1.0);
  EXPECT_EQ(dMinGridValue(1), 1.1);
  EXPECT_EQ(dMinGridValue(89), 9.9);
  EXPECT_EQ(dMinGridValue(90), 10.0);
  EXPECT_EQ(dMinGridValue(-1), 0.99);
  EXPECT_EQ(dMinGridValue(-71), 0.29);
  EXPECT_EQ(formatDMin(dMinGridValue(-71)), "0.29");
  EXPECT_EQ(formatDMin(dMinGridValue(-1000)), "9e-12");  // -1000 = -12 · 90 + 80: m = 90, e = -13
  for (int64_t i = kDMinGridFirst; i < kDMinGridLast; ++i) {
    ASSERT_GT(dMinGridValue(i + 1), dMinGridValue(i)) << i;
    ASSERT_LE(dMinGridValue(i + 1), dMinGridValue(i) * 1.1 + 1e-300) << i;
  }
  EXPECT_EQ(dMinGridValue(dMinGridIndexAbove(0.5)), 0.51);
  EXPECT_EQ(dMinGridValue(dMinGridIndexAbove(0.505)), 0.51);
  EXPECT_EQ(dMinGridValue(dMinGridIndexAbove(0.18829)), 0.19);
  EXPECT_EQ(dMinGridIndexAbove(1e30), kDMinGridLast + 1);
}

TEST(DMinGrid, SizesAndCountsPrintAsOptionValues) {
  EXPECT_EQ(byteSizeArgument(uint64_t(8) << 30), "8GiB");
  EXPECT_EQ(byteSizeArgument(uint64_t(1536) << 20), "1536MiB");
  EXPECT_EQ(byteSizeArgument(1000), "1000");
  EXPECT_EQ(groupThousands(18168), "18,168");
  EXPECT_EQ(groupThousands(999), "999");
  EXPECT_EQ(groupThousands(1000000), "1,000,000");
}

// No file under `path` and no temporary beside it.
void expectNothingWritten(const std::string& path) {
  EXPECT_FALSE(std::filesystem::exists(path));
  const std::filesystem::path p(path);
  for (const auto& e : std::filesystem::directory_iterator(p.parent_path()))
    EXPECT_NE(e.path().filename().string().rfind(p.filename().string() + ".tmp-", 0), 0u) << e.path();
}

TEST(OutputGuard, APlanOverTheLimitIsRefusedBeforeTheOutputExistsNamingADMinThatFits) {
  const Scene s = gridScene(8, 8, 32, 2.0f, true, true);
  const BuildParams p = outputSizeParams(0.5);
  const OutputEstimate full = estimateOutput(planBuild(s, p));
  OutputGuard g;
  g.maxBytes = full.totalBytes - 1;
  TempFile out("tree.mta");
  std::string message;
  try {
    buildMta(s, p, out.path, g);
  } catch (const Error& e) {
    message = e.what();
  }
  ASSERT_FALSE(message.empty()) << "a plan one byte over the limit was built";
  expectNothingWritten(out.path);
  EXPECT_NE(message.find("the tree would take " + formatBytes(full.totalBytes) + " (" + groupThousands(full.nodes) +
                         " nodes"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("--max-output is " + formatBytes(g.maxBytes)), std::string::npos) << message;
  EXPECT_NE(message.find("--fit " + byteSizeArgument(g.maxBytes)), std::string::npos) << message;
  // The suggested d_min, planned independently, fits.
  const std::string key = "pass --d-min ";
  const size_t at = message.find(key);
  ASSERT_NE(at, std::string::npos) << message;
  const double suggested = std::stod(message.substr(at + key.size()));
  EXPECT_GT(suggested, 0.5);
  const OutputEstimate fits = estimateOutput(planBuild(s, outputSizeParams(suggested)));
  EXPECT_LE(fits.totalBytes, g.maxBytes);
  EXPECT_NE(message.find("d_min " + formatDMin(suggested) + " fits (" + formatBytes(fits.totalBytes)),
            std::string::npos)
      << message;
  // At the limit itself it builds.
  g.maxBytes = full.totalBytes;
  EXPECT_EQ(buildMta(s, p, out.path, g).fileBytes, full.totalBytes);
}

TEST(OutputGuard, WhenNoDMinFitsTheMessageSaysSoAndNamesTheSmallestTree) {
  const Scene s = gridScene(4, 4, 32, 2.0f);
  OutputGuard g;
  g.maxBytes = 300;  // less than the metadata alone
  TempFile out("tree.mta");
  try {
    buildMta(s, outputSizeParams(0.5), out.path, g);
    FAIL() << "built into 300 bytes";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no d_min fits"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("raise --max-output"), std::string::npos) << e.what();
  }
  expectNothingWritten(out.path);
}

TEST(OutputGuard, FitChoosesADMinThatFitsWhoseNextFinerCandidateDoesNot) {
  const Scene s = railway();
  BuildParams p;  // default d_min: D / 72, about 0.19 m for railway (13.3 GiB)
  const uint64_t size = uint64_t(200) << 20;
  const DMinFit fit = fitDMin(s, p, size);
  ASSERT_TRUE(fit.found);
  EXPECT_GT(fit.plans, 2u);
  EXPECT_EQ(dMinGridValue(dMinGridIndexAbove(fit.dMin) - 1), fit.dMin) << "not a grid value: " << fit.dMin;
  // Planned again here, independently of the search: the choice fits, the next finer grid value does not.
  BuildParams chosen = p, finer = p;
  chosen.dMin = fit.dMin;
  finer.dMin = dMinGridValue(dMinGridIndexAbove(fit.dMin) - 2);
  EXPECT_EQ(finer.dMin, fit.finerDMin);
  const uint64_t chosenBytes = estimateOutput(planBuild(s, chosen)).totalBytes;
  const uint64_t finerBytes = estimateOutput(planBuild(s, finer)).totalBytes;
  EXPECT_LE(chosenBytes, size);
  EXPECT_GT(finerBytes, size);
  EXPECT_EQ(fit.estimate.totalBytes, chosenBytes);
  EXPECT_EQ(fit.finerBytes, finerBytes);
  // Same inputs, same choice.
  EXPECT_EQ(fitDMin(s, p, size).dMin, fit.dMin);
}

TEST(OutputGuard, FitKeepsTheFinestDMinWhenItFits) {
  const Scene s = gridScene(4, 4, 32, 2.0f);
  const BuildParams p = outputSizeParams(0.0);  // D / 72
  const uint64_t full = estimateOutput(planBuild(s, p)).totalBytes;
  const DMinFit fit = fitDMin(s, p, full);
  ASSERT_TRUE(fit.found);
  EXPECT_EQ(fit.dMin, resolveDMin(s, p));
  EXPECT_EQ(fit.plans, 1u);
}

TEST(OutputGuard, FitWithAnExplicitDMinIsRefused) {
  OutputGuard g;
  g.fitBytes = uint64_t(1) << 30;
  TempFile out("tree.mta");
  try {
    buildMta(gridScene(4, 4, 32, 2.0f), outputSizeParams(2.0), out.path, g);
    FAIL() << "--fit with --d-min was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--fit chooses d_min itself"), std::string::npos) << e.what();
  }
  expectNothingWritten(out.path);
}

TEST(OutputGuard, ABuildWithFitWritesTheChosenTreeAndReportsTheChoice) {
  const Scene s = gridScene(8, 8, 32, 2.0f);
  const BuildParams p = outputSizeParams(0.0);
  const uint64_t full = estimateOutput(planBuild(s, p)).totalBytes;
  OutputGuard g;
  g.fitBytes = full - 1;
  TempFile out("tree.mta");
  const BuildReport rep = buildMta(s, p, out.path, g);
  EXPECT_GT(rep.fitDMin, resolveDMin(s, p));
  EXPECT_LE(rep.fileBytes, g.fitBytes);
  EXPECT_EQ(rep.fileBytes, rep.estimate.totalBytes);
  const PagingFile f(out.path);
  EXPECT_EQ(f.meta().params.dMin, rep.fitDMin);
}

}  // namespace
}  // namespace tessera::mta
