// `tessera crosscheck --stability`: the GL side rendered again under other conditions, each in a
// child process (llvmpipe reads LP_NUM_THREADS etc. once per process, gl/gl_backend.h), by spawning
// this executable (/proc/self/exe) with the hidden subcommand `gl-dump`, which renders a frame (or a
// prefix of it) on GL and writes the raw presented images to a directory.
//
// Implements: the child side (`gl-dump`) and the parent side (a verify::StabilityRenderer that runs
// one child per call). Does not implement: the comparison and bisection (verify/stability.h).
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "base/resource_limits.h"
#include "gl/gl_backend.h"
#include "raster/command_list.h"

namespace tessera::cli {

// Registers the hidden `gl-dump` subcommand.
void addGlDumpCommand(CLI::App& app);

// Runs verify::checkStability for `frame` (a scene name or .tframe path, loaded by the children the
// same way) and returns its JSON. `pixelsPerImage` as verify::checkStability takes it. Every child uses
// `glBase`'s driver, GL path and EGL platform; the conditions set the rest.
nlohmann::json runStability(const std::string& frame, const std::string& size, const CommandList& list,
                            const std::vector<size_t>& pixelsPerImage, const ResourceLimits& limits,
                            const gl::GlOptions& glBase);

}  // namespace tessera::cli
