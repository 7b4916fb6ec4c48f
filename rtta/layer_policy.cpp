#include "rtta/layer_policy.h"

#include <charconv>
#include <fmt/format.h>

#include "base/error.h"

namespace tessera::rtta {

std::string LayerPolicy::name() const { return lazy ? fmt::format("lazy:{}", frames) : "exact"; }

LayerPolicy parseLayerPolicy(std::string_view text, std::string_view option) {
  if (text == "exact") return {};
  if (text.substr(0, 5) == "lazy:") {
    const std::string_view k = text.substr(5);
    uint32_t v = 0;
    const auto [end, ec] = std::from_chars(k.data(), k.data() + k.size(), v);
    if (ec == std::errc() && end == k.data() + k.size() && v >= 1 && v <= 10000) return {true, v};
  }
  throw Error(fmt::format("{} '{}': expected 'exact' or 'lazy:K' with K frames in 1..10000", option, text));
}

uint32_t LayerAllocator::frame(uint32_t needed) {
  needed = needed == 0 ? 1 : needed;
  stableFrames_ = needed == lastNeeded_ ? stableFrames_ + 1 : 1;
  lastNeeded_ = needed;
  uint32_t next = allocated_;
  if (!policy_.lazy || needed > allocated_) next = needed;
  else if (needed < allocated_ && stableFrames_ >= policy_.frames) next = needed;
  if (next != allocated_) ++reallocations_, allocated_ = next;
  return allocated_;
}

}  // namespace tessera::rtta
