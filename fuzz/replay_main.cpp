// The replay driver: a main() for a fuzz target's LLVMFuzzerTestOneInput, so that the inputs kept in the
// repository run in every build (Release and ASan, gcc, no libFuzzer) as the ctest `fuzz_replay.<target>`.
//
// Usage: fuzz_replay_<target> PATH...   Each PATH is a file or a directory (searched recursively); the
// files are replayed in byte order of their paths, each through one call of LLVMFuzzerTestOneInput.
// Exit status: 0 when every input returned; a crash, an abort (a property the target checks) or an escaping
// exception ends the process, naming the input on stderr first. A PATH that does not exist or holds no file
// is an error (exit 2), so a misspelt corpus directory cannot pass silently.
// Does not implement: fuzzing, timeouts or memory limits (ctest's TIMEOUT bounds the whole run).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s FILE|DIR...\n", argv[0]);
    return 2;
  }
  std::vector<fs::path> files;
  for (int i = 1; i < argc; ++i) {
    const fs::path p(argv[i]);
    std::error_code ec;
    const size_t before = files.size();
    if (fs::is_regular_file(p, ec)) {
      files.push_back(p);
    } else if (fs::is_directory(p, ec)) {
      for (fs::recursive_directory_iterator it(p, ec), end; !ec && it != end; it.increment(ec))
        if (it->is_regular_file(ec)) files.push_back(it->path());
    }
    if (files.size() == before) {
      std::fprintf(stderr, "%s: %s: no such file, or a directory without files\n", argv[0], argv[i]);
      return 2;
    }
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& f : files) {
    std::ifstream in(f, std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "%s: cannot read %s\n", argv[0], f.c_str());
      return 2;
    }
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // Named before the call: if the input crashes the process, this is the last line on stderr.
    std::fprintf(stderr, "replay %s (%zu bytes)\n", f.c_str(), bytes.size());
    // libFuzzer never passes a null pointer, not even for an empty input; neither do we.
    static const uint8_t kEmpty = 0;
    LLVMFuzzerTestOneInput(bytes.empty() ? &kEmpty : bytes.data(), bytes.size());
  }
  std::printf("%s: %zu input(s) replayed\n", argv[0], files.size());
  return 0;
}
