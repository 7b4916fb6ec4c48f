#include "gl/gl_backend.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

#include "base/cpu_time.h"
#include "gl/egl_context.h"
#include "gl/gl_api.h"
#include "gl/gl_debug.h"
#include "gl/gl_enums.h"
#include "gl/gl_mutation.h"
#include "gl/gl_programs.h"
#include "gl/gl_resources.h"
#include "gl/gl_state.h"
#include "gl/gl_targets.h"
#include "raster/validate.h"

namespace tessera::gl {

nlohmann::json GlCallCounts::toJson() const {
  return {{"draw_calls", draw_calls},
          {"texture_binds", texture_binds},
          {"sampler_binds", sampler_binds},
          {"program_binds", program_binds},
          {"vertex_buffer_binds", vertex_buffer_binds},
          {"index_buffer_binds", index_buffer_binds},
          {"framebuffer_binds", framebuffer_binds},
          {"uniform_updates", uniform_updates},
          {"internal_uniform_updates", internal_uniform_updates},
          {"texture_unit_resets", texture_unit_resets},
          {"draw_buffer_changes", draw_buffer_changes},
          {"vertex_stride_rebinds", vertex_stride_rebinds}};
}

namespace {

// Adds `flag` to the comma-separated list in environment variable `name` (Mesa's flag syntax),
// keeping what the user already set.
void addEnvFlag(const char* name, const char* flag) {
  const char* old = std::getenv(name);
  const std::string_view current = old ? old : "";
  // Appends rather than `"," + s + ","`: gcc 12 raises a false -Wrestrict on that pattern.
  size_t pos = 0;
  while (pos <= current.size()) {
    size_t end = current.find(',', pos);
    if (end == std::string_view::npos) end = current.size();
    if (current.substr(pos, end - pos) == flag) return;
    pos = end + 1;
  }
  std::string v(current);
  if (!v.empty()) v.push_back(',');
  v.append(flag);
  setenv(name, v.c_str(), 1);
}

}  // namespace

struct GlBackend::Impl {
  GlOptions options;
  std::unique_ptr<EglContext> context;
  DebugLog debugLog;
  ProgramCompiler compiler;
  FrameResources res;
  FramebufferCache fbos;
  std::vector<LinkedProgram> programs;  // indexed by id; name 0 = not a program
  GLuint vao = 0;
  GLint maxRelativeOffset = 0, maxStride = 0;
  // The 4.5 path (DSA); false: the 3.3 core path, through bind points (docs/gl-backend.md).
  bool dsa = true;
  // 3.3 path: glVertexAttribPointer captures the buffer and stride, so the attribute pointers are
  // specified at the next draw after BindVertexBuffer or SetVertexLayout changed them.
  bool attribsDirty = false;

  // Replay state of the current frame.
  std::array<ResourceId, kMaxTextureUnits> unitTexture{};
  std::array<GLenum, kMaxTextureUnits> unitTarget{};  // the one GL target holding a texture, or GL_NONE
  ResourceId program = kNone, vertexBuffer = kNone;
  IndexType indexType = IndexType::U16;
  VertexLayout layout;
  uint32_t boundStride = 0;  // the stride of the last glVertexArrayVertexBuffer
  DepthState depth;
  uint8_t clipMask = 0;
  RenderTarget target;
  bool targetBound = false;
  GlFramebuffer* fb = nullptr;

  GlCallCounts counts;
  double ms = 0.0;
  FrameTimes frame;
  std::vector<PresentedImage> presented;

  // The command being replayed, for error messages: "<frame>: command N (Kind)".
  std::string_view frameName;
  const CommandList* list = nullptr;
  size_t commandIndex = 0;
  std::string where() const {
    return std::string(frameName) + ": command " + std::to_string(commandIndex) + " (" +
           std::string(commandName(list->commands()[commandIndex].index())) + ")";
  }

  ~Impl() {
    if (!context) return;
    try {
      context->makeCurrent();
    } catch (const Error&) {
      return;  // the context is unusable: its objects go with it when EGL destroys it
    }
    releaseFrame({});
    compiler.release();
    if (options.debug) debugLog.uninstall();
  }

