#include "mta/residency.h"

#include <algorithm>
#include <charconv>
#include <chrono>

#include "base/byte_size.h"
#include "base/error.h"

namespace tessera::mta {

const char* usageName(Usage u) {
  switch (u) {
    case Usage::Needed: return "needed";
    case Usage::Culled: return "culled";
    case Usage::ParentNeeded: return "parent_needed";
    case Usage::Unused: return "unused";
  }
  return "?";
}

bool morePressing(const BlockPriority& a, uint32_t blockA, const BlockPriority& b, uint32_t blockB) {
  if (a.usage != b.usage) return a.usage < b.usage;
  if (a.distance != b.distance) return a.distance < b.distance;
  if (a.level != b.level) return a.level < b.level;
  return blockA < blockB;
}

LoadBudget LoadBudget::parse(const std::string& text, const std::string& what) {
  double v = 0.0;
  const char* b = text.data();
  const char* e = text.data() + text.size();
  auto [p, ec] = std::from_chars(b, e, v);
  if (ec != std::errc() || !(v > 0.0) || !(v < 1e18))
    throw Error(what + ": '" + text + "' is not a positive number with an optional unit (B, KiB, MiB, GiB, TiB, blocks, ms)");
  const std::string unit(p, e);
  LoadBudget r;
  // Byte sizes have one parser (base/byte_size.h): exact for whole numbers, overflow-checked.
  if (isByteUnit(unit)) r.kind = Kind::Bytes, r.perFrame = parseByteSize(text, what);
  else if (unit == "blocks" || unit == "block") r.kind = Kind::Blocks, r.perFrame = uint64_t(v);
  else if (unit == "ms") r.kind = Kind::Time, r.slotMs = v;
  else throw Error(what + ": unknown unit '" + unit + "' in '" + text + "' (use B, KiB, MiB, GiB, TiB, blocks or ms)");
  if (r.kind != Kind::Time && r.perFrame == 0) throw Error(what + ": '" + text + "' rounds to zero");
  return r;
}

std::string LoadBudget::describe() const {
  switch (kind) {
    case Kind::Bytes: return std::to_string(perFrame) + " bytes per frame";
    case Kind::Blocks: return std::to_string(perFrame) + " blocks per frame";
    case Kind::Time: return std::to_string(slotMs) + " ms per frame (background loader)";
  }
  return "?";
}

Residency::Residency(const PagingFile& file, ResidencyOptions options) : file_(file), options_(options) {
  const MtaMeta& m = file.meta();
  state_.resize(m.blocks.size());
  priority_.resize(m.blocks.size());
  if (options_.maxQueue == 0) throw Error("memory manager: the request queue length must be at least 1");
  auto drawn = [&](uint32_t layer) { return layer < 32 && (options_.drawnLayers >> layer & 1); };
  uint64_t rootBytes = 0;
  for (const Tree& t : m.trees)
    for (uint32_t l = 0; l < m.layerCount; ++l) {
      // Guaranteed by the paging file's validator; checked because it is indexed with.
      if (t.atlasBlocks.size() < m.layerCount || t.atlasBlocks[l] >= m.blocks.size())
        throw Error("memory manager: internal error: a root atlas block is out of range");
      if (drawn(l)) rootBytes += m.blocks[t.atlasBlocks[l]].size;
    }
  if (rootBytes > options_.capacityBytes)
    throw Error("memory manager: capacity " + std::to_string(options_.capacityBytes) + " bytes cannot hold the root atlases (" +
                std::to_string(rootBytes) + " bytes), which stay in memory (thesis §4.6)");
  for (const Tree& t : m.trees)
    for (uint32_t l = 0; l < m.layerCount; ++l) {
      const uint32_t b = t.atlasBlocks[l];
      if (!drawn(l) || state_[b].resident) continue;
      install(b, file_.readBlock(b));
      bytesResident_ += m.blocks[b].size;
      state_[b].pinned = true;
    }
  peak_ = bytesResident_;
  checkCapacity();
  if (options_.budget.kind == LoadBudget::Kind::Time) loader_ = std::thread([this] { loaderMain(); });
}

Residency::~Residency() {
  if (loader_.joinable()) {
    {
      std::lock_guard<std::mutex> lk(mu_);
      stop_ = true;
    }
    cv_.notify_all();
    loader_.join();
  }
}

std::span<const uint8_t> Residency::data(uint32_t block) const {
  const BlockState& s = state_[block];
  if (!s.resident) return {};
  return s.bytes;
}

void Residency::install(uint32_t block, std::vector<uint8_t> bytes) {
  BlockState& s = state_[block];
  s.bytes = std::move(bytes);
  s.resident = true;
  s.inFlight = false;
  s.progress = 0;
  ++s.generation;
  ++blocksResident_;
}

void Residency::checkCapacity() const {
  if (bytesResident_ > options_.capacityBytes)
    throw Error("memory manager: internal error: " + std::to_string(bytesResident_) + " bytes in memory exceed the capacity of " +
                std::to_string(options_.capacityBytes));
}

// Removes blocks of lowest priority (never pinned, in-flight or ideal ones) until `bytes` more fit.
bool Residency::makeRoom(uint64_t bytes) {
  const MtaMeta& m = file_.meta();
  while (bytesResident_ + bytes > options_.capacityBytes) {
    int64_t victim = -1;
    for (uint32_t b = 0; b < state_.size(); ++b) {
      const BlockState& s = state_[b];
      if (!s.resident || s.pinned || s.ideal) continue;
      if (victim < 0 || morePressing(priority_[uint32_t(victim)], uint32_t(victim), priority_[b], b)) victim = b;
    }
    if (victim < 0) return false;
    BlockState& s = state_[uint32_t(victim)];
    s.resident = false;
    std::vector<uint8_t>().swap(s.bytes);
    bytesResident_ -= m.blocks[uint32_t(victim)].size;
    --blocksResident_;
    ++stats_.blocksEvicted;
    stats_.evictionOrder.push_back(uint32_t(victim));
  }
  return true;
}

const ResidencyFrameStats& Residency::update(const std::vector<BlockPriority>& given) {
  const MtaMeta& m = file_.meta();
  if (given.size() != state_.size())
    throw Error("memory manager: " + std::to_string(given.size()) + " priorities for " + std::to_string(state_.size()) + " blocks");
  stats_ = ResidencyFrameStats{};
  // Unused blocks are not reached by the usage traversal, so their distance is not measured: they keep
  // the distance and level of the last frame that reached them (the priority_ entry), which orders the
  // removal of resident Unused blocks as §4.6 does (descendants, then their ancestors).
  for (uint32_t b = 0; b < state_.size(); ++b) {
    if (given[b].usage != Usage::Unused) priority_[b] = given[b];
    else priority_[b].usage = Usage::Unused;
  }
  const std::vector<BlockPriority>& priority = priority_;

  // The ideal block set: Needed, Culled and Parent needed blocks by priority, cut to the capacity. The
  // pinned root atlases occupy their share whatever their category.
  std::vector<uint32_t> candidates;
  uint64_t used = 0;
  for (uint32_t b = 0; b < state_.size(); ++b) {
    state_[b].ideal = false;
    if (state_[b].pinned) used += m.blocks[b].size;
    else if (priority[b].usage != Usage::Unused) candidates.push_back(b);
  }
  std::sort(candidates.begin(), candidates.end(),
            [&](uint32_t a, uint32_t b) { return morePressing(priority[a], a, priority[b], b); });
  std::vector<uint32_t> ideal;
  for (size_t i = 0; i < candidates.size(); ++i) {
    const uint32_t b = candidates[i];
    if (used + m.blocks[b].size > options_.capacityBytes) {
      stats_.idealBlocksCut = candidates.size() - i;
      break;
    }
    used += m.blocks[b].size;
    state_[b].ideal = true;
    ideal.push_back(b);
  }
  stats_.idealBlocks = ideal.size();
  stats_.idealBytes = used;

  // A partially read block that left the ideal set is abandoned and its reservation released.
  for (uint32_t b : queue_) {
    BlockState& s = state_[b];
    if (!s.ideal && s.progress > 0) {
      bytesResident_ -= m.blocks[b].size;
      s.progress = 0;
      ++stats_.loadsCancelled;
    }
  }
  if (options_.budget.kind == LoadBudget::Kind::Time) cancelTimed();
  std::erase_if(queue_, [&](uint32_t b) {
    const bool drop = !state_[b].ideal || state_[b].resident;
    if (drop) state_[b].queued = false;
    return drop;
  });
  for (uint32_t b : ideal) {
    if (queue_.size() >= options_.maxQueue) break;
    BlockState& s = state_[b];
    if (s.resident || s.queued || s.inFlight) continue;
    s.queued = true;
    queue_.push_back(b);
  }
  // A priority queue (§4.6): priorities change with the camera, so the order is rebuilt every frame.
  std::sort(queue_.begin(), queue_.end(), [&](uint32_t a, uint32_t b) { return morePressing(priority[a], a, priority[b], b); });

  if (options_.budget.kind == LoadBudget::Kind::Time) serveTimed();
  else serveDeterministic();

  stats_.queueLength = queue_.size();
  for (uint32_t b = 0; b < state_.size(); ++b)
    if (priority[b].usage == Usage::Needed && !state_[b].resident) ++stats_.neededMissing;
  peak_ = std::max(peak_, bytesResident_);
  checkCapacity();
  return stats_;
}

void Residency::serveDeterministic() {
  const MtaMeta& m = file_.meta();
  uint64_t remaining = options_.budget.perFrame;
  while (!queue_.empty() && remaining > 0) {
    const uint32_t b = queue_.front();
    BlockState& s = state_[b];
    const uint64_t size = m.blocks[b].size;
    if (s.progress == 0) {
      // Reserve the whole block when its loading starts, so a block half read still counts (§4.6: the
      // summed size of the blocks in memory never exceeds k).
      if (!makeRoom(size)) throw Error("memory manager: internal error: no block can be removed to load block " + std::to_string(b));
      bytesResident_ += size;
    }
    uint64_t take = size - s.progress;
    if (options_.budget.kind == LoadBudget::Kind::Bytes) take = std::min(take, remaining);
    s.progress += take;
    remaining = options_.budget.kind == LoadBudget::Kind::Bytes ? remaining - take : remaining - 1;
    if (s.progress < size) break;  // continued next frame
    install(b, file_.readBlock(b));
    s.queued = false;
    queue_.erase(queue_.begin());
    ++stats_.blocksLoaded;
    stats_.bytesLoaded += size;
    stats_.loadOrder.push_back(b);
  }
}

// Blocks handed to the loader that left the ideal set: taken back if the loader has not started them (their
// reservation released now), marked to be dropped when their read ends otherwise (their bytes are in memory
// until then, so the reservation stays). A marked block that is ideal again is kept after all.
void Residency::cancelTimed() {
  const MtaMeta& m = file_.meta();
  std::lock_guard<std::mutex> lk(mu_);
  std::erase_if(toLoad_, [&](uint32_t b) {
    BlockState& s = state_[b];
    if (s.ideal) return false;
    s.inFlight = false;
    bytesResident_ -= m.blocks[b].size;
    ++stats_.loadsCancelled;
    return true;
  });
  for (uint32_t b = 0; b < state_.size(); ++b) {
    BlockState& s = state_[b];
    if (!s.inFlight) continue;
    if (!s.ideal && !s.cancelled) ++stats_.loadsCancelled;
    s.cancelled = !s.ideal;
  }
}

void Residency::waitForLoader() {
  if (!loader_.joinable()) return;
  std::unique_lock<std::mutex> lk(mu_);
  cv_.wait(lk, [&] { return (toLoad_.empty() && !reading_) || !loaderError_.empty(); });
}

void Residency::serveTimed() {
  const MtaMeta& m = file_.meta();
  constexpr size_t kInFlight = 2;  // enough to keep one read going while another is installed
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double, std::milli>(options_.budget.slotMs);
  size_t inFlight = 0;
  for (const BlockState& s : state_) inFlight += s.inFlight ? 1 : 0;
  for (;;) {
    while (inFlight < kInFlight && !queue_.empty()) {
      const uint32_t b = queue_.front();
      if (!makeRoom(m.blocks[b].size)) break;
      bytesResident_ += m.blocks[b].size;
      queue_.erase(queue_.begin());
      state_[b].queued = false;
      state_[b].inFlight = true;
      ++inFlight;
      {
        std::lock_guard<std::mutex> lk(mu_);
        toLoad_.push_back(b);
      }
      cv_.notify_all();
    }
    std::vector<std::pair<uint32_t, std::vector<uint8_t>>> done;
    {
      std::unique_lock<std::mutex> lk(mu_);
      cv_.wait_until(lk, deadline, [&] { return !loaded_.empty() || !loaderError_.empty() || inFlight == 0; });
      if (!loaderError_.empty()) throw Error(loaderError_);
      done.swap(loaded_);
    }
    for (auto& [b, bytes] : done) {
      --inFlight;
      if (state_[b].cancelled) {  // left the ideal set while it was read
        BlockState& s = state_[b];
        s.cancelled = s.inFlight = false;
        bytesResident_ -= m.blocks[b].size;
        continue;
      }
      install(b, std::move(bytes));
      ++stats_.blocksLoaded;
      stats_.bytesLoaded += m.blocks[b].size;
      stats_.loadOrder.push_back(b);
    }
    if (std::chrono::steady_clock::now() >= deadline || (inFlight == 0 && queue_.empty())) break;
  }
}

void Residency::loaderMain() {
  for (;;) {
    uint32_t b = 0;
    {
      std::unique_lock<std::mutex> lk(mu_);
      cv_.wait(lk, [&] { return stop_ || !toLoad_.empty(); });
      if (stop_) return;
      b = toLoad_.front();
      toLoad_.pop_front();
      reading_ = true;
    }
    try {
      std::vector<uint8_t> bytes = options_.blockReader ? options_.blockReader(b) : file_.readBlock(b);
      std::lock_guard<std::mutex> lk(mu_);
      loaded_.emplace_back(b, std::move(bytes));
      reading_ = false;
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lk(mu_);
      loaderError_ = e.what();
      reading_ = false;
    }
    cv_.notify_all();
  }
}

}  // namespace tessera::mta
