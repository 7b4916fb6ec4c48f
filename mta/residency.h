// The memory manager of the atlas tree (thesis §4.6): which paging-file blocks are in memory.
//
// Implements, as §4.6 describes:
// - blocks (node atlases and original-texture blocks) with a capacity k in bytes that the summed size of
//   the blocks in memory (plus blocks being loaded) never exceeds; the root atlases of the layers drawn
//   are loaded at construction and never removed;
// - per frame, from the block priorities of the usage traversal (traversal.h: usage category Needed /
//   Culled / Parent needed / Unused, then distance, then tree level): the ideal block set, i.e. the
//   blocks of the first three categories in priority order, cut to the longest prefix whose size fits
//   the capacity;
// - a request queue (at most maxQueue blocks, in priority order) refilled from the ideal set with the
//   most important blocks neither in memory nor queued, and dropped entries that left the ideal set (§4.6:
//   "a block is removed from the queue if ... it is no longer in the ideal block set"), also while they
//   are being loaded: a partly read block (Bytes budget) is abandoned, a block handed to the background
//   loader (Time budget) is taken back if its read has not started and dropped when the read ends if it
//   has;
// - loading within a per-frame budget, removing the block of lowest priority when a load would exceed
//   the capacity (never a block of the ideal set: the ideal set fits by construction);
// - Unused blocks keep the distance and level of the last frame that gave them another category (the
//   traversal does not reach them, so it cannot measure them): among resident Unused blocks the farthest
//   and deepest go first, so a node's descendants and its originals are removed before the node itself,
//   as §4.6 wants ("if the atlas of a node N is in memory, the atlases for all nodes on the path to N
//   should also be in memory"). Blocks never given a category keep the default (infinite distance,
//   deepest level).
// Budgets: Bytes / Blocks are deterministic (the same path gives the same residency on every run and
// machine; tests and goldens use them); Time reserves a wall-clock slot per frame for blocks read by a
// background loader thread (interactive use; not reproducible).
// Block sizes are paging-file payload bytes: what the thesis's k bounds. The textures made from them
// (RGBA8 with mipmaps, frame_recorder.h) are a derived cache dropped with their blocks.
// Does not implement: the usage traversal and rendering (traversal.h).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "mta/paging_file.h"

namespace tessera::mta {

enum class Usage : uint8_t { Needed = 0, Culled = 1, ParentNeeded = 2, Unused = 3 };
const char* usageName(Usage u);

// Smaller is more important: usage, then distance, then level, then block index (a total order, so
// every tie is broken the same way on every machine). The default is what a block that no frame has
// reached yet gets.
struct BlockPriority {
  Usage usage = Usage::Unused;
  double distance = std::numeric_limits<double>::infinity();
  uint32_t level = std::numeric_limits<uint32_t>::max();
};
bool morePressing(const BlockPriority& a, uint32_t blockA, const BlockPriority& b, uint32_t blockB);

struct LoadBudget {
  enum class Kind : uint8_t { Bytes, Blocks, Time } kind = Kind::Bytes;
  uint64_t perFrame = uint64_t(8) << 20;  // Bytes: payload bytes per frame; Blocks: blocks per frame
  double slotMs = 4.0;                    // Time: wall-clock milliseconds per frame
  // Parses "8MiB", "3000000", "4blocks", "5ms" (the --budget syntax); throws Error naming `what`.
  static LoadBudget parse(const std::string& text, const std::string& what);
  std::string describe() const;
};

struct ResidencyOptions {
  uint64_t capacityBytes = uint64_t(100) << 20;  // k; the thesis used 100 MB
  LoadBudget budget;
  uint32_t maxQueue = 32;
  // The layers the renderer draws (TreeRenderer passes frame_recorder.h's kRecordedLayers): only their
  // root atlases are pinned. The usage traversal requests nothing of the other layers (traversal.h).
  LayerMask drawnLayers = 1;
  // Time budget: what the background loader reads a block with (empty: PagingFile::readBlock). Tests
  // substitute a reader they can hold, to make a block leave the ideal set while it is being read.
  std::function<std::vector<uint8_t>(uint32_t block)> blockReader;
};

// What happened in one update().
struct ResidencyFrameStats {
  uint64_t blocksLoaded = 0, bytesLoaded = 0, blocksEvicted = 0;
  uint64_t loadsCancelled = 0;                        // loads under way that left the ideal set (see above)
  uint64_t idealBlocks = 0, idealBytes = 0;          // after the cut to capacity
  uint64_t idealBlocksCut = 0;                        // blocks of the first three categories left out
  uint64_t neededMissing = 0;                         // Needed blocks not in memory after loading
  uint64_t queueLength = 0;
  std::vector<uint32_t> loadOrder;                    // blocks completed this frame, in order
  std::vector<uint32_t> evictionOrder;                // blocks removed this frame, in order
};

class Residency {
 public:
  // Loads every root atlas. Throws Error if the capacity cannot hold them.
  Residency(const PagingFile& file, ResidencyOptions options);
  ~Residency();
  Residency(const Residency&) = delete;
  Residency& operator=(const Residency&) = delete;

