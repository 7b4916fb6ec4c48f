// A headless OpenGL 4.5 core context through EGL, with no window system and no GPU:
// EGL_MESA_platform_surfaceless (fallback: EGL_EXT_platform_device), a pbuffer-capable config, and
// eglMakeCurrent with EGL_NO_SURFACE (EGL_KHR_surfaceless_context); rendering goes to FBOs only.
// On the project's machines this is Mesa llvmpipe (docs/gl-backend.md, "EGL setup").
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

#include "gl/gl_info.h"

namespace tessera::gl {

class EglContext {
 public:
  // Creates and makes current a GL 4.5 core context (a KHR_debug context when `debug`). Throws
  // tessera::Error with the failing EGL call, the EGL error name and a hint when EGL or GL 4.5 is
  // unavailable. llvmpipe reads its environment (LP_NUM_THREADS, ...) when the EGL display is
  // initialised, once per process, so set it before the first create().
  static std::unique_ptr<EglContext> create(bool debug);
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  // Makes the context current on the calling thread if it is not already.
  void makeCurrent() const;
  const GlInfo& info() const { return info_; }

 private:
  EglContext() = default;
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
  GlInfo info_;
};

}  // namespace tessera::gl