  // Deletes every GL object of the frame except the presented textures.
  void releaseFrame(const std::vector<ResourceId>& keep) {
    // Unbind first, so deletion is immediate rather than deferred until unbound (GL 4.6 §5.1.2-3).
    glUseProgram(0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    unbindAllUnits(dsa);
    glBindVertexArray(0);
    for (const LinkedProgram& p : programs) compiler.recycle(p);  // kept for the next frame's JIT cache
    programs.clear();
    fbos.releaseAll();
    fb = nullptr;
    res.releaseExcept(keep);
    if (vao != 0) glDeleteVertexArrays(1, &vao);
    vao = 0;
  }

  void beginFrame() {
    releaseFrame({});
    presented.clear();
    counts = {};
    unitTexture.fill(kNone);
    unitTarget.fill(GL_NONE);
    program = vertexBuffer = kNone;
    indexType = IndexType::U16;
    layout = {};
    boundStride = 0;
    depth = {};
    clipMask = 0;
    target = {};
    targetBound = false;
    attribsDirty = false;
    // A fresh vertex array: every attribute disabled (reads (0, 0, 0, 1), GL 4.6 §10.2), no buffers.
    if (dsa) {
      glCreateVertexArrays(1, &vao);
    } else {
      glGenVertexArrays(1, &vao);
    }
    glBindVertexArray(vao);
    resetFrameState(dsa);
  }

  // --- commands ---------------------------------------------------------------------------------
  void apply(const CommandList&, const CreateTexture& c) { res.createTexture(c.id, c.desc); }
  void apply(const CommandList& l, const UploadTexture& c) {
    if (options.mutation) {
      const GlTexture* t = res.texture(c.id);
      if (t) {
        const std::vector<uint8_t> corrupted = options.mutation->applyToUpload(t->desc, l.bytes(c.data));
        if (!corrupted.empty()) return res.uploadTexture(c, corrupted);
      }
    }
    res.uploadTexture(c, l.bytes(c.data));
  }
  void apply(const CommandList&, const CreateBuffer& c) { res.createBuffer(c.id, c.size); }
  void apply(const CommandList& l, const UploadBuffer& c) { res.uploadBuffer(c, l.bytes(c.data)); }
  void apply(const CommandList&, const CreateSampler& c) {
    res.createSampler(c.id, options.mutation ? options.mutation->applyToState(c.state) : c.state);
  }
  void apply(const CommandList&, const CreateProgram& c) {
    if (programs.size() <= c.id) programs.resize(size_t(c.id) + 1);
    programs[c.id] = compiler.acquire(c.name, counts.internal_uniform_updates);
  }

  void apply(const CommandList&, const BindTexture& c) {
    // A GL unit holds one binding per texture target (GL 4.6 §8.1); the oracle's unit holds one
    // texture. Binding a texture of another target than the one the unit holds first resets the unit
    // (texture 0 resets every target), so a program never sees a stale binding of another target.
    const GlTexture* t = res.texture(c.texture);
    const GLenum newTarget = t ? t->target : GL_NONE;
    if (t != nullptr && unitTarget[c.unit] != GL_NONE && unitTarget[c.unit] != newTarget) {
      bindTextureOnUnit(dsa, int(c.unit), GL_NONE, 0);
      ++counts.texture_unit_resets;
    }
    bindTextureOnUnit(dsa, int(c.unit), newTarget, t ? t->name : 0);
    ++counts.texture_binds;
    unitTarget[c.unit] = newTarget;
    unitTexture[c.unit] = t ? c.texture : kNone;
  }
  void apply(const CommandList&, const BindSampler& c) {
    // Sampler 0 = the texture's own parameters, GL's defaults = SamplerState{} (gl_resources.h).
    glBindSampler(c.unit, res.sampler(c.sampler));
    ++counts.sampler_binds;
  }
  void apply(const CommandList&, const UseProgram& c) {
    glUseProgram(c.program < programs.size() ? programs[c.program].name : 0);
    ++counts.program_binds;
    program = c.program;
  }
  void apply(const CommandList& l, const SetUniforms& c) {
    // u[64] has explicit location 0 in every twin, so slot k is location k (GL 4.6 §7.3.1:
    // consecutive locations for the elements of an array with an explicit location). Writes to
    // elements the linker found unused are ignored by GL, as they are unobservable in the oracle.
    float values[kMaxUniformSlots * 4];
    const auto src = l.bytes(c.data);
    std::memcpy(values, src.data(), std::min(src.size(), sizeof values));  // the blob may be unaligned
    const LinkedProgram& p = programs[program];
    uniform4fv(dsa, p.name, p.slotLocation(c.slot), GLsizei(c.count), values);  // p is the current program
    ++counts.uniform_updates;
  }
  void apply(const CommandList&, const BindVertexBuffer& c) {
    if (dsa) {
      glVertexArrayVertexBuffer(vao, 0, res.buffer(c.buffer), 0, GLsizei(layout.stride));
    } else {
      glBindBuffer(GL_ARRAY_BUFFER, res.buffer(c.buffer));
      attribsDirty = true;
    }
    ++counts.vertex_buffer_binds;
    vertexBuffer = c.buffer;
    boundStride = layout.stride;
  }
  void apply(const CommandList&, const SetVertexLayout& c) {
    layout = c.layout;
    if (!dsa) {
      attribsDirty = true;
      return;
    }
    if (layout.stride > uint32_t(maxStride))
      throw Error(where() + ": stride " + std::to_string(layout.stride) + " exceeds GL_MAX_VERTEX_ATTRIB_STRIDE (" +
                  std::to_string(maxStride) + ")");
    std::array<bool, kMaxAttribs> enabled{};
    for (const VertexAttrib& a : layout.attribs) {
      if (a.components == 0 || a.location >= kMaxAttribs) continue;
      if (a.offset > uint32_t(maxRelativeOffset))
        throw Error(where() + ": attribute offset " + std::to_string(a.offset) +
                    " exceeds GL_MAX_VERTEX_ATTRIB_RELATIVE_OFFSET (" + std::to_string(maxRelativeOffset) + ")");
      // U32 reaches the program as float, not normalized (glVertexAttribFormat, not IFormat): the
      // oracle converts with float(u), exact below 2^24 (V7).
      glVertexArrayAttribFormat(vao, a.location, a.components, a.type == AttribType::U32 ? GL_UNSIGNED_INT : GL_FLOAT,
                                GL_FALSE, a.offset);
      glVertexArrayAttribBinding(vao, a.location, 0);
      enabled[a.location] = true;
    }
    for (GLuint loc = 0; loc < GLuint(kMaxAttribs); ++loc) {
      if (enabled[loc]) {
        glEnableVertexArrayAttrib(vao, loc);
      } else {
        glDisableVertexArrayAttrib(vao, loc);  // reads the current value (0, 0, 0, 1)
      }
    }
    // The stride lives with the buffer binding in GL but with the layout in the command list.
    if (vertexBuffer != kNone && boundStride != layout.stride) {
      glVertexArrayVertexBuffer(vao, 0, res.buffer(vertexBuffer), 0, GLsizei(layout.stride));
      ++counts.vertex_stride_rebinds;
      boundStride = layout.stride;
    }
  }
  void apply(const CommandList&, const BindIndexBuffer& c) {
    if (dsa) {
      glVertexArrayElementBuffer(vao, res.buffer(c.buffer));
    } else {
      glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, res.buffer(c.buffer));  // VAO state (GL 3.3 §2.10)
    }
    ++counts.index_buffer_binds;
    indexType = c.type;
  }
  void apply(const CommandList&, const SetViewport& c) { applyViewport(c.rect); }
  void apply(const CommandList&, const SetScissor& c) { applyScissor(c.state); }
  void apply(const CommandList&, const SetDepthState& c) {
    applyDepth(c.state);
    depth = c.state;
  }
  void apply(const CommandList&, const SetBlendState& c) { applyBlend(c.state); }
  void apply(const CommandList&, const SetRasterState& c) {
    applyRaster(c.state);
    clipMask = c.state.clipMask;
  }
  void apply(const CommandList&, const SetRenderTarget& c) {
    fb = fbos.get(c.target, res, where());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fb ? fb->name : 0);
    ++counts.framebuffer_binds;
    target = c.target;
    targetBound = true;
  }
  void apply(const CommandList&, const ClearColor& c) {
    // glClearNamedFramebuffer* clears draw buffer `attachment` within the scissor, every layer of a
    // layered attachment (GL 4.6 §17.4.3, §9.8), as the oracle does (F5).
    if (FramebufferCache::setDrawMask(*fb, uint8_t(fb->drawMask | (1u << c.attachment)))) ++counts.draw_buffer_changes;
    if (isInteger(fb->colorFormat[c.attachment])) {
      if (dsa) {
        glClearNamedFramebufferuiv(fb->name, GL_COLOR, GLint(c.attachment), c.bits.data());
      } else {
        glClearBufferuiv(GL_COLOR, GLint(c.attachment), c.bits.data());  // fb is the bound draw framebuffer
      }
    } else {
      float v[4];
      std::memcpy(v, c.bits.data(), sizeof v);
      if (dsa) {
        glClearNamedFramebufferfv(fb->name, GL_COLOR, GLint(c.attachment), v);
      } else {
        glClearBufferfv(GL_COLOR, GLint(c.attachment), v);
      }
    }
  }
  void apply(const CommandList&, const ClearDepth& c) {
    // The oracle clamps to [0, 1] (glClearDepth's rule); do it here so the float target gets the
    // same value whatever ClearBuffer does with out-of-range depth.
    const float d = c.depth > 0.0f ? (c.depth < 1.0f ? c.depth : 1.0f) : 0.0f;
    // GL masks depth clears with glDepthMask (GL 4.6 §17.4.3) and so does the oracle (spec-choices F5).
    if (dsa) {
      glClearNamedFramebufferfv(fb->name, GL_DEPTH, 0, &d);
    } else {
      glClearBufferfv(GL_DEPTH, 0, &d);
    }
  }
  void apply(const CommandList&, const Draw& d) {
    LinkedProgram& p = programs[program];
    prepareDraw(p);
    if (attribsDirty) specifyAttribs();
    if (d.indexed) {
      const uintptr_t offset = uintptr_t(d.first) * indexBytes(indexType);
      glDrawElements(GL_TRIANGLES, GLsizei(d.count), glIndexType(indexType), reinterpret_cast<const void*>(offset));
    } else {
      glDrawArrays(GL_TRIANGLES, GLint(d.first), GLsizei(d.count));
    }
    ++counts.draw_calls;
  }
  void apply(const CommandList&, const Marker&) {}

