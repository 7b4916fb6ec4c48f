// The options of every `tessera` command that creates a GL backend (crosscheck, bench crosscheck,
// demo): which GL implementation, which GL path and which EGL platform (docs/gl-backend.md,
// "Drivers", "The 3.3 core path", "EGL setup").
//
// Implements: --gl-driver llvmpipe|softpipe|zink, --gl-version 45|33 and --egl-platform
// surfaceless|device, each checked while the command line is parsed (exit 2 on any other value) and
// written into gl::GlOptions. Does not implement: the checks that need a context (the backend refuses a
// driver the context does not report, naming both).
#pragma once

#include <CLI/CLI.hpp>

#include "gl/gl_backend.h"

namespace tessera::cli {

inline void addGlBackendOptions(CLI::App* cmd, gl::GlOptions& o) {
  cmd->add_option("--gl-driver", o.driver,
                  "Mesa Gallium driver: llvmpipe (the default), softpipe or zink (GALLIUM_DRIVER); an error if the "
                  "context reports another")
      ->check(CLI::IsMember({"llvmpipe", "softpipe", "zink"}));
  cmd->add_option("--gl-version", o.glVersion,
                  "GL path: 45 (OpenGL 4.5 core, DSA) or 33 (OpenGL 3.3 core, bind points); default: 4.5, else 3.3 "
                  "when the driver offers no 4.5")
      ->check(CLI::IsMember({45, 33}));
  cmd->add_option("--egl-platform", o.eglPlatform,
                  "EGL platform: surfaceless (Mesa) or device (EGL_EXT_platform_device, for NVIDIA / AMD / Intel "
                  "drivers); default: surfaceless, else device")
      ->check(CLI::IsMember({"surfaceless", "device"}));
}

}  // namespace tessera::cli
