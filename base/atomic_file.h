// Atomic output files: a reader never sees a half-written file under the final name.
//
// Implements: the one way every output of the project is written. Bytes go to a temporary
// `<path>.tmp-<pid>` beside the final file, which is flushed, fsynced and renamed over `path` by
// commit(); a writer that is destroyed without commit() (an exception, an early return) removes its
// temporary. Three ways a temporary could still outlive its writer are handled:
// - SIGINT / SIGTERM: while any AtomicFile is open, a handler removes every live temporary of the
//   process and exits with 128 + the signal number (130 / 143), as a shell reports a killed job.
//   The handler is installed on first use, only where the signal's disposition is the default one:
//   a program that set its own handler, or inherited SIG_IGN (nohup), keeps it.
// - SIGKILL, a crash or power loss: the next writer of the same `path` finds `<name>.tmp-<pid>`
//   temporaries beside it whose process no longer exists (kill(pid, 0) fails with ESRCH) and removes
//   them before it starts. A temporary of a live process is never touched, whoever owns it.
// - Two writers of one path in one process would share the temporary; callers never do that.
// Does not implement: locking between processes that write the same path at the same time (the last
// rename wins, and each renamed file is whole), or stale detection across machines (a pid on an NFS
// share may belong to another host: such temporaries are left alone unless that pid is gone here).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>

namespace tessera {

class AtomicFile {
 public:
  // Removes stale temporaries of `path` (see above) and creates the temporary. Throws Error naming
  // `path` when the temporary cannot be created (missing directory, no permission, a directory in
  // the way).
  explicit AtomicFile(std::string path);
  // Without commit(): closes and removes the temporary. Never throws.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& path() const { return path_; }
  // The temporary's name, for writers that must open a file by name themselves (OpenImageIO): they
  // write it completely, close it, and the caller then calls commit().
  const std::string& tempPath() const { return tmp_; }

  // Appends bytes at the end of what was written so far. Throws Error naming `path`.
  void write(std::span<const uint8_t> bytes);
  void write(std::string_view text);
  // Writes bytes at an absolute offset (a header filled in last). Does not move the append position
  // backwards. Throws Error naming `path` and the offset.
  void writeAt(uint64_t offset, std::span<const uint8_t> bytes);

  // Flushes and fsyncs the temporary, renames it over `path` and fsyncs the directory. Throws Error
  // naming `path` on failure, and the temporary is removed. Afterwards the object is inert.
  void commit();

 private:
  std::string path_, tmp_;
  int fd_ = -1;
  int slot_ = -1;  // index in the signal handler's table of live temporaries, or -1
  uint64_t end_ = 0;
  bool committed_ = false;
};

// The whole file at once.
void writeFileAtomically(const std::string& path, std::span<const uint8_t> bytes);
void writeFileAtomically(const std::string& path, std::string_view text);
// For a writer that needs a file name: `write(tempPath)` must create the whole file or throw.
void writeFileAtomically(const std::string& path, const std::function<void(const std::string& tempPath)>& write);

// Removes `<name>.tmp-<pid>` files beside `path` whose process is gone. Returns how many were removed.
// AtomicFile calls this itself; it is public for tests and for tools that clean a directory.
size_t removeStaleTemporaries(const std::string& path);

// Removes every entry `<prefix><pid>` of `directory` (a file, or a directory with its contents) whose
// process is gone, as above. Returns how many were removed. Also used for per-process scratch folders.
size_t removeEntriesOfDeadProcesses(const std::string& directory, const std::string& prefix);

}  // namespace tessera
