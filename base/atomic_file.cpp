#include "base/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "base/error.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

// The signal handler may only call async-signal-safe functions (POSIX.1-2017 §2.4.3): unlink and
// _exit are. So the live temporaries sit in a fixed table of plain character arrays, each guarded
// by an atomic state, instead of a std::set that the handler could catch in mid-rehash.
constexpr int kSlots = 256;
enum SlotState : int { kFree = 0, kFilling = 1, kLive = 2 };
struct Slot {
  std::atomic<int> state{kFree};
  char path[PATH_MAX];
};
Slot gSlots[kSlots];
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads these atomics");

extern "C" void removeTemporariesAndExit(int sig) {
  for (Slot& s : gSlots)
    if (s.state.load(std::memory_order_acquire) == kLive) ::unlink(s.path);
  ::_exit(128 + sig);
}

void installHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int sig : {SIGINT, SIGTERM}) {
      struct sigaction old{};
      if (::sigaction(sig, nullptr, &old) != 0) continue;
      // Respect a handler or SIG_IGN that someone else chose; only replace the default action.
      if (!(old.sa_flags & SA_SIGINFO) && old.sa_handler == SIG_DFL) {
        struct sigaction sa{};
        sa.sa_handler = removeTemporariesAndExit;
        sigemptyset(&sa.sa_mask);
        ::sigaction(sig, &sa, nullptr);
      }
    }
  });
}

int registerTemporary(const std::string& tmp) {
  if (tmp.size() >= PATH_MAX) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (gSlots[i].state.compare_exchange_strong(expected, kFilling, std::memory_order_acq_rel)) {
      std::memcpy(gSlots[i].path, tmp.c_str(), tmp.size() + 1);
      gSlots[i].state.store(kLive, std::memory_order_release);
      return i;
    }
  }
  return -1;  // table full: this temporary is left to the next run's stale check
}

void unregisterTemporary(int slot) {
  if (slot >= 0) gSlots[slot].state.store(kFree, std::memory_order_release);
}

[[noreturn]] void fail(const std::string& path, const std::string& what, int err) {
  throw Error(path + ": " + what + ": " + std::strerror(err));
}

std::string tempName(const std::string& path) { return path + ".tmp-" + std::to_string(::getpid()); }

}  // namespace

size_t removeEntriesOfDeadProcesses(const std::string& directory, const std::string& prefix) {
  std::error_code ec;
  fs::directory_iterator it(directory, ec);
  if (ec) return 0;  // the directory's problems are reported when something is created in it
  size_t removed = 0;
  for (; it != fs::directory_iterator(); it.increment(ec)) {
    if (ec) break;
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const long pid = std::stol(digits);
    if (pid <= 0 || pid == long(::getpid())) continue;
    // ESRCH: no such process. EPERM means it exists under another user: leave it.
    if (::kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue;
    std::error_code rec;
    if (fs::remove_all(it->path(), rec) > 0 && !rec) ++removed;
  }
  return removed;
}

size_t removeStaleTemporaries(const std::string& path) {
  const fs::path p(path);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  return removeEntriesOfDeadProcesses(dir.string(), p.filename().string() + ".tmp-");
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)), tmp_(tempName(path_)) {
  installHandlers();
  removeStaleTemporaries(path_);
  std::error_code ec;
  if (fs::is_directory(path_, ec)) throw Error(path_ + ": is a directory, cannot write a file there");
  // Register before creating, so a signal between open() and registration cannot leak the file.
  slot_ = registerTemporary(tmp_);
  fd_ = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    const int err = errno;
    unregisterTemporary(slot_);
    slot_ = -1;
    committed_ = true;  // nothing was created: never unlink a file of that name someone else owns
    fail(path_, "cannot create the temporary file '" + tmp_ + "'", err);
  }
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_) ::unlink(tmp_.c_str());
  unregisterTemporary(slot_);
}

void AtomicFile::writeAt(uint64_t offset, std::span<const uint8_t> bytes) {
  if (fd_ < 0) throw Error(path_ + ": write after commit");
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::pwrite(fd_, bytes.data() + done, bytes.size() - done, off_t(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(path_, "cannot write " + std::to_string(bytes.size()) + " bytes at byte " + std::to_string(offset) + " of '" + tmp_ + "'", n < 0 ? errno : EIO);
    done += size_t(n);
  }
  end_ = std::max(end_, offset + bytes.size());
}

void AtomicFile::write(std::span<const uint8_t> bytes) { writeAt(end_, bytes); }

void AtomicFile::write(std::string_view text) {
  write(std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

void AtomicFile::commit() {
  if (committed_) return;
  // A writer that wrote by name (tempPath()) may have replaced the file: reopen it to fsync it.
  if (fd_ < 0) throw Error(path_ + ": commit after a failed write");
  const int fd = fd_;
  fd_ = -1;
  struct stat st{};
  if (::fstat(fd, &st) == 0 && st.st_nlink == 0) {
    // Our descriptor lost its name: the named writer created a new file. fsync that one instead.
    ::close(fd);
    const int fd2 = ::open(tmp_.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd2 < 0) fail(path_, "the temporary file '" + tmp_ + "' is gone", errno);
    if (::fsync(fd2) != 0) {
      const int err = errno;
      ::close(fd2);
      fail(path_, "cannot fsync '" + tmp_ + "'", err);
    }
    ::close(fd2);
  } else {
    // fsync before rename: otherwise a crash can leave the final name pointing at an empty file.
    if (::fsync(fd) != 0) {
      const int err = errno;
      ::close(fd);
      fail(path_, "cannot fsync '" + tmp_ + "'", err);
    }
    if (::close(fd) != 0) fail(path_, "cannot close '" + tmp_ + "'", errno);
  }
  if (::rename(tmp_.c_str(), path_.c_str()) != 0) fail(path_, "cannot rename the temporary file '" + tmp_ + "' over it", errno);
  committed_ = true;
  unregisterTemporary(slot_);
  slot_ = -1;
  // Make the rename itself durable; failure here cannot un-write the file, so it is not an error.
  const fs::path dir = fs::path(path_).parent_path();
  const int dirFd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dirFd >= 0) {
    (void)::fsync(dirFd);
    ::close(dirFd);
  }
}

void writeFileAtomically(const std::string& path, std::span<const uint8_t> bytes) {
  AtomicFile f(path);
  f.write(bytes);
  f.commit();
}

void writeFileAtomically(const std::string& path, std::string_view text) {
  AtomicFile f(path);
  f.write(text);
  f.commit();
}

void writeFileAtomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  AtomicFile f(path);
  write(f.tempPath());
  f.commit();
}

}  // namespace tessera
