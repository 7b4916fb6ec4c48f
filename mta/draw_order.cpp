#include "mta/draw_order.h"

#include <algorithm>
#include <map>
#include <set>
#include <utility>

namespace tessera::mta {

namespace {

// The texture a draw binds on the recorder's unit 0, as one number: the source in the top bits, then
// (tree, node) for an atlas and the scene texture for an original. White and Untextured bind the same
// 1x1 texture but differ in the tint, so they are two keys.
uint64_t textureKey0(const PlannedDraw& d) {
  const uint64_t src = uint64_t(d.source) << 60;
  switch (d.source) {
    case DrawSource::Atlas:
      return src | (uint64_t(d.tree) << 32) | d.node;
    case DrawSource::Original:
      return src | uint32_t(d.texture);
    case DrawSource::White:
    case DrawSource::Untextured:
      return src;
  }
  return src;
}

// Both units: unit 1 holds the atlas's own layer 1 (a function of the node), the original's layer-1
// texture, or white; only an original draw's layer-1 texture is not implied by unit 0's key.
std::pair<uint64_t, int32_t> textureKey(const PlannedDraw& d) {
  return {textureKey0(d), d.source == DrawSource::Original ? d.texture1 : -1};
}

}  // namespace

void groupDrawsByTexture(FramePlan& plan) {
  std::vector<PlannedDraw>& draws = plan.draws;
  if (draws.size() < 2) return;
  // Rank of each key's first appearance; a draw is sorted by the rank of its key.
  std::map<std::pair<uint64_t, int32_t>, uint32_t> rankOf;
  std::vector<std::pair<uint32_t, uint32_t>> order(draws.size());  // (rank, plan position)
  for (size_t i = 0; i < draws.size(); ++i) {
    const auto [it, fresh] = rankOf.emplace(textureKey(draws[i]), uint32_t(rankOf.size()));
    order[i] = {it->second, uint32_t(i)};
  }
  // (rank, position) pairs are distinct, so this is the stable sort by rank, without depending on the
  // standard library's stable_sort.
  std::sort(order.begin(), order.end());
  std::vector<PlannedDraw> out;
  out.reserve(draws.size());
  uint32_t lastRank = UINT32_MAX;
  for (const auto& [rank, i] : order) {
    const PlannedDraw& d = draws[i];
    if (rank == lastRank && out.back().first + out.back().count == d.first) {
      out.back().count += d.count;  // the same texture and state over a contiguous range: one draw
      continue;
    }
    out.push_back(d);
    lastRank = rank;
  }
  draws = std::move(out);
}

uint32_t textureKeyCount(const FramePlan& plan) {
  std::set<std::pair<uint64_t, int32_t>> keys;
  for (const PlannedDraw& d : plan.draws) keys.insert(textureKey(d));
  return uint32_t(keys.size());
}

}  // namespace tessera::mta