  // State the oracle decides per draw that GL would leave open (docs/gl-backend.md, "Pinning").
  void prepareDraw(LinkedProgram& p) {
    // Only attachments below the program's output count are written by the oracle; GL leaves
    // attachments without an output undefined (GL 4.6 §17.4.1), so those draw buffers are NONE.
    const uint8_t outputs = uint8_t((1u << std::min(p.colorOutputs, kMaxColorAttachments)) - 1u);
    if (FramebufferCache::setDrawMask(*fb, uint8_t(fb->attached & outputs))) ++counts.draw_buffer_changes;
    // A layer outside a layered target drops the primitive in the oracle (F6); GL leaves it
    // undefined (llvmpipe clamps). The twin's geometry stage drops layer >= this limit.
    setInternal(p, p.layerLimitLocation, p.layerLimitSet, p.layerLimit,
                target.layer == kLayered ? fb->layerCount : 0xffffffffu);
    // texelFetch on a unit without a texture is (0, 0, 0, 1) in the oracle (incomplete, T12); GL's
    // default buffer texture has no buffer and its value is undefined.
    uint32_t bound = 0;
    for (int u = 0; u < kMaxTextureUnits; ++u)
      if (unitTexture[size_t(u)] != kNone) bound |= 1u << u;
    setInternal(p, p.boundUnitsLocation, p.boundUnitsSet, p.boundUnits, bound);
    // llvmpipe (Mesa 22.3) clips by every clip distance the last vertex stage writes, enabled or
    // not (GL 4.6 §13.7.1 says a disabled one is ignored). Twins write 0 (inside) for disabled ones.
    setInternal(p, p.clipMaskLocation, p.clipMaskSet, p.clipMask, clipMask);
  }