  // priority: one entry per paging-file block (from the usage traversal). An Unused entry's distance and
  // level are ignored: the block keeps those of the last frame that gave it another category.
  const ResidencyFrameStats& update(const std::vector<BlockPriority>& priority);
  // The priority the last update() used for `block` (Unused blocks with their last distance and level).
  const BlockPriority& priority(uint32_t block) const { return priority_[block]; }
  // Time budget: waits until the background loader has read every block handed to it (returns at once for
  // the other budgets); the next update() installs or drops them. For tests, which must not time a read.
  void waitForLoader();

  bool resident(uint32_t block) const { return state_[block].resident; }
  // The payload of a resident block (empty span otherwise).
  std::span<const uint8_t> data(uint32_t block) const;
  // Bumped each time the block is loaded: caches of derived textures key on (block, generation).
  uint64_t generation(uint32_t block) const { return state_[block].generation; }
  bool pinned(uint32_t block) const { return state_[block].pinned; }

  uint64_t bytesResident() const { return bytesResident_; }  // includes blocks being loaded
  uint64_t blocksResident() const { return blocksResident_; }
  uint64_t capacity() const { return options_.capacityBytes; }
  uint64_t peakBytesResident() const { return peak_; }
  const ResidencyOptions& options() const { return options_; }

 private:
  struct BlockState {
    bool resident = false, pinned = false, queued = false, inFlight = false, ideal = false;
    bool cancelled = false;  // in flight (Time budget) but no longer ideal: dropped when its read ends
    uint64_t progress = 0;  // Bytes budget: payload bytes read so far
    uint64_t generation = 0;
    std::vector<uint8_t> bytes;
  };
  bool makeRoom(uint64_t bytes);
  void install(uint32_t block, std::vector<uint8_t> bytes);
  void checkCapacity() const;
  void serveDeterministic();
  void serveTimed();
  void cancelTimed();
  void loaderMain();

  const PagingFile& file_;
  ResidencyOptions options_;
  std::vector<BlockState> state_;
  std::vector<BlockPriority> priority_;  // this frame's, Unused blocks with their last distance and level
  std::vector<uint32_t> queue_;
  uint64_t bytesResident_ = 0, blocksResident_ = 0, peak_ = 0;
  ResidencyFrameStats stats_;

  // Time budget: the loader thread reads the blocks it is handed (space already reserved).
  std::thread loader_;
  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<uint32_t> toLoad_;
  std::vector<std::pair<uint32_t, std::vector<uint8_t>>> loaded_;
  std::string loaderError_;
  bool reading_ = false;  // the loader is reading a block it took from toLoad_
  bool stop_ = false;
};

}  // namespace tessera::mta
