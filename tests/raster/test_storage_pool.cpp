// StoragePool (raster/storage_pool.h): storage handed out again is zeroed and fits, and a backend
// reusing a frame's texel storage shows none of that frame's texels in the next.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "raster/cpu_backend.h"
#include "raster/storage_pool.h"
#include "tests/raster/render_helpers.h"

namespace tessera {

TEST(StoragePool, TakenStorageIsZeroedEvenWhenItsLastOwnerFilledIt) {
  StoragePool pool;
  std::vector<uint8_t> used(4096, 0xab);
  const uint8_t* where = used.data();
  pool.give(std::move(used));
  const std::vector<uint8_t> again = pool.take(3000);
  EXPECT_EQ(again.data(), where);  // the same storage, not a new allocation
  ASSERT_EQ(again.size(), 3000u);
  EXPECT_TRUE(std::all_of(again.begin(), again.end(), [](uint8_t b) { return b == 0; }));
  EXPECT_EQ(pool.spareCount(), 0u);
}

TEST(StoragePool, TheSmallestSpareThatFitsIsTakenAndAMuchLargerOneIsLeft) {
  StoragePool pool;
  std::vector<uint8_t> big(1 << 20), exact(1 << 16), small(100);
  const uint8_t* exactData = exact.data();
  pool.give(std::move(big));
  pool.give(std::move(exact));
  pool.give(std::move(small));
  EXPECT_EQ(pool.take(1 << 16).data(), exactData);
  // 4 bytes: `small` fits; `big` must never serve a tiny level.
  const std::vector<uint8_t> tiny = pool.take(4);
  EXPECT_LE(tiny.capacity(), 100u);
  // Nothing left that fits 300 KB without wasting more than half: a new vector.
  EXPECT_EQ(pool.take(300 << 10).size(), size_t(300) << 10);
  EXPECT_EQ(pool.spareCount(), 1u);  // `big`
  pool.release();
  EXPECT_EQ(pool.spareCount(), 0u);
}

TEST(StoragePool, ATargetNeverClearedShowsZerosAfterAFrameThatFilledTheSameSizedStorage) {
  // Frame 1 clears a 64x64 RGBA8 target to white; frame 2 binds a new target of the same size and
  // presents it untouched. GL leaves its contents undefined; the oracle's textures start at zero
  // (texture.h), and reused storage must keep that.
  auto frame = [](bool clear) {
    CommandList cl;
    TextureDesc d;
    d.format = Format::RGBA8;
    d.width = 64;
    d.height = 64;
    RenderTarget rt;
    rt.color[0] = cl.createTexture(d);
    cl.setRenderTarget(rt);
    cl.setViewport({0, 0, 64, 64});
    if (clear) cl.clearColor(0, {1, 1, 1, 1});
    return cl;
  };
  CpuBackend reused(RenderOptions{2});
  reused.execute(frame(true), "white");
  reused.execute(frame(false), "untouched");
  const PresentedImage p = reused.presented().at(0);
  const TextureData& t = *reused.texture(p.texture);
  EXPECT_TRUE(std::all_of(t.levels[0].begin(), t.levels[0].end(), [](uint8_t b) { return b == 0; }));
  EXPECT_EQ(imageSha256(t, 0, 0), tessera::testing::renderList(frame(false), 2).hashes.at(0));
}

}  // namespace tessera