  // 3.3 path, before a draw: the attribute pointers of the current layout into the bound
  // GL_ARRAY_BUFFER (the buffer and stride are captured per attribute, GL 3.3 §2.8). Validation
  // guarantees a vertex buffer before a draw that reads attributes.
  void specifyAttribs() {
    attribsDirty = false;
    std::array<bool, kMaxAttribs> enabled{};
    if (vertexBuffer != kNone) {
      for (const VertexAttrib& a : layout.attribs) {
        if (a.components == 0 || a.location >= kMaxAttribs) continue;
        // U32 as float, not normalized (V7), as glVertexArrayAttribFormat on the 4.5 path.
        glVertexAttribPointer(a.location, a.components, a.type == AttribType::U32 ? GL_UNSIGNED_INT : GL_FLOAT,
                              GL_FALSE, GLsizei(layout.stride), reinterpret_cast<const void*>(uintptr_t(a.offset)));
        enabled[a.location] = true;
      }
    }
    for (GLuint loc = 0; loc < GLuint(kMaxAttribs); ++loc) {
      if (enabled[loc]) {
        glEnableVertexAttribArray(loc);
      } else {
        glDisableVertexAttribArray(loc);  // reads the current value (0, 0, 0, 1)
      }
    }
  }

  void setInternal(const LinkedProgram& p, GLint location, bool& set, uint32_t& held, uint32_t value) {
    if (location < 0 || (set && held == value)) return;
    uniform1ui(dsa, p.name, location, value);  // p is the current program (a draw is being prepared)
    ++counts.internal_uniform_updates;
    held = value;
    set = true;
  }

