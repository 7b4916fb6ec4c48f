// A CpuBackend reused for a sequence of frames keeps the memory of the earlier frames (triangle blocks,
// bins, setup sinks, per-draw vertex arrays; cpu_backend.cpp adoptCapacity) but none of their state:
// every frame must give a new backend's bytes and counters.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "render_helpers.h"
#include "tools/scenes/scenes.h"
#include "tools/scenes/sweep_scenes.h"

namespace tessera {

namespace {

struct NamedFrame {
  std::string name;
  CommandList list;
};

}  // namespace

TEST(BackendReuse, EveryFrameOfASequenceHasTheBytesAndCountersOfANewBackend) {
  // Frames that grow and shrink every reused array: many triangles (several setup chunks and blocks),
  // other target sizes (bin count), several draws per frame, and the big frame again at the end so
  // that spare blocks holding earlier triangles are reused.
  std::vector<NamedFrame> frames;
  frames.push_back({"tiny_tris 20000", scenes::buildTinyTris(320, 240, 20000)});
  frames.push_back({"city_block", scenes::build("city_block", 160, 120)});
  frames.push_back({"tiny_tris 700", scenes::buildTinyTris(96, 64, 700)});
  frames.push_back({"depth_ties", scenes::build("depth_ties", 64, 48)});
  frames.push_back({"tiny_tris 20000 again", scenes::buildTinyTris(320, 240, 20000)});
  frames.push_back({"clip_planes", scenes::build("clip_planes", 128, 96)});
  for (int threads : {1, 3}) {
    CpuBackend reused(RenderOptions{threads});
    for (const NamedFrame& f : frames) {
      reused.execute(f.list, f.name);
      const tessera::testing::Rendered fresh = tessera::testing::renderList(f.list, threads);
      const std::vector<PresentedImage> presented = reused.presented();
      ASSERT_EQ(presented.size(), fresh.hashes.size()) << f.name;
      for (size_t i = 0; i < presented.size(); ++i)
        EXPECT_EQ(imageSha256(*reused.texture(presented[i].texture), presented[i].level, presented[i].layer),
                  fresh.hashes[i])
            << f.name << " at " << threads << " threads, image " << i;
      testing::expectSameCounters(reused.stats(), fresh.stats, f.name + ": reused backend against a new one");
    }
  }
}

}  // namespace tessera
