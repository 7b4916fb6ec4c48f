// tessera: the command-line front end of the oracle.
#include <cstdio>
#include <exception>

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
  tessera::cli::addCityCommand(app);
  tessera::cli::addMtaCommands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const tessera::Error& e) {
    std::fprintf(stderr, "tessera: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tessera: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
