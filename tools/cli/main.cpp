// tessera: the command-line front end of the oracle.
//
// Exit status: 0 success (and --help); 1 a check that ran and found problems (validate, crosscheck,
// visibility, golden check; compare uses idiff's 1..4); 2 bad input of any kind: a command line CLI11
// refuses, an option out of its range, a file that cannot be read or written, a frame or model
// that fails validation; 3 an internal error (a bug: please report it); 130 / 143 interrupted
// (base/atomic_file.h).
#include <cstdio>
#include <exception>
#include <filesystem>

#include "base/error.h"
#include "tools/cli/commands.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Tessera: a deterministic, tile-based CPU rasterizer used as an oracle for OpenGL.\n"
      "Frames are recorded command lists; every image is bit-reproducible for any thread count.\n"
      "Run `tessera <command> --help` for a command's options."};
  app.require_subcommand(1);
  tessera::cli::addRenderCommands(app);
  tessera::cli::addDemoCommand(app);
  tessera::cli::addGoldenCommands(app);
  tessera::cli::addVerifyCommands(app);
  tessera::cli::addMutantsCommand(app);
  tessera::cli::addCityCommand(app);
  tessera::cli::addMtaCommands(app);
  tessera::cli::addTabCommands(app);
  tessera::cli::addRttaCommands(app);
  tessera::cli::addSuiteCommands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // a command's own verdict (exit 1, compare's 1..4), already reported
  } catch (const CLI::ParseError& e) {
    // CLI11 prints its message (or the help, for --help, whose code is 0); every refusal is bad input.
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const tessera::Error& e) {
    std::fprintf(stderr, "tessera: error: %s\n", e.what());
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    // The safety net behind every output path: a path the user gave that the file system refuses
    // (a file where a directory is needed, no permission, ...) is bad input, not a bug.
    const std::string path = e.path1().empty() ? std::string() : e.path1().string() + ": ";
    std::fprintf(stderr, "tessera: error: %s%s\n", path.c_str(), e.code().message().c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tessera: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
