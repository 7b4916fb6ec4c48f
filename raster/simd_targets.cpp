#include "raster/simd_targets.h"

#include <hwy/detect_targets.h>
#include <hwy/targets.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdint>

#include "base/error.h"

namespace tessera::simd {
namespace {

// Off: "reference". Relaxed: the switch is flipped between frames, never while one renders.
std::atomic<bool> g_kernelsOn{true};

std::string lower(const char* s) {
  std::string r(s);
  for (char& c : r) c = char(std::tolower(static_cast<unsigned char>(c)));
  return r;
}

struct Compiled {
  int64_t bits;
  std::string name;
};

// The compiled targets this CPU runs, best first (Highway numbers better targets with lower bits).
// Computed before forceTarget() first mocks the CPU (it calls this first), so it is the real list.
const std::vector<Compiled>& compiled() {
  static const std::vector<Compiled> list = [] {
    std::vector<Compiled> v;
    for (int64_t bits : hwy::SupportedAndGeneratedTargets()) v.push_back({bits, lower(hwy::TargetName(bits))});
    return v;
  }();
  return list;
}

}  // namespace

std::vector<std::string> availableTargets() {
  std::vector<std::string> names;
  for (const Compiled& c : compiled()) names.push_back(c.name);
  names.push_back("reference");
  return names;
}

std::string activeTarget() {
  if (!kernelsOn()) return "reference";
  // The dispatch runs the best target the (possibly mocked) CPU supports among those compiled.
  const int64_t targets = hwy::SupportedTargets() & HWY_TARGETS;
  return targets == 0 ? "reference" : lower(hwy::TargetName(targets & -targets));
}

bool kernelsOn() { return g_kernelsOn.load(std::memory_order_relaxed); }

void forceTarget(const std::string& name) {
  const std::vector<Compiled>& list = compiled();
  if (name.empty() || name == "best" || name == "reference") {
    hwy::SetSupportedTargetsForTest(0);
    g_kernelsOn.store(name != "reference", std::memory_order_relaxed);
    return;
  }
  const auto it = std::find_if(list.begin(), list.end(), [&](const Compiled& c) { return c.name == name; });
  if (it == list.end()) {
    std::string names;
    for (const std::string& n : availableTargets()) names += (names.empty() ? "" : ", ") + n;
    throw Error("SIMD target '" + name + "' is not available in this build on this CPU; available: " + names +
                " (or best)");
  }
  hwy::SetSupportedTargetsForTest(it->bits);
  g_kernelsOn.store(true, std::memory_order_relaxed);
}

}  // namespace tessera::simd
