#include "raster/storage_pool.h"

namespace tessera {

std::vector<uint8_t> StoragePool::take(size_t n) {
  // Best fit: the smallest spare that holds n bytes. A spare more than twice too large is left for a
  // larger request (a 1x1 level must not take a texture array's storage); frames mostly repeat their
  // sizes, so the exact fit is the usual case. A linear scan: a frame has at most a few hundred levels.
  size_t best = spare_.size();
  for (size_t i = 0; i < spare_.size(); ++i) {
    const size_t c = spare_[i].capacity();
    if (c < n || c / 2 > n + 4096) continue;
    if (best == spare_.size() || c < spare_[best].capacity()) best = i;
  }
  if (best == spare_.size()) return std::vector<uint8_t>(n, uint8_t{0});
  std::vector<uint8_t> v = std::move(spare_[best]);
  spare_[best] = std::move(spare_.back());
  spare_.pop_back();
  v.assign(n, uint8_t{0});  // within capacity: no reallocation, every byte zero as in a new vector
  return v;
}

}  // namespace tessera
