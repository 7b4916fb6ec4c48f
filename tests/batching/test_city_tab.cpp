// Texture-array batching of generated cities (model/city_gen.h) with Table 1's texture counts: berlin
// (one facade resolution: one array per d_max textures) at N = 14, 204, 269, 864, and chemnitz (many
// resolutions, RGBA, MASK and BLEND materials). Small textures keep the test fast; Algorithm 1 only
// sees their keys.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "batching/batcher.h"
#include "batching/input_batches.h"
#include "batching/tab_stats.h"
#include "model/city_gen.h"
#include "model/model.h"
#include "tests/batching/scratch_dir.h"

namespace tessera::batching {
namespace {

namespace fs = std::filesystem;

using testing::TempDir;

TabScene cityInput(model::CityPreset preset, uint32_t buildings, uint32_t textureSize, const fs::path& dir) {
  model::CityOptions o;
  o.preset = preset;
  o.buildings = buildings;
  o.textureSize = textureSize;
  o.outDir = (dir / (std::string(model::cityPresetName(preset)) + std::to_string(buildings))).string();
  o.progress = false;
  return prepareInput(model::loadModel(model::generateCity(o).gltf));
}

// Table 1's berlin texture counts. Under the sanitizers two of them, one below 256 (one array) and one
// above (several arrays, one output batch), through the same code: there the four took 127 s (3.2 s in
// Release), three quarters of it in decoding the 1,351 facades, as OpenImageIO 2.4 reads each 8x8 PNG
// through a fresh 64 MiB buffer (CONTRIBUTING.md, "CI"). Release checks all four.
#if defined(__SANITIZE_ADDRESS__)
constexpr uint32_t kBerlinTextureCounts[] = {14u, 269u};
#else
constexpr uint32_t kBerlinTextureCounts[] = {14u, 204u, 269u, 864u};
#endif

TEST(TabCity, BerlinWithTableOnesTextureCountsBatchesEveryFacadeIntoFullArrays) {
  TempDir tmp;
  for (uint32_t n : kBerlinTextureCounts) {
    TabScene s = cityInput(model::CityPreset::Berlin, n, 8, tmp.dir);
    runAlgorithm1(s, TabParams{});
    const nlohmann::json t = tableOneJson(s);
    EXPECT_EQ(t["textures"], n) << n;
    EXPECT_EQ(t["input_batches"], n) << n;
    // One resolution: ceil(n / 256) arrays, all in one output batch (at most 8 arrays), one draw.
    EXPECT_EQ(t["array_count"], (n + 255) / 256) << n;
    EXPECT_EQ(t["output_batches"], 1u) << n;
    EXPECT_EQ(t["geometry_batches"], 1u) << n;
    EXPECT_EQ(t["untextured"]["draws"], 1u) << n;  // roofs and ground: one flat-colour draw
  }
}

TEST(TabCity, ChemnitzKeepsBlendMeshesUnbatchedAndMaskMeshesBatched) {
  TempDir tmp;
  TabScene s = cityInput(model::CityPreset::Chemnitz, 60, 64, tmp.dir);  // sizes scale by 64 / 512: still many
  runAlgorithm1(s, TabParams{});
  size_t blend = 0, mask = 0;
  for (const TabMesh& m : s.meshes) {
    if (m.kind == MeshKind::Blend) ++blend;
    if (m.kind == MeshKind::Batched && m.alphaMode == AlphaMode::Mask) {
      ++mask;
      const TamEntry& e = s.batches[m.outputBatch].tam[m.tamIndex];
      EXPECT_EQ(e.alphaCutoff, m.alphaCutoff);
      EXPECT_TRUE(e.opaque);
    }
  }
  EXPECT_GT(blend, 0u);
  EXPECT_GT(mask, 0u);
  const nlohmann::json t = tableOneJson(s);
  EXPECT_GT(t["array_count"].get<uint64_t>(), 8u);  // many resolutions
  EXPECT_GE(t["output_batches"].get<uint64_t>(), (t["array_count"].get<uint64_t>() + 7) / 8);
}

}  // namespace
}  // namespace tessera::batching
