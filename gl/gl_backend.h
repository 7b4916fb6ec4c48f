// The GL backend: replays a CommandList through OpenGL 4.5 core with DSA, or OpenGL 3.3 core with
// bind points where 4.5 is absent, on a headless EGL context (Mesa llvmpipe or softpipe here), so
// every frame the oracle renders can be compared with GL pixel by pixel.
//
// Implements: execution of every command kind of command_list.h with GL calls that mirror the
// oracle's semantics (docs/spec-choices.md); where GL leaves a choice open, the backend pins GL to
// the oracle's choice (docs/gl-backend.md lists every such pin). Counts the GL calls it issues per
// command kind (GlCallCounts), which equal the oracle's API counters for the same list.
// Does not implement: comparison of images (the caller does that), timing beyond one execute (its
// wall time, and the frame's own wall and CPU time without uploads, FrameTimes).
//
// Outputs: after execute(), the presented images are the colour attachments of the render target
// bound when the list ends (every layer of a layered target), exactly as CpuBackend::presented().
// GL objects of a frame are deleted at the end of execute(), except the presented textures, which
// live until the next execute() or the destructor.
//
// Environment: llvmpipe reads LP_NUM_THREADS, LP_PERF, GALLIVM_PERF, ... when the process
// initialises its EGL display, once (the display is kept for the life of the process); create()
// sets them from GlOptions *before* that. A later create() with other options still sets the
// variables but shares the initialised display, so the new values do not take effect: use one
// option set per process. info().env records the values llvmpipe actually read.
//
// Threading: the backend owns a GL context; call every member from the thread that created it.
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "base/resource_limits.h"
#include "gl/gl_info.h"
#include "raster/command_list.h"
#include "raster/cpu_backend.h"

namespace tessera::gl {

struct Mutation;  // gl/gl_mutation.h

struct GlOptions {
  // >= 0: sets LP_NUM_THREADS (llvmpipe rasterizer threads; 0 = rasterize on the calling thread).
  int lpThreads = -1;
  // Adds LP_PERF=no_rast_linear, LP_DEBUG=no_fastpath and GALLIVM_PERF=no_aos_sampling to the
  // environment: switches that drop llvmpipe fast paths without changing GL semantics
  // (docs/gl-backend.md). LP_DEBUG is honoured only by debug builds of Mesa (Debian's release
  // swrast_dri.so does not contain the string), so it is set for completeness only.
  bool strict = false;
  // A KHR_debug context; glGetError after every command, reported with the command index.
  bool debug = false;
  // execute() refuses a list over limits.frameBytes before creating any GL object (raster/validate.h).
  ResourceLimits limits;
  // The Gallium driver: "" = Mesa's default (llvmpipe here), "llvmpipe", "softpipe" or "zink". Set as
  // GALLIUM_DRIVER (zink also MESA_LOADER_DRIVER_OVERRIDE=zink) before the EGL display initialises;
  // create() throws when the context's GL_RENDERER names another driver, naming both.
  std::string driver;
  // 0 = OpenGL 4.5 core, else 3.3 core when the driver offers no 4.5; 45 or 33 forces that path (33
  // runs the 3.3 path even on a driver that returns a 4.5 context). GlInfo::contextVersion says which.
  int glVersion = 0;
  // The EGL platform: "" = surfaceless, else device; "surfaceless" or "device" (EGL_EXT_platform_device,
  // the platform of NVIDIA / AMD / Intel drivers, which have no surfaceless platform) forces one.
  std::string eglPlatform;
  // A deliberate fault for mutation testing (gl/gl_mutation.h, `tessera mutants`); nullptr = none.
  const Mutation* mutation = nullptr;
};

// GL calls issued by the last execute(). The first eight mirror commands one to one, so for a valid
// list they equal the oracle's counters (raster/counters.h) of the same list:
//   draw_calls = FrameCounters::draw_calls, texture_binds, sampler_binds, program_binds,
//   vertex_buffer_binds, index_buffer_binds, uniform_updates: the same-named counters;
//   framebuffer_binds = render_target_changes + redundant_render_target_binds (one glBindFramebuffer
//   per SetRenderTarget).
// The rest mirror no command: calls that pin GL to the oracle's choices (docs/gl-backend.md).
// The names are the 4.5 path's calls; the 3.3 path counts its equivalents the same way
// (glBindTexture, glBindBuffer, glUniform4fv, ...), except that it re-specifies vertex attribute
// pointers before a draw without counting them (vertex_stride_rebinds stays 0 there).
struct GlCallCounts {
  uint64_t draw_calls = 0;           // glDrawArrays / glDrawElements
  uint64_t texture_binds = 0;        // glBindTextureUnit
  uint64_t sampler_binds = 0;        // glBindSampler
  uint64_t program_binds = 0;        // glUseProgram
  uint64_t vertex_buffer_binds = 0;  // glVertexArrayVertexBuffer for BindVertexBuffer
  uint64_t index_buffer_binds = 0;   // glVertexArrayElementBuffer
  uint64_t framebuffer_binds = 0;    // glBindFramebuffer
  uint64_t uniform_updates = 0;      // glProgramUniform4fv for SetUniforms

