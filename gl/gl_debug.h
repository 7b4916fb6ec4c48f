// GL error reporting for the backend's debug mode: glGetError names and a KHR_debug message log
// (GL 4.6 §20: debug output), so a failing command is reported with its index, the GL error and
// what the driver said about it.
// Internal to gl/.
#pragma once

#include <string>
#include <vector>

#include "gl/gl_api.h"

namespace tessera::gl {

const char* glErrorName(GLenum e);

// Collects KHR_debug messages of the current context while installed. Only errors and
// high/medium-severity messages are kept (llvmpipe also sends informational shader-compile notes).
class DebugLog {
 public:
  // Installs the callback with synchronous output, so a message arrives inside the call that
  // caused it. Call with the owning context current.
  void install();
  void uninstall();
  // Returns and clears the collected messages, joined with "; ".
  std::string take();

 private:
  static void APIENTRY callback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                const GLchar* message, const void* user);
  std::vector<std::string> messages_;
  bool installed_ = false;
};

// Drains the GL error queue; returns the names of every pending error joined with ", ", or "".
std::string drainErrors();

}  // namespace tessera::gl
