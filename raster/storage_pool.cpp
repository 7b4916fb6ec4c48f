#include "raster/storage_pool.h"

namespace tessera {

std::vector<uint8_t> StoragePool::take(size_t n) {
  // Best fit: the smallest spare that holds n bytes. A spare more than twice too large is left for a
  // larger request (a 1x1 level must not take a texture array's storage); frames mostly repeat their
  // sizes, so the exact fit is the usual case. Every spare above the smallest fit is larger still, so
  // if that one is too large, all are.
  const auto it = spare_.lower_bound(n);
  if (it == spare_.end() || it->first / 2 > n + 4096) return std::vector<uint8_t>(n, uint8_t{0});
  std::vector<uint8_t> v = std::move(it->second);
  spare_.erase(it);
  v.assign(n, uint8_t{0});  // within capacity: no reallocation, every byte zero as in a new vector
  return v;
}

}  // namespace tessera
