#include "tools/cli/suite_run.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/error.h"

namespace tessera::cli::suite {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

volatile sig_atomic_t gStopSignal = 0;
extern "C" void onStopSignal(int sig) { gStopSignal = sig; }

struct Slot {
  size_t ci = 0;  // position in `cases`
  int attempt = 1;
  size_t step = 0;
  pid_t pid = -1;
  Clock::time_point caseStart, attemptStart;
  bool timedOut = false;
  std::string firstExit;    // how attempt 1 ended, when it failed
  std::string firstStatus;  // its status
  std::string stdoutPath, stderrPath;
};

std::string readHead(const std::string& path, size_t limit) {
  std::ifstream in(path, std::ios::binary);
  std::string s(limit, '\0');
  in.read(s.data(), std::streamsize(limit));
  s.resize(size_t(in.gcount()));
  return s;
}

std::string readTail(const std::string& path, size_t limit) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return "";
  const std::streamoff size = in.tellg();
  const std::streamoff from = size > std::streamoff(limit) ? size - std::streamoff(limit) : 0;
  in.seekg(from);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string substitute(std::string arg, const std::string& out, const std::string& repo) {
  for (const auto& [key, value] : {std::pair<std::string, std::string>{"{out}", out}, {"{repo}", repo}}) {
    for (size_t p = arg.find(key); p != std::string::npos; p = arg.find(key, p + value.size()))
      arg.replace(p, key.size(), value);
  }
  return arg;
}

pid_t spawn(const std::string& exe, const std::vector<std::string>& args, const std::string& out,
            const std::string& err, uint64_t memoryBytes) {
  const int outFd = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const int errFd = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const int inFd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  if (outFd < 0 || errFd < 0 || inFd < 0) {
    const std::string why = std::strerror(errno);
    for (int fd : {outFd, errFd, inFd})
      if (fd >= 0) ::close(fd);
    throw Error(out + ": cannot create the case's log: " + why);
  }
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(exe.c_str()));
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    // Only async-signal-safe calls until exec.
    ::setpgid(0, 0);
    if (memoryBytes) {
      const struct rlimit lim { rlim_t(memoryBytes), rlim_t(memoryBytes) };
      ::setrlimit(RLIMIT_AS, &lim);
    }
    ::dup2(inFd, 0), ::dup2(outFd, 1), ::dup2(errFd, 2);
    ::signal(SIGINT, SIG_DFL), ::signal(SIGTERM, SIG_DFL);
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  const int forkErrno = errno;
  ::close(outFd), ::close(errFd), ::close(inFd);
  if (pid < 0) throw Error(std::string("suite: cannot start a case process: ") + std::strerror(forkErrno));
  ::setpgid(pid, pid);  // also here, so that a kill of the group cannot come before the child's own call
  return pid;
}

}  // namespace