  // Debug mode, after every command: a GL error names the command and what the driver said.
  void checkErrors() {
    const std::string errors = drainErrors();
    const std::string messages = debugLog.take();
    if (!errors.empty()) throw Error(where() + ": " + errors + (messages.empty() ? "" : " (driver: " + messages + ")"));
  }

  void run(const CommandList& cl, std::string_view name) {
    beginFrame();
    list = &cl;
    frameName = name;
    const auto& cmds = cl.commands();
    // The frame's clock (FrameTimes): from the first command that is not a resource command, after a
    // glFinish so the uploads before it are done, to the glFinish at the end; resource commands inside
    // the frame are timed apart (after a glFinish before an upload, as the oracle flushes there), so
    // the frame's time is the draws' and clears' whatever the list interleaves.
    using Clock = std::chrono::steady_clock;
    bool started = false;
    Clock::time_point frameStart;
    Clock::duration inFrameResources{};
    double frameCpuStart = 0.0, inFrameResourcesCpu = 0.0;
    for (commandIndex = 0; commandIndex < cmds.size(); ++commandIndex) {
      const Command& cmd = cmds[commandIndex];
      const bool resource = std::holds_alternative<CreateTexture>(cmd) || std::holds_alternative<UploadTexture>(cmd) ||
                            std::holds_alternative<CreateBuffer>(cmd) || std::holds_alternative<UploadBuffer>(cmd) ||
                            std::holds_alternative<CreateSampler>(cmd) || std::holds_alternative<CreateProgram>(cmd);
      if (!resource && !started) {
        glFinish();
        started = true;
        frameStart = Clock::now();
        frameCpuStart = processCpuMs();
      }
      const bool timedApart = resource && started;
      Clock::time_point t0;
      double cpu0 = 0.0;
      if (timedApart) {
        if (std::holds_alternative<UploadTexture>(cmd) || std::holds_alternative<UploadBuffer>(cmd)) glFinish();
        t0 = Clock::now();
        cpu0 = processCpuMs();
      }
      std::visit([&](const auto& c) { apply(cl, c); }, cmd);
      if (options.mutation) options.mutation->applyToState(cmd);
      if (options.debug) checkErrors();
      if (timedApart) {
        inFrameResources += Clock::now() - t0;
        inFrameResourcesCpu += processCpuMs() - cpu0;
      }
    }
    glFinish();
    frame = {};
    if (started) {
      const Clock::duration span = Clock::now() - frameStart - inFrameResources;
      frame.frameMs = std::max(0.0, std::chrono::duration<double, std::milli>(span).count());
      frame.frameCpuMs = std::max(0.0, processCpuMs() - frameCpuStart - inFrameResourcesCpu);
    }
    if (const std::string errors = drainErrors(); !errors.empty())
      throw Error(std::string(name) + ": GL reported " + errors +
                  " during the frame; GlOptions::debug names the command");

    // The presented images, as CpuBackend::presented() chooses them.
    std::vector<ResourceId> keep;
    if (targetBound) {
      for (uint32_t a = 0; a < uint32_t(kMaxColorAttachments); ++a) {
        const GlTexture* t = res.texture(target.color[a]);
        if (t == nullptr) continue;
        keep.push_back(target.color[a]);
        if (target.layer == kLayered) {
          for (uint32_t l = 0; l < t->desc.layers; ++l) presented.push_back({target.color[a], a, target.level, l});
        } else {
          presented.push_back({target.color[a], a, target.level, target.layer});
        }
      }
    }
    releaseFrame(keep);
  }
};

