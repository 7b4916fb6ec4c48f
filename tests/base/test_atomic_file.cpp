// AtomicFile: a reader sees the old file or the whole new one, never a part; temporaries vanish on
// SIGINT / SIGTERM (exit 130 / 143) and are removed by the next writer after a SIGKILL.
// The interruption tests fork a child that writes half of its output and then waits to be killed,
// so the kill always lands mid-write, whatever the machine's speed.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "base/atomic_file.h"
#include "base/error.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path dir;
  TempDir() {
    dir = fs::temp_directory_path() / ("tessera-atomic-" + std::to_string(::getpid()) + "-" +
                                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~TempDir() { fs::remove_all(dir); }
  std::string file(const std::string& name) const { return (dir / name).string(); }
};

std::string readAll(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Names in `dir` that contain ".tmp-".
std::vector<std::string> temporaries(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(".tmp-") != std::string::npos) out.push_back(e.path().filename().string());
  return out;
}

// Forks a child that opens an AtomicFile for `path`, writes `half` bytes, tells the parent through a
// pipe, and then waits forever. Returns the child's pid once the half-written temporary exists.
pid_t childWritingHalf(const std::string& path, size_t half) {
  int fds[2];
  if (::pipe(fds) != 0) return -1;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    AtomicFile f(path);
    f.write(std::string(half, 'n'));
    const char ready = 'r';
    (void)::write(fds[1], &ready, 1);
    for (;;) ::pause();
  }
  ::close(fds[1]);
  char c = 0;
  const ssize_t n = ::read(fds[0], &c, 1);
  ::close(fds[0]);
  return n == 1 ? pid : -1;
}

TEST(AtomicFile, ACommittedFileHasExactlyTheBytesWrittenAndNoTemporaryRemains) {
  TempDir t;
  const std::string path = t.file("out.bin");
  AtomicFile f(path);
  EXPECT_EQ(f.tempPath(), path + ".tmp-" + std::to_string(::getpid()));
  f.write(std::string("hello "));
  f.write(std::string("world"));
  const uint8_t header[2] = {'H', 'W'};
  f.writeAt(0, header);  // a header filled in last, as the paging file does
  EXPECT_FALSE(fs::exists(path)) << "the final name must not exist before commit()";
  f.commit();
  EXPECT_EQ(readAll(path), "HWllo world");
  EXPECT_TRUE(temporaries(t.dir).empty());
}

TEST(AtomicFile, AWriterDestroyedWithoutCommitLeavesTheOldFileAndNoTemporary) {
  TempDir t;
  const std::string path = t.file("out.txt");
  writeFileAtomically(path, std::string_view("old"));
  {
    AtomicFile f(path);
    f.write(std::string("new but unfinished"));
  }
  EXPECT_EQ(readAll(path), "old");
  EXPECT_TRUE(temporaries(t.dir).empty());
}

TEST(AtomicFile, AWriterByNameThatThrowsLeavesTheOldFileAndNoTemporary) {
  TempDir t;
  const std::string path = t.file("img.png");
  writeFileAtomically(path, std::string_view("old"));
  EXPECT_THROW(writeFileAtomically(path,
                                   [](const std::string& tmp) {
                                     std::ofstream(tmp) << "partial";
                                     throw Error("encoder failed");
                                   }),
               Error);
  EXPECT_EQ(readAll(path), "old");
  EXPECT_TRUE(temporaries(t.dir).empty());
}

