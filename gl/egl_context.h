// A headless OpenGL 4.5 core (or 3.3 core) context through EGL, with no window system and no GPU:
// EGL_MESA_platform_surfaceless (fallback, or on request: EGL_EXT_platform_device, the platform of
// real GPUs' drivers), a pbuffer-capable config, and eglMakeCurrent with EGL_NO_SURFACE
// (EGL_KHR_surfaceless_context); rendering goes to FBOs only. On the project's machines this is
// Mesa llvmpipe or softpipe (docs/gl-backend.md, "EGL setup", "The 3.3 core path").
//
// Implements: display sharing between contexts (one process-wide EGLDisplay, initialised on first
// use and kept for the life of the process), context creation, making it current, and the GlInfo
// record.
// Does not implement: any rendering (gl_backend.h).
//
// Threading: a context is current on one thread at a time; makeCurrent() binds it to the calling
// thread. Create, use and destroy a context on one thread.
#pragma once

#include <memory>
#include <set>
#include <string>

#include "gl/gl_info.h"

namespace tessera::gl {

struct ContextRequest {
  bool debug = false;  // a KHR_debug context
  // 45: OpenGL 4.5 core only; 33: a 3.3 core context, used through the 3.3 path whatever version
  // the driver returns; 0: 4.5 core, else 3.3 core when the driver refuses 4.5 (EGL_BAD_MATCH).
  int glVersion = 0;
  // "surfaceless", "device" or "" (surfaceless, else device). Applies when the process-wide display
  // is first opened; asking a later context for another platform is an error.
  std::string eglPlatform;
  // The driver GlOptions::driver asked for ("" = any): the context must report it (GL_RENDERER).
  std::string driver;
};

class EglContext {
 public:
  // Creates and makes current a GL context as `request` asks. Throws tessera::Error with the failing
  // EGL call, the EGL error name and a hint when EGL or the GL version is unavailable, or when the
  // context's GL_RENDERER is not the driver asked for (naming both). Mesa reads its environment
  // (GALLIUM_DRIVER, LP_NUM_THREADS, ...) when the EGL display is initialised, once per process, so
  // set it before the first create().
  static std::unique_ptr<EglContext> create(const ContextRequest& request);
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  // Makes the context current on the calling thread if it is not already.
  void makeCurrent() const;
  const GlInfo& info() const { return info_; }
  GlInfo& info() { return info_; }
  // Whether GL_EXTENSIONS (glGetStringi) lists `name`.
  bool hasExtension(const std::string& name) const { return extensions_.count(name) != 0; }

 private:
  EglContext() = default;
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
  GlInfo info_;
  std::set<std::string> extensions_;
};

}  // namespace tessera::gl