GlBackend::GlBackend() : impl_(std::make_unique<Impl>()) {}
GlBackend::~GlBackend() = default;

std::unique_ptr<GlBackend> GlBackend::create(const GlOptions& options) {
  // llvmpipe reads these when the EGL display is initialised (see the header).
  if (options.lpThreads >= 0) setenv("LP_NUM_THREADS", std::to_string(options.lpThreads).c_str(), 1);
  if (options.strict) {
    addEnvFlag("LP_PERF", "no_rast_linear");
    addEnvFlag("LP_DEBUG", "no_fastpath");
    addEnvFlag("GALLIVM_PERF", "no_aos_sampling");
  }
  if (!options.driver.empty()) {
    if (options.driver != "llvmpipe" && options.driver != "softpipe" && options.driver != "zink")
      throw Error("GL backend: driver '" + options.driver + "' is not supported (llvmpipe, softpipe or zink)");
    // Mesa's Gallium software loader reads GALLIUM_DRIVER; zink is a DRI driver of its own, which the
    // loader picks only with MESA_LOADER_DRIVER_OVERRIDE (docs/gl-backend.md, "Drivers").
    setenv("GALLIUM_DRIVER", options.driver.c_str(), 1);
    if (options.driver == "zink") setenv("MESA_LOADER_DRIVER_OVERRIDE", "zink", 1);
  }
  std::unique_ptr<GlBackend> b(new GlBackend());
  Impl& m = *b->impl_;
  m.options = options;
  m.context = EglContext::create({options.debug, options.glVersion, options.eglPlatform, options.driver});
  EglContext& ctx = *m.context;
  m.dsa = ctx.info().contextVersion == 45;
  GlslDialect dialect;
  dialect.core450 = m.dsa;
  dialect.gpuShader5 = ctx.hasExtension("GL_ARB_gpu_shader5");
  dialect.fp64 = ctx.hasExtension("GL_ARB_gpu_shader_fp64");
  dialect.derivativeControl = ctx.hasExtension("GL_ARB_derivative_control");
  dialect.languagePack420 = ctx.hasExtension("GL_ARB_shading_language_420pack");
  ctx.info().glslDialect = dialect.name();
  ctx.info().glslExtensions = dialect.extensions();
  ctx.info().glslFallbacks = dialect.fallbacks();
  m.compiler.configure(dialect, m.dsa, m.dsa || ctx.hasExtension("GL_ARB_program_interface_query"));
  // S3TC is an extension (GL 4.6 core has no S3TC formats); Mesa exposes it on llvmpipe and softpipe. Without
  // it a compressed texture is refused when the frame creates one (gl_resources.cpp), never decoded here.
  m.res.configure(m.dsa, ctx.hasExtension("GL_EXT_texture_compression_s3tc"), ctx.info().renderer);
  m.fbos.configure(m.dsa);
  // KHR_debug is GL 4.3; a 3.3 context without it still checks glGetError after every command.
  if (options.debug && (m.dsa || ctx.hasExtension("GL_KHR_debug"))) m.debugLog.install();
  if (options.mutation) m.compiler.setMutation(options.mutation);
  pinContextState(m.dsa);
  if (m.dsa) {
    glGetIntegerv(GL_MAX_VERTEX_ATTRIB_RELATIVE_OFFSET, &m.maxRelativeOffset);
    glGetIntegerv(GL_MAX_VERTEX_ATTRIB_STRIDE, &m.maxStride);
  } else {
    // GL 3.3 has neither limit (both are GL 4.3 / 4.4): glVertexAttribPointer takes any GLsizei stride.
    m.maxRelativeOffset = m.maxStride = std::numeric_limits<GLint>::max();
  }
  if (const std::string errors = drainErrors(); !errors.empty())
    throw Error("GL backend: context set-up raised " + errors);
  return b;
}

