#include "gl/egl_context.h"

#define EGL_EGLEXT_PROTOTYPES
#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <cstring>
#include <mutex>
#include <string>
#include <vector>

#include "base/error.h"

namespace tessera::gl {
namespace {

const char* eglErrorName(EGLint e) {
  switch (e) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE:
      return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP:
      return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW:
      return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
      return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST:
      return "EGL_CONTEXT_LOST";
    default:
      return "unknown EGL error";
  }
}

constexpr const char* kHint =
    " (headless GL needs Mesa's EGL and llvmpipe: Debian packages libegl-dev libegl-mesa0 libgl1-mesa-dri "
    "libopengl-dev, installed by tools/bootstrap.sh; EGL_LOG_LEVEL=debug explains EGL failures)";

[[noreturn]] void fail(const std::string& what) {
  const EGLint e = eglGetError();
  throw Error("GL backend: " + what + (e == EGL_SUCCESS ? std::string() : std::string(": ") + eglErrorName(e)) + kHint);
}

bool hasExtension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

// One EGLDisplay per process, shared by every context, initialised on first use and never
// terminated. eglTerminate would invalidate the display for every user at once (EGL 1.5 §3.2), and
// it unloads Mesa's driver, after which LeakSanitizer can no longer attribute (or suppress) what the
// driver left allocated; Mesa's displays are process singletons anyway
// (eglGetPlatformDisplay returns the same handle for the same arguments).
struct SharedDisplay {
  std::mutex mutex;
  EGLDisplay display = EGL_NO_DISPLAY;
  std::string platform;
  std::string version, vendor;
  // The llvmpipe switches as they were when the display (and with it llvmpipe's screen) was
  // initialised: what the driver actually runs with, whatever the environment says later.
  std::vector<std::pair<std::string, std::optional<std::string>>> env;
};
SharedDisplay& shared() {
  static SharedDisplay s;
  return s;
}

EGLDisplay openDisplay(std::string& platform) {
  // Client extensions are queried on EGL_NO_DISPLAY (EGL_EXT_client_extensions).
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (client == nullptr || *client == '\0')
    fail("EGL reports no client extensions: libglvnd found no EGL vendor library (Mesa's libegl-mesa0)");
  auto getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!hasExtension(client, "EGL_EXT_platform_base") || getPlatformDisplay == nullptr)
    fail("EGL_EXT_platform_base is not supported (client extensions: " + std::string(client) + ")");
  // The surfaceless platform needs no window system and no DRM device (docs/gl-backend.md, "EGL setup").
  if (hasExtension(client, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY) {
      platform = "surfaceless";
      return d;
    }
  }
  // Fallback: the first EGL device (llvmpipe exposes one software device).
  if (hasExtension(client, "EGL_EXT_platform_device") && hasExtension(client, "EGL_EXT_device_enumeration")) {
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    EGLDeviceEXT devices[8];
    EGLint n = 0;
    if (queryDevices != nullptr && queryDevices(8, devices, &n) && n > 0) {
      EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr);
      if (d != EGL_NO_DISPLAY) {
        platform = "device";
        return d;
      }
    }
  }
  fail("no headless EGL platform: neither EGL_MESA_platform_surfaceless nor EGL_EXT_platform_device gave a display");
}

EGLDisplay acquireDisplay(GlInfo& info) {
  SharedDisplay& s = shared();
  std::lock_guard lock(s.mutex);
  if (s.display == EGL_NO_DISPLAY) {
    s.env = readRecordedEnv();
    EGLDisplay d = openDisplay(s.platform);
    EGLint major = 0, minor = 0;
    if (!eglInitialize(d, &major, &minor)) fail("eglInitialize on the " + s.platform + " platform failed");
    s.display = d;
    const char* v = eglQueryString(d, EGL_VERSION);
    const char* vd = eglQueryString(d, EGL_VENDOR);
    s.version = v ? v : "";
    s.vendor = vd ? vd : "";
  }
  info.eglPlatform = s.platform;
  info.eglVersion = s.version;
  info.eglVendor = s.vendor;
  info.env = s.env;
  return s.display;
}

std::string glString(GLenum name) {
  const GLubyte* s = glGetString(name);
  return s ? reinterpret_cast<const char*>(s) : "";
}

}  // namespace

std::unique_ptr<EglContext> EglContext::create(bool debug) {
  std::unique_ptr<EglContext> c(new EglContext());
  EGLDisplay dpy = acquireDisplay(c->info_);
  c->display_ = dpy;

  if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API) failed");
  // A surfaceless display has no window configs; the default EGL_SURFACE_TYPE (WINDOW_BIT) matches
  // nothing (EGL 1.5 §3.4.1: the default of EGL_SURFACE_TYPE is EGL_WINDOW_BIT), so ask for a
  // pbuffer-capable config.
  const EGLint configAttribs[] = {EGL_SURFACE_TYPE,
                                  EGL_PBUFFER_BIT,
                                  EGL_RENDERABLE_TYPE,
                                  EGL_OPENGL_BIT,
                                  EGL_RED_SIZE,
                                  8,
                                  EGL_GREEN_SIZE,
                                  8,
                                  EGL_BLUE_SIZE,
                                  8,
                                  EGL_ALPHA_SIZE,
                                  8,
                                  EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (!eglChooseConfig(dpy, configAttribs, &config, 1, &count)) fail("eglChooseConfig failed");
  if (count < 1) throw Error(std::string("GL backend: eglChooseConfig found no RGBA8 pbuffer OpenGL config") + kHint);

  // EGL_CONTEXT_FLAGS_KHR (EGL_KHR_create_context) rather than the EGL 1.5 EGL_CONTEXT_OPENGL_DEBUG
  // token, which displays that report EGL 1.4 reject with EGL_BAD_ATTRIBUTE.
  const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                   4,
                                   EGL_CONTEXT_MINOR_VERSION,
                                   5,
                                   EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                   EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                   EGL_CONTEXT_FLAGS_KHR,
                                   debug ? EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR : 0,
                                   EGL_NONE};
  EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, contextAttribs);
  if (ctx == EGL_NO_CONTEXT) fail("eglCreateContext for OpenGL 4.5 core failed");
  c->context_ = ctx;
  if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx))
    fail("eglMakeCurrent with EGL_NO_SURFACE failed (EGL_KHR_surfaceless_context missing?)");

  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  GlInfo& i = c->info_;
  i.vendor = glString(GL_VENDOR);
  i.renderer = glString(GL_RENDERER);
  i.version = glString(GL_VERSION);
  i.glslVersion = glString(GL_SHADING_LANGUAGE_VERSION);
  if (i.version.empty() || major * 10 + minor < 45)
    throw Error("GL backend: the context reports GL_VERSION '" + i.version + "'; OpenGL 4.5 core is required" + kHint);
  i.mesaVersion = parseMesaVersion(i.version);
  GLint flags = 0;
  glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
  i.debugContext = (flags & GL_CONTEXT_FLAG_DEBUG_BIT) != 0;
  GLint subpixelBits = 0;
  glGetIntegerv(GL_SUBPIXEL_BITS, &subpixelBits);
  i.subpixelBits = subpixelBits;
  i.cpu = readCpuCaps();
  return c;
}

EglContext::~EglContext() {
  if (display_ == nullptr || context_ == nullptr) return;
  if (eglGetCurrentContext() == context_) eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
}

void EglContext::makeCurrent() const {
  if (eglGetCurrentContext() == context_) return;
  if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) fail("eglMakeCurrent failed");
}

}  // namespace tessera::gl
