// How many layers the atlas texture array has allocated, frame after frame (Trapp & Döllner 2010,
// §4.2): the paper saw driver stalls when layers were removed from the texture array and answered with
// lazy updates, "if the number of layers have not changed during a number of passes".
// - exact:    allocated = needed on every frame (a reallocation whenever Td changes);
// - lazy:K:   grow at once when a frame needs more layers (it could not be captured otherwise); shrink
//             to the need only after K consecutive frames that all needed the same, smaller count.
// parseLayerPolicy accepts "exact" and "lazy:K" with 1 <= K <= 10000.
// Does not implement: the allocation itself (the recorder creates the texture of allocated() layers).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace tessera::rtta {

struct LayerPolicy {
  bool lazy = false;
  uint32_t frames = 0;  // K
  std::string name() const;
};
// Throws Error naming `option` and the text on anything else.
LayerPolicy parseLayerPolicy(std::string_view text, std::string_view option = "--layers");

class LayerAllocator {
 public:
  explicit LayerAllocator(LayerPolicy p) : policy_(p) {}
  // The layer count to allocate for a frame that needs `needed` layers (at least 1: an empty atlas
  // still needs a target). Counts reallocations (every change of the allocated count).
  uint32_t frame(uint32_t needed);
  uint32_t allocated() const { return allocated_; }
  uint64_t reallocations() const { return reallocations_; }

 private:
  LayerPolicy policy_;
  uint32_t allocated_ = 0;
  uint32_t lastNeeded_ = 0;
  uint32_t stableFrames_ = 0;
  uint64_t reallocations_ = 0;
};

}  // namespace tessera::rtta