  uint64_t internal_uniform_updates = 0;  // glProgramUniform1ui of tessera_layerLimit / tessera_boundUnits
  uint64_t texture_unit_resets = 0;       // glBindTextureUnit(u, 0) before binding another target on u
  uint64_t draw_buffer_changes = 0;       // glNamedFramebufferDrawBuffers masking unwritten outputs
  uint64_t vertex_stride_rebinds = 0;     // glVertexArrayVertexBuffer when a layout changes the stride

  bool operator==(const GlCallCounts&) const = default;
  nlohmann::json toJson() const;
};

// Format and size of a presented image as readImage() returns it.
struct GlImageDesc {
  Format format = Format::RGBA8;
  uint32_t width = 0, height = 0;
};

// What the last execute() spent on the frame itself (docs/bench.md): the counterpart of the oracle's
// StageTimes::frameMs. The clock starts at the first command that is not a resource command
// (CreateTexture, UploadTexture, CreateBuffer, UploadBuffer, CreateSampler, CreateProgram), after a
// glFinish so the uploads before it are complete, and stops after the final glFinish; resource
// commands inside the frame are timed apart and left out (an upload after a glFinish, as the oracle
// flushes before one). Validation, the uploads before the frame and the deletion of the frame's
// objects are outside. frameCpuMs is the process's CPU time (getrusage, every thread: llvmpipe's
// rasterizer threads included) over the same span. Both 0 for a list of resource commands only.
struct FrameTimes {
  double frameMs = 0.0, frameCpuMs = 0.0;
};

class GlBackend {
 public:
  // Sets the environment from `options`, creates the EGL context and compiles nothing yet (twins
  // are compiled on first use). Throws Error with a clear message when EGL or the GL version is
  // unavailable, or when the context is not the driver options.driver asked for.
  static std::unique_ptr<GlBackend> create(const GlOptions& options = {});
  ~GlBackend();
  GlBackend(const GlBackend&) = delete;
  GlBackend& operator=(const GlBackend&) = delete;

  const GlInfo& info() const;
  const GlOptions& options() const;
  // Replaces options().mutation for the next execute(): drops every compiled twin (they recompile
  // with the new mutation's edits) and re-pins the context state a mutation may have changed.
  void setMutation(const Mutation* mutation);

  // Validates the list against options().limits (validateOrThrow: Error naming `frameName` and the
  // command index) before creating any GL object, then replays it and waits for GL to finish
  // (glFinish). GL errors throw Error: with the command index in debug mode, else once at the end of
  // the frame.
  void execute(const CommandList& list, std::string_view frameName = "frame");

  std::vector<PresentedImage> presented() const;
  GlImageDesc describe(const PresentedImage& image) const;
  // The pixels of a presented image in tessera::imagePixels() layout: top row first, tightly
  // packed, the texture's own format (RGBA8: 4 bytes, R32UI: one little-endian uint32, ...).
  std::vector<uint8_t> readImage(const PresentedImage& image) const;

  const GlCallCounts& calls() const;
  // Wall time of the last execute(), validation and glFinish included (like the oracle's oracle_ms).
  double lastExecuteMs() const;
  // The frame alone of the last execute() (FrameTimes above), for benchmarks.
  const FrameTimes& lastFrameTimes() const;
  // GL object names the backend holds right now (textures, buffers, samplers, framebuffers,
  // programs, vertex arrays, cached shaders); for leak tests.
  size_t liveObjects() const;

 private:
  GlBackend();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tessera::gl