const GlInfo& GlBackend::info() const { return impl_->context->info(); }
const GlOptions& GlBackend::options() const { return impl_->options; }

void GlBackend::setMutation(const Mutation* mutation) {
  impl_->context->makeCurrent();
  impl_->compiler.setMutation(mutation);
  pinContextState(impl_->dsa);  // undoes what the previous mutation changed in state pinned once per context
  impl_->options.mutation = mutation;
}

void GlBackend::execute(const CommandList& list, std::string_view frameName) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  validateOrThrow(list, frameName, impl_->options.limits);
  impl_->context->makeCurrent();
  drainErrors();  // errors of earlier misuse must not be blamed on this frame
  impl_->run(list, frameName);
  impl_->ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

std::vector<PresentedImage> GlBackend::presented() const { return impl_->presented; }

GlImageDesc GlBackend::describe(const PresentedImage& image) const {
  const GlTexture* t = impl_->res.texture(image.texture);
  const bool known = std::any_of(impl_->presented.begin(), impl_->presented.end(), [&](const PresentedImage& p) {
    return p.texture == image.texture && p.level == image.level && p.layer == image.layer;
  });
  if (t == nullptr || !known)
    throw Error("GL backend: texture " + std::to_string(image.texture) + " level " + std::to_string(image.level) +
                " layer " + std::to_string(image.layer) + " is not a presented image of the last frame");
  return {t->desc.format, levelWidth(t->desc, image.level), levelHeight(t->desc, image.level)};
}

std::vector<uint8_t> GlBackend::readImage(const PresentedImage& image) const {
  const GlImageDesc d = describe(image);
  impl_->context->makeCurrent();
  const GlTexture& t = *impl_->res.texture(image.texture);
  const GlFormat f = glFormat(d.format);
  const size_t row = size_t(d.width) * texelBytes(d.format);
  std::vector<uint8_t> gl(row * d.height);
  // glGetTextureSubImage reads one layer of one level straight from the texture (GL 4.6 §8.11.4),
  // rows bottom first with GL_PACK_ALIGNMENT 1. GL 3.3 reads whole levels only (glGetTexImage, every
  // layer of an array), on the scratch unit.
  if (impl_->dsa) {
    glGetTextureSubImage(t.name, GLint(image.level), 0, 0,
                         t.desc.kind == TextureKind::Tex2DArray ? GLint(image.layer) : 0, GLsizei(d.width),
                         GLsizei(d.height), 1, f.format, f.type, GLsizei(gl.size()), gl.data());
  } else {
    const bool array = t.desc.kind == TextureKind::Tex2DArray;
    std::vector<uint8_t> all(gl.size() * (array ? t.desc.layers : 1));
    glBindTexture(t.target, t.name);
    glGetTexImage(t.target, GLint(image.level), f.format, f.type, all.data());
    std::memcpy(gl.data(), all.data() + (array ? gl.size() * image.layer : 0), gl.size());
  }
  if (const std::string errors = drainErrors(); !errors.empty())
    throw Error("GL backend: reading texture " + std::to_string(image.texture) + " raised " + errors);
  // imagePixels() order: top row first.
  std::vector<uint8_t> out(gl.size());
  for (uint32_t y = 0; y < d.height; ++y)
    std::memcpy(out.data() + size_t(d.height - 1 - y) * row, gl.data() + size_t(y) * row, row);
  return out;
}

const GlCallCounts& GlBackend::calls() const { return impl_->counts; }
double GlBackend::lastExecuteMs() const { return impl_->ms; }
const FrameTimes& GlBackend::lastFrameTimes() const { return impl_->frame; }

size_t GlBackend::liveObjects() const {
  size_t n = impl_->res.liveObjects() + impl_->fbos.size() + impl_->compiler.objectCount() + (impl_->vao != 0);
  for (const LinkedProgram& p : impl_->programs) n += p.name != 0;
  return n;
}

}  // namespace tessera::gl