TEST(AtomicFile, AMissingDirectoryIsAnErrorNamingThePath) {
  TempDir t;
  const std::string path = t.file("no/such/dir/out.txt");
  try {
    writeFileAtomically(path, std::string_view("x"));
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(AtomicFile, ADirectoryInTheWayIsAnErrorNamingThePath) {
  TempDir t;
  const std::string path = t.file("taken");
  fs::create_directories(path);
  try {
    writeFileAtomically(path, std::string_view("x"));
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": is a directory"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_directory(path));
}

void expectSignalRemovesTemporary(int sig, int expectedStatus) {
  // A process started in the background by a non-interactive shell inherits SIGINT as SIG_IGN, and
  // AtomicFile rightly leaves an ignored signal alone: the child would then pause for ever. Say so
  // instead of hanging (ctest resets every disposition to the default in the processes it starts).
  struct sigaction current{};
  ASSERT_EQ(::sigaction(sig, nullptr, &current), 0);
  ASSERT_FALSE(!(current.sa_flags & SA_SIGINFO) && current.sa_handler == SIG_IGN)
      << "signal " << sig << " is ignored in this test process (inherited from the shell that started it)";
  TempDir t;
  const std::string path = t.file("frame.tframe");
  writeFileAtomically(path, std::string_view("the old output"));
  const pid_t pid = childWritingHalf(path, 1 << 20);
  ASSERT_GT(pid, 0);
  ASSERT_EQ(temporaries(t.dir).size(), 1u) << "the child's half-written temporary must exist before the signal";
  ASSERT_EQ(::kill(pid, sig), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "the handler exits instead of dying by the signal";
  EXPECT_EQ(WEXITSTATUS(status), expectedStatus);
  EXPECT_TRUE(temporaries(t.dir).empty());
  EXPECT_EQ(readAll(path), "the old output");
}

TEST(AtomicFile, SigtermMidWriteRemovesTheTemporaryAndExitsWith143) { expectSignalRemovesTemporary(SIGTERM, 143); }

TEST(AtomicFile, SigintMidWriteRemovesTheTemporaryAndExitsWith130) { expectSignalRemovesTemporary(SIGINT, 130); }

TEST(AtomicFile, TheNextWriterRemovesTheTemporaryOfAProcessKilledWithSigkill) {
  TempDir t;
  const std::string path = t.file("tree.mta");
  writeFileAtomically(path, std::string_view("the old output"));
  const pid_t pid = childWritingHalf(path, 1 << 20);
  ASSERT_GT(pid, 0);
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);  // reaped: the pid no longer names a process
  ASSERT_TRUE(WIFSIGNALED(status));
  const std::vector<std::string> left = temporaries(t.dir);
  ASSERT_EQ(left.size(), 1u) << "SIGKILL cannot be caught: its temporary stays until the next writer";
  EXPECT_EQ(left[0], "tree.mta.tmp-" + std::to_string(pid));
  EXPECT_EQ(readAll(path), "the old output");
  writeFileAtomically(path, std::string_view("the new output"));
  EXPECT_TRUE(temporaries(t.dir).empty());
  EXPECT_EQ(readAll(path), "the new output");
}

TEST(AtomicFile, ATemporaryOfALiveProcessIsNeverRemoved) {
  TempDir t;
  const std::string path = t.file("out.json");
  const pid_t pid = childWritingHalf(path, 100);  // alive until we kill it
  ASSERT_GT(pid, 0);
  EXPECT_EQ(removeStaleTemporaries(path), 0u);
  writeFileAtomically(path, std::string_view("{}"));
  EXPECT_EQ(temporaries(t.dir).size(), 1u) << "the live child's temporary must survive our write";
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  EXPECT_EQ(removeStaleTemporaries(path), 1u);
  EXPECT_TRUE(temporaries(t.dir).empty());
}

TEST(AtomicFile, OnlyTemporariesOfThatOutputAreConsidered) {
  TempDir t;
  const std::string path = t.file("a.png");
  // A dead pid: a child that exited and was reaped.
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ::waitpid(dead, nullptr, 0);
  const std::string d = std::to_string(dead);
  for (const std::string& name : std::vector<std::string>{"a.png.tmp-" + d, "b.png.tmp-" + d, "a.png.tmp-" + d + "x", "a.png.tmp-"})
    std::ofstream(t.file(name)) << "junk";
  EXPECT_EQ(removeStaleTemporaries(path), 1u);
  EXPECT_FALSE(fs::exists(t.file("a.png.tmp-" + d)));
  EXPECT_TRUE(fs::exists(t.file("b.png.tmp-" + d))) << "another output's temporary is not ours to judge";
  EXPECT_TRUE(fs::exists(t.file("a.png.tmp-" + d + "x"))) << "not a pid suffix";
  EXPECT_TRUE(fs::exists(t.file("a.png.tmp-")));
}

TEST(AtomicFile, AScratchFolderOfADeadProcessIsRemovedWithItsContentsAndALiveOnesIsKept) {
  TempDir t;
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ::waitpid(dead, nullptr, 0);
  const std::string gone = t.file("scratch-" + std::to_string(dead)), mine = t.file("scratch-" + std::to_string(::getpid()));
  fs::create_directories(gone + "/sub");
  std::ofstream(gone + "/sub/f") << "junk";
  fs::create_directories(mine);
  EXPECT_EQ(removeEntriesOfDeadProcesses(t.dir.string(), "scratch-"), 1u);
  EXPECT_FALSE(fs::exists(gone));
  EXPECT_TRUE(fs::exists(mine)) << "this process is alive";
}

}  // namespace
}  // namespace tessera
