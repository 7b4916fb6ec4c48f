// Fuzz target `mta`: the atlas tree paging file reader and validator (mta/paging_file.h) and what the
// renderer does with a file that passed it, short of drawing: the runtime geometry
// (mta/runtime_geometry.h), the block index, the usage traversal and the rendering traversal of
// mta/traversal.h in all three modes with the draws grouped by texture (mta/draw_order.h), and reading
// blocks (the root atlas and the smaller original images).
//
// The input is a .mta file, written to the scratch directory because PagingFile takes a path. Before that,
// the fields a mutation cannot keep consistent by chance are recomputed: the file size (bytes 16..23), the
// metadata size (32..39, from the metadata offset at 24..31 that the input keeps), the metadata SHA-256
// (40..71) and the header SHA-256 (96..127). So mutations of the node tables, the geometry and the block
// directory reach the validator instead of stopping at a checksum. Block payloads keep their own
// checksums (in the metadata); a mutation of the metadata leaves them valid, so readImage() sees hostile
// piece records over genuine blocks.
// Cameras: frame 0 of the built-in "orbit" path (an overview) and the middle frame of "street" (a
// pedestrian view that refines deep), both laid out over the trees' root bounds as `tessera mta render` does.
// Does not record or render frames (mta/frame_recorder.h, the oracle): too slow per input.
#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "base/error.h"
#include "base/sha256.h"
#include "fuzz/fuzz_support.h"
#include "mta/camera_path.h"
#include "mta/draw_order.h"
#include "mta/paging_file.h"
#include "mta/runtime_geometry.h"
#include "mta/traversal.h"

namespace {

using namespace tessera;
using namespace tessera::mta;

constexpr uint8_t kMagic[8] = {'T', 'E', 'S', 'S', 'M', 'T', 'A', 0x1a};

template <typename T>
void put(std::vector<uint8_t>& b, size_t at, T v) {
  std::memcpy(b.data() + at, &v, sizeof v);  // the format is little-endian, as is every target we run on
}

void fixHeader(std::vector<uint8_t>& b) {
  if (b.size() < kHeaderSize || std::memcmp(b.data(), kMagic, 8) != 0) return;
  const uint64_t size = b.size();
  uint64_t metaOffset = 0;
  std::memcpy(&metaOffset, b.data() + 24, 8);
  put<uint64_t>(b, 16, size);
  if (metaOffset >= kHeaderSize && metaOffset <= size) {
    put<uint64_t>(b, 32, size - metaOffset);
    const auto ms = sha256(std::span<const uint8_t>(b).subspan(size_t(metaOffset)));
    std::memcpy(b.data() + 40, ms.data(), 32);
  }
  const auto hs = sha256(std::span<const uint8_t>(b.data(), 96));
  std::memcpy(b.data() + 96, hs.data(), 32);
}

// The trees' root bounds, as tools/cli/mta_path_run.cpp lays out the built-in paths.
bool sceneBounds(const MtaMeta& meta, std::array<float, 6>& b) {
  b = {1e30f, 1e30f, 1e30f, -1e30f, -1e30f, -1e30f};
  for (const Tree& t : meta.trees) {
    if (t.nodes.empty()) continue;
    for (int k = 0; k < 3; ++k) {
      b[k] = std::min(b[k], t.nodes[0].bounds[k]);
      b[k + 3] = std::max(b[k + 3], t.nodes[0].bounds[k + 3]);
    }
  }
  return b[0] <= b[3];
}

void traverse(const PagingFile& file) {
  const MtaMeta& meta = file.meta();
  std::array<float, 6> bounds;
  if (!sceneBounds(meta, bounds)) return;
  std::vector<Camera> cameras;
  try {
    cameras.push_back(builtinPath("orbit", bounds, 1).frames.at(0));
    cameras.push_back(builtinPath("street", bounds, 3).frames.at(1));
  } catch (const Error&) {
    return;  // non-finite or inverted bounds: the CLI stops here too
  }
  const RuntimeGeometry geometry = buildRuntimeGeometry(meta);
  // Every layer of the file, so that the per-layer image lists of the index are exercised for each.
  const BlockIndex index = buildBlockIndex(meta, ~LayerMask(0));
  for (Camera c : cameras) {
    c.tanHalfFovX = meta.params.tanHalfFov;
    ViewParams v;
    v.camera = c;
    v.width = 64;
    v.height = 48;
    ViewContext ctx;
    try {
      ctx = makeViewContext(meta, v);
    } catch (const Error&) {
      continue;  // a camera the file's parameters make invalid
    }
    (void)usagePriorities(meta, index, ctx);
    // Every third block missing, so that the traversal also takes its "refinement impossible" path.
    auto someResident = [](uint32_t b) { return b % 3 != 1; };
    for (RenderMode mode : {RenderMode::AtlasTree, RenderMode::Original, RenderMode::Dummy}) {
      FramePlan plan = planFrame(meta, geometry, index, ctx, mode, someResident);
      groupDrawsByTexture(plan);
    }
  }
}

void readBlocks(const PagingFile& file) {
  const MtaMeta& meta = file.meta();
  if (!meta.trees.empty()) {
    try {
      (void)file.readAtlas(0, 0, 0);
    } catch (const Error&) {
    }
  }
  // Only small images: a validated file may still describe a 65536 x 65536 image made of pieces that
  // share one block, and allocating that per input would only measure the machine.
  for (uint32_t i = 0, read = 0; i < meta.images.size() && read < 4; ++i) {
    const ImageRecord& r = meta.images[i];
    if (uint64_t(r.width) * r.height > (uint64_t(1) << 20)) continue;
    ++read;
    try {
      (void)file.readImage(i);
    } catch (const Error&) {
    }
  }
}

void run(const uint8_t* data, size_t size) {
  std::vector<uint8_t> bytes(data, data + size);
  fixHeader(bytes);
  const std::string path = fuzz::writeScratch("input.mta", bytes);
  try {
    const PagingFile file(path);
    traverse(file);
    readBlocks(file);
    if (fuzz::verbose())
      fuzz::note("mta", "opened and traversed: " + std::to_string(file.meta().trees.size()) + " tree(s), " +
                            std::to_string(file.meta().blocks.size()) + " block(s)");
  } catch (const Error& e) {
    fuzz::note("mta", e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fuzz::DescriptorCheck descriptors;
  run(data, size);
  descriptors.expectNoLeak("mta");
  return 0;
}
