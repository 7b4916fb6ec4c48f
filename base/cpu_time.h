// CPU time of the whole process (every thread: the oracle's workers, llvmpipe's rasterizer threads),
// for benchmarks that report CPU time next to wall time (docs/bench.md).
//
// Implements: processCpuMs(), getrusage(RUSAGE_SELF) user + system time in milliseconds.
// Does not implement: per-thread times, or any use in a rendered value (timing never changes a byte).
#pragma once

#include <sys/resource.h>

namespace tessera {

inline double processCpuMs() {
  rusage u{};
  if (getrusage(RUSAGE_SELF, &u) != 0) return 0.0;
  const auto ms = [](const timeval& t) { return double(t.tv_sec) * 1e3 + double(t.tv_usec) * 1e-3; };
  return ms(u.ru_utime) + ms(u.ru_stime);
}

}  // namespace tessera
