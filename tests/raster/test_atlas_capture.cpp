// The render-to-texture-atlas capture programs: atlas_capture (one bound texture per draw) and
// atlas_capture_tab (texture-array batching's TAM lookup, records on unit 9), on the scenes
// atlas_capture and atlas_capture_tab (tools/scenes/scene_atlas_capture.cpp).
#include <gtest/gtest.h>

#include <cstring>

#include "raster/cpu_backend.h"
#include "raster/image_io.h"
#include "tests/raster/render_helpers.h"
#include "tools/scenes/scenes.h"

namespace tessera {

TEST(AtlasCaptureTab, OneBatchedDrawCapturesEveryRegionAsThePerObjectDrawsDo) {
  // The same objects, the same textures (as layers of one array), the same records: the batched
  // lookup (textureGrad with the quad's coarse derivatives) picks the LOD the implicit lookup picks,
  // so all four images (RGBA8 and RG32F, two layers) must be the same bytes, from 1 draw instead of 6
  // (the draw count itself is checked against GL's calls by gl_tests).
  const auto bound = tessera::testing::renderList(scenes::build("atlas_capture", 96, 64), 2);
  const auto tab = tessera::testing::renderList(scenes::build("atlas_capture_tab", 96, 64), 2);
  ASSERT_EQ(bound.images.size(), 4u);
  ASSERT_EQ(tab.images.size(), 4u);
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(bound.images[i], tab.images[i]) << "image " << i;
  // The same triangles reach the pipeline (6 boxes x 12, 12 of them dropped for object 4's layer -1).
  EXPECT_EQ(tab.stats.primitives_assembled, 72u);
  EXPECT_EQ(tab.stats.primitives_dropped_by_program, 12u);
  EXPECT_EQ(bound.stats.primitives_assembled, 72u);
}

TEST(AtlasCapture, ObjectTexelsHaveAlphaOneAndCoveredDepthWhereEmptyTexelsKeepTheClear) {
  // Output 0's alpha is forced to 1 (the checker's dark cells have alpha 128), the clear has alpha 0;
  // output 1 is (z, 1) exactly where output 0 was written and the clear (1, 0) elsewhere.
  CpuBackend b(RenderOptions{2});
  b.execute(scenes::build("atlas_capture", 96, 64), "capture");
  const auto shown = b.presented();
  ASSERT_EQ(shown.size(), 4u);  // attachment 0 layers 0, 1; attachment 1 layers 0, 1
  size_t covered = 0;
  for (uint32_t layer = 0; layer < 2; ++layer) {
    const TextureData& colour = *b.texture(shown[layer].texture);
    const TextureData& depth = *b.texture(shown[2 + layer].texture);
    for (uint32_t y = 0; y < 64; ++y)
      for (uint32_t x = 0; x < 96; ++x) {
        const uint8_t alpha = colour.texel(0, layer, x, y)[3];
        float d[2];
        std::memcpy(d, depth.texel(0, layer, x, y), sizeof d);
        ASSERT_TRUE(alpha == 0 || alpha == 255) << x << "," << y << " layer " << layer;
        if (alpha == 255) {
          ++covered;
          EXPECT_EQ(d[1], 1.0f);
          EXPECT_GT(d[0], 0.0f);
          EXPECT_LT(d[0], 1.0f);
        } else {
          EXPECT_EQ(d[0], 1.0f);
          EXPECT_EQ(d[1], 0.0f);
        }
      }
  }
  EXPECT_GT(covered, 0u);
  EXPECT_LE(covered, size_t(b.stats().pixels_written));  // a pixel may be written more than once
}

}  // namespace tessera
