// Shared by the judgement tests (test_judge.cpp, test_candidates.cpp): a bounded search for the pixels an
// edit should touch.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

namespace tessera::testing {

// The first `n` distinct pixels (in top-down scan order, from `from`) of an image of `count` pixels that
// satisfy `pred`; fewer if the image has fewer. Every search is bounded by the image size and its result
// checked by the caller.
inline std::vector<size_t> findPixels(size_t count, size_t n, const std::function<bool(size_t)>& pred,
                                      size_t from = 0) {
  std::vector<size_t> found;
  for (size_t i = from; i < count && found.size() < n; ++i)
    if (pred(i)) found.push_back(i);
  return found;
}

}  // namespace tessera::testing
