#include "gl/gl_debug.h"

namespace tessera::gl {

const char* glErrorName(GLenum e) {
  switch (e) {
    case GL_NO_ERROR:
      return "GL_NO_ERROR";
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_STACK_OVERFLOW:
      return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW:
      return "GL_STACK_UNDERFLOW";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_CONTEXT_LOST:
      return "GL_CONTEXT_LOST";
    default:
      return "unknown GL error";
  }
}

void DebugLog::install() {
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(&DebugLog::callback, this);
  installed_ = true;
}

void DebugLog::uninstall() {
  if (!installed_) return;
  glDebugMessageCallback(nullptr, nullptr);
  glDisable(GL_DEBUG_OUTPUT);
  installed_ = false;
}

void APIENTRY DebugLog::callback(GLenum, GLenum type, GLuint, GLenum severity, GLsizei length, const GLchar* message,
                                 const void* user) {
  if (type != GL_DEBUG_TYPE_ERROR && severity != GL_DEBUG_SEVERITY_HIGH && severity != GL_DEBUG_SEVERITY_MEDIUM) return;
  auto* self = static_cast<DebugLog*>(const_cast<void*>(user));
  if (self->messages_.size() >= 16) return;  // a runaway loop must not grow the log without bound
  self->messages_.emplace_back(message, length >= 0 ? size_t(length) : std::char_traits<char>::length(message));
}

std::string DebugLog::take() {
  std::string s;
  for (const std::string& m : messages_) s += (s.empty() ? "" : "; ") + m;
  messages_.clear();
  return s;
}

std::string drainErrors() {
  std::string s;
  // Bounded: a lost context may report errors forever.
  for (int i = 0; i < 16; ++i) {
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) break;
    s += (s.empty() ? "" : ", ") + std::string(glErrorName(e));
  }
  return s;
}

}  // namespace tessera::gl
