// StoragePool: byte vectors kept from the textures and buffers of a backend's previous frame, handed
// out again zeroed, so that a backend rendering a sequence of frames (an atlas-tree path, a TAB path,
// the LOD probe of every frame) writes into pages it already owns instead of faulting in fresh ones
// and unmapping the old ones. On railway's texture arrays those page faults and unmaps were about a
// third of a frame.
//
// Implements: give() (storage of a finished frame), take() (n zero bytes, in the smallest spare whose
// capacity fits and wastes at most about half of it, else a new vector), release().
// Does not: ever hand out old contents (take() zeroes every byte it returns, exactly as a new vector
// would, so a frame renders as on a new backend), or keep storage a frame did not take: CpuBackend
// releases the leftovers when the frame ends, so the pool holds at most the previous frame's storage.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

namespace tessera {

class StoragePool {
 public:
  void give(std::vector<uint8_t>&& bytes) {
    if (bytes.capacity() > 0) spare_.emplace(bytes.capacity(), std::move(bytes));
  }
  std::vector<uint8_t> take(size_t n);
  void release() { spare_.clear(); }
  size_t spareCount() const { return spare_.size(); }

 private:
  // By capacity: the best fit is one lookup. A frame of a few hundred textures has a few thousand
  // levels, and a linear scan per level was a tenth of a small frame's time (city_block at 320x240).
  std::multimap<size_t, std::vector<uint8_t>> spare_;
};

}  // namespace tessera