std::vector<CaseResult> runCases(const std::vector<SuiteCase>& cases, const RunOptions& o) {
  std::error_code ec;
  const std::string exe = fs::read_symlink("/proc/self/exe", ec).string();
  if (ec) throw Error("suite: cannot find the running executable (/proc/self/exe): " + ec.message());
  const std::string repo = repoRoot();
  const std::string outAbs = fs::absolute(o.outDir).lexically_normal().string();
  std::vector<CaseResult> results(cases.size());
  std::vector<Slot> running;
  size_t next = 0, done = 0;

  gStopSignal = 0;
  struct sigaction sa {
  }, oldInt{}, oldTerm{};
  sa.sa_handler = onStopSignal;
  sigemptyset(&sa.sa_mask);
  ::sigaction(SIGINT, &sa, &oldInt);
  ::sigaction(SIGTERM, &sa, &oldTerm);

  auto caseDir = [&](const SuiteCase& c) { return outAbs + "/cases/" + c.name; };
  auto startStep = [&](Slot& s) {
    const SuiteCase& c = cases[s.ci];
    const std::string dir = caseDir(c);
    const std::string base = fmt::format("{}/attempt{}.step{}", dir, s.attempt, s.step + 1);
    s.stdoutPath = base + ".stdout.txt", s.stderrPath = base + ".stderr.txt";
    std::vector<std::string> args;
    for (const std::string& a : c.steps[s.step]) args.push_back(substitute(a, dir, repo));
    s.timedOut = false;
    s.pid = spawn(exe, args, s.stdoutPath, s.stderrPath, c.memoryBytes);
  };
  auto startCase = [&](size_t ci) {
    const SuiteCase& c = cases[ci];
    const std::string dir = caseDir(c);
    fs::remove_all(dir, ec);  // a previous run's logs and state must not leak into this one
    fs::create_directories(dir, ec);
    if (ec) throw Error(dir + ": cannot create the case's directory: " + ec.message());
    Slot s;
    s.ci = ci;
    s.caseStart = s.attemptStart = Clock::now();
    startStep(s);
    running.push_back(s);
  };
  auto killAll = [&] {
    for (Slot& s : running) ::kill(-s.pid, SIGKILL), ::kill(s.pid, SIGKILL);
    for (Slot& s : running) ::waitpid(s.pid, nullptr, 0);
  };

  try {
    while (next < cases.size() || !running.empty()) {
      if (gStopSignal) {
        const int sig = gStopSignal;
        killAll();
        std::fprintf(stderr, "suite: interrupted (signal %d): stopped %zu running cases\n", sig, running.size());
        ::sigaction(SIGINT, &oldInt, nullptr), ::sigaction(SIGTERM, &oldTerm, nullptr);
        ::signal(sig, SIG_DFL);
        ::raise(sig);
        std::_Exit(128 + sig);
      }
      while (running.size() < size_t(o.jobs) && next < cases.size()) startCase(next++);
      int status = 0;
      const pid_t pid = ::waitpid(-1, &status, WNOHANG);
      if (pid <= 0) {
        const Clock::time_point now = Clock::now();
        for (Slot& s : running) {
          const double t = std::chrono::duration<double>(now - s.attemptStart).count();
          if (!s.timedOut && t > cases[s.ci].timeoutSeconds) {
            s.timedOut = true;
            ::kill(-s.pid, SIGKILL), ::kill(s.pid, SIGKILL);
          }
        }
        struct timespec ts {
          0, 5'000'000
        };
        ::nanosleep(&ts, nullptr);
        continue;
      }
      auto it = std::find_if(running.begin(), running.end(), [&](const Slot& s) { return s.pid == pid; });
      if (it == running.end()) continue;  // not ours (cannot happen: the runner starts no other children)
      Slot& s = *it;
      const SuiteCase& c = cases[s.ci];
      std::string exitText, status1, detail;
      if (s.timedOut) {
        status1 = "timeout", exitText = fmt::format("timeout after {} s", c.timeoutSeconds);
      } else if (WIFSIGNALED(status)) {
        const int sig = WTERMSIG(status);
        status1 = "crash", exitText = fmt::format("signal {} ({})", sig, sigabbrev_np(sig) ? sigabbrev_np(sig) : "?");
        if (sig == SIGKILL) detail = "killed by SIGKILL from outside (the kernel's OOM killer?)";
      } else {
        const int code = WEXITSTATUS(status);
        exitText = fmt::format("exit {}", code);
        status1 = code == 0 ? "pass" : code == 3 ? "crash" : "fail";
        if (code == 3) detail = "internal error";
        if (code == 127) detail = "the executable could not be started";
      }
      if (status1 == "crash") {
        const std::string tail = readTail(s.stderrPath, 4096);
        if (tail.find("bad_alloc") != std::string::npos || tail.find("out of memory") != std::string::npos)
          detail = "out of memory";
      }
      if (status1 == "pass" && s.step + 1 < c.steps.size()) {
        ++s.step;
        startStep(s);
        continue;
      }
      const BaselineEntry* be = o.baseline ? o.baseline->match(c.name, o.glDriver) : nullptr;
      if (status1 != "pass" && s.attempt == 1 && !(be && baselineExpects(*be, status1))) {
        // One retry, from the first step, with fresh logs (attempt2.*) in the same directory.
        if (o.progress)
          std::fprintf(stderr, "suite: %s: %s (%s), retrying once\n", c.name.c_str(), status1.c_str(),
                       exitText.c_str());
        s.firstExit = exitText, s.firstStatus = status1;
        s.attempt = 2, s.step = 0, s.attemptStart = Clock::now();
        startStep(s);
        continue;
      }
      CaseResult r;
      r.index = c.index, r.name = c.name, r.kind = c.kind, r.attempts = s.attempt, r.exit = exitText, r.detail = detail;
      r.durationSeconds = std::chrono::duration<double>(Clock::now() - s.caseStart).count();
      r.firstAttempt = s.firstExit;
      r.knownFlake = o.flakes && o.flakes->matches(c.name);
      if (be) r.baselineId = be->id;
      if (status1 == "pass")
        r.status = s.attempt == 2 ? "flake" : be ? "unexpected-pass" : "pass";
      else
        r.status = be && baselineExpects(*be, status1) ? "expected-fail" : status1;
      r.figures = keyFigures(readHead(s.stdoutPath, size_t(8) << 20));
      const std::string dir = caseDir(c);
      // The case's report: a command's HTML report (crosscheck, compare, mutants), else its stats JSON (render,
      // replay).
      for (const char* f : {"/report/index.html", "/stats.json"})
        if (r.report.empty() && fs::exists(dir + f, ec)) r.report = "cases/" + c.name + f;
      r.log = fs::relative(s.stdoutPath, outAbs, ec).string();
      results[s.ci] = r;
      running.erase(it);
      ++done;
      if (o.progress)
        std::fprintf(stderr, "[%zu/%zu] %-15s %s (%.1f s)\n", done, cases.size(), r.status.c_str(), r.name.c_str(),
                     r.durationSeconds);
    }
  } catch (...) {
    killAll();
    ::sigaction(SIGINT, &oldInt, nullptr), ::sigaction(SIGTERM, &oldTerm, nullptr);
    throw;
  }
  ::sigaction(SIGINT, &oldInt, nullptr), ::sigaction(SIGTERM, &oldTerm, nullptr);
  return results;
}

}  // namespace tessera::cli::suite
