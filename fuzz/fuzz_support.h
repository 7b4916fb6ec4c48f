// What every fuzz target of fuzz/ shares: a per-process scratch directory for the readers that take a
// path, the rule for which exceptions count as a finding, and a way to stop with a message when a
// property (a round trip) is broken.
//
// Implements: scratchDir() (created on first use under /dev/shm, else $TMPDIR, else /tmp, named after the
// process id, removed at exit; directories left behind by processes that died, e.g. a crashing libFuzzer
// child, are removed by the next process that starts), writeScratch() (the same file name is rewritten
// for every input, through base/atomic_file.h like every other output), propertyViolated(), and note()
// (with TESSERA_FUZZ_VERBOSE=1 in the environment, what became of each input: the Error that rejected it,
// or what was accepted; silent otherwise, as libFuzzer wants), and DescriptorCheck: an input must not leave
// a file descriptor open (a reader that throws must still close what it opened), checked around every input
// as LeakSanitizer checks memory. TESSERA_FUZZ_ALLOW_FD_LEAKS=1 turns that check off, for fuzzing a target
// past a known descriptor leak until it is fixed (fuzz/crashers/README.md lists such leaks).
// Does not implement: the targets themselves (one .cpp each) or the replay driver (replay_main.cpp).
//
// The exception rule: loaders and decoders promise a tessera::Error naming the file and the reason for
// any hostile input. A target therefore catches tessera::Error only; anything else (std::bad_alloc,
// std::length_error, a JSON library exception, a crash) escapes to libFuzzer and is reported as a
// finding, and the replay test fails on it.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include "base/atomic_file.h"

namespace tessera::fuzz {

namespace detail {

inline constexpr const char* kScratchPrefix = "tessera-fuzz-";

inline std::filesystem::path scratchRoot() {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory("/dev/shm", ec) && ::access("/dev/shm", W_OK) == 0) return "/dev/shm";
  if (const char* t = std::getenv("TMPDIR"); t && *t) return t;
  return "/tmp";
}

struct Scratch {
  std::filesystem::path dir;
  Scratch() {
    namespace fs = std::filesystem;
    const fs::path root = scratchRoot();
    // A crash skips the atexit clean-up: remove the folders of processes that are gone.
    removeEntriesOfDeadProcesses(root.string(), kScratchPrefix);
    dir = root / (kScratchPrefix + std::to_string(::getpid()));
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) {
      std::fprintf(stderr, "fuzz: cannot create the scratch directory %s: %s\n", dir.c_str(), ec.message().c_str());
      std::abort();
    }
  }
  ~Scratch() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
};

}  // namespace detail

// The process's scratch directory (created on first use, removed at exit).
inline const std::filesystem::path& scratchDir() {
  static detail::Scratch s;
  return s.dir;
}

// Writes `bytes` to scratchDir()/name (replacing the previous input of that name) and returns the path.
inline std::string writeScratch(const std::string& name, std::span<const uint8_t> bytes) {
  const std::string path = (scratchDir() / name).string();
  writeFileAtomically(path, bytes);
  return path;
}
inline std::string writeScratch(const std::string& name, std::string_view text) {
  return writeScratch(name, std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

// A broken property (a round trip that does not give back the same bits) is a finding like a crash:
// say which, then abort so that libFuzzer saves the input and the replay test fails.
[[noreturn]] inline void propertyViolated(std::string_view target, std::string_view what) {
  std::fprintf(stderr, "fuzz %.*s: property violated: %.*s\n", int(target.size()), target.data(), int(what.size()),
               what.data());
  std::abort();
}

inline bool envFlag(const char* name) {
  const char* e = std::getenv(name);
  return e && *e && std::string_view(e) != "0";
}

// Compares the lowest free descriptor number (what open() returns next) before and after one input: if a
// descriptor the input opened is still open, the number has moved up.
class DescriptorCheck {
 public:
  DescriptorCheck() : before_(lowestFree()) {}
  void expectNoLeak(std::string_view target) const {
    static const bool allowed = envFlag("TESSERA_FUZZ_ALLOW_FD_LEAKS");
    if (allowed || lowestFree() <= before_) return;
    propertyViolated(target, "the input left file descriptor " + std::to_string(before_) +
                                 " open (a reader that fails must still close what it opened)");
  }

 private:
  static int lowestFree() {
    const int fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
    if (fd >= 0) ::close(fd);
    return fd;
  }
  int before_;
};

inline bool verbose() {
  static const bool v = envFlag("TESSERA_FUZZ_VERBOSE");
  return v;
}

// One line on stderr when verbose(): "<target>: <what>".
inline void note(std::string_view target, std::string_view what) {
  if (verbose()) std::fprintf(stderr, "%.*s: %.*s\n", int(target.size()), target.data(), int(what.size()), what.data());
}

}  // namespace tessera::fuzz
