// Helpers of the suite tests: a scratch directory per test, writing files, and running `tessera`.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace tessera::cli::suite::test {

inline std::filesystem::path scratchRoot() {
  return std::filesystem::temp_directory_path() / ("tessera-suite-test-" + std::to_string(::getpid()));
}

// Removes this process's scratch root after the last test when every test passed, and keeps it for
// inspection when one failed: ctest runs each test in its own process, so without this every run
// left a directory per test in /tmp.
class ScratchCleanup : public ::testing::Environment {
 public:
  void TearDown() override {
    if (!::testing::UnitTest::GetInstance()->Passed()) return;
    std::error_code ec;
    std::filesystem::remove_all(scratchRoot(), ec);
  }
};
inline ::testing::Environment* const kScratchCleanup = ::testing::AddGlobalTestEnvironment(new ScratchCleanup);

inline std::string scratchDir(const std::string& name) {
  const std::filesystem::path d = scratchRoot() / name;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d.string();
}

inline void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;  // test input, not an output of the project
}

inline std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Run {
  int exitCode = -1;
  std::string out, err;
};

// Runs `tessera <args>` through the shell with stdout and stderr captured to files beside `dir`.
inline Run tessera(const std::string& args, const std::string& dir) {
  const std::string out = dir + ".stdout", err = dir + ".stderr";
  const std::string cmd = std::string("'") + TESSERA_BIN + "' " + args + " >'" + out + "' 2>'" + err + "'";
  const int st = std::system(cmd.c_str());
  Run r;
  r.exitCode = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  r.out = readText(out), r.err = readText(err);
  return r;
}

inline nlohmann::json readJson(const std::string& path) { return nlohmann::json::parse(readText(path)); }

}  // namespace tessera::cli::suite::test
