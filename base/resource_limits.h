// Resource limits: the budgets that input is checked against before anything is allocated.
//
// Implements: one home for every size limit that protects the process from a file or an option
// (a frame's total texture / buffer / render-target memory, a model's instances, triangles and
// decoded texture bytes, the nesting depth of scene graphs, worker threads, an atlas tree's per-leaf
// block references, the frames, bytes and line length of camera path files), their documented defaults
// (docs/limits.md), overflow-checked arithmetic for computing a need, and the one error message
// format: what needs how much, the limit, by how much it is over, and the option that raises it.
// Does not implement: the GL limits of a frame's contents (raster/limits.h: texture size, units,
// layers), which are part of the oracle's contract rather than protection, or measuring free memory:
// the defaults are fixed numbers so that a verdict does not depend on the machine.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace tessera {

constexpr uint64_t kKiB = 1024, kMiB = 1024 * kKiB, kGiB = 1024 * kMiB;

struct ResourceLimits {
  // Every texture level, buffer and render target a frame creates, summed (validate(), --memory-budget).
  uint64_t frameBytes = 4 * kGiB;
  // A model: instances after expanding the node graph, triangles and vertices over all instances, and
  // the RGBA8 bytes of all its textures once decoded (--model-budget-* options of the commands that load
  // models). Vertices are limited apart from triangles because an instance copies every vertex of its
  // mesh, used by a triangle or not; the default is three per triangle of the triangle limit.
  uint64_t modelInstances = 1'000'000;
  uint64_t modelTriangles = 50'000'000;
  uint64_t modelVertices = 150'000'000;
  uint64_t modelTextureBytes = 8 * kGiB;
  // Nesting of a scene graph (glTF nodes, AC3D kids): deeper input is refused, whatever the memory.
  uint32_t graphDepth = 256;
  // An atlas tree paging file (mta/paging_file.h): the original-texture blocks indexed per leaf, one per
  // leaf and piece of each image the leaf uses. The memory manager's block index holds them, and a
  // frame's traversal may visit every one, so a small file whose leaves all share a many-piece image
  // would otherwise cost memory and time quadratic in its size.
  uint64_t mtaLeafBlockRefs = 64'000'000;
};

// Worker threads accepted by every --threads option (0 = all cores). Far above any machine the
// project runs on; far below what tbbmalloc and the per-thread scratch can survive.
constexpr int kMaxThreads = 256;

// Camera path files (mta/camera_path.h): frames of a path (file or built-in), bytes of a file, bytes of
// one line. A frame line written by mta::writePathFile is under 200 bytes.
constexpr uint32_t kMaxPathFrames = 1'000'000;
constexpr uint64_t kMaxPathFileBytes = 256 * kMiB;
constexpr uint32_t kMaxPathLineBytes = 4096;

// a * b and a + b, or nullopt when the result does not fit in 64 bits.
std::optional<uint64_t> checkedMul(uint64_t a, uint64_t b);
std::optional<uint64_t> checkedAdd(uint64_t a, uint64_t b);

// "1.5 GiB", "12 MiB", "300 B": binary units, one decimal.
std::string formatBytes(uint64_t bytes);

// The one message for a limit that input exceeds, e.g.
//   "<where>: needs 2.0 TiB of frame memory, over the budget of 4.0 GiB by 2.0 TiB (raise it with --memory-budget)"
// `need` is nullopt when it overflowed 64 bits ("needs more than 16 EiB"). `bytes` selects byte units.
std::string overLimitMessage(std::string_view where, std::string_view what, std::optional<uint64_t> need,
                             uint64_t limit, std::string_view option, bool bytes);

}  // namespace tessera
