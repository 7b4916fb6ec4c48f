#include "gl/gl_targets.h"

#include <algorithm>
#include <string>

namespace tessera::gl {
namespace {

const char* statusName(GLenum s) {
  switch (s) {
    case GL_FRAMEBUFFER_COMPLETE:
      return "GL_FRAMEBUFFER_COMPLETE";
    case GL_FRAMEBUFFER_UNDEFINED:
      return "GL_FRAMEBUFFER_UNDEFINED";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT:
      return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT:
      return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER:
      return "GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER";
    case GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER:
      return "GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER";
    case GL_FRAMEBUFFER_UNSUPPORTED:
      return "GL_FRAMEBUFFER_UNSUPPORTED";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE:
      return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS:
      return "GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS";
    default:
      return "unknown framebuffer status";
  }
}

void attach(bool dsa, GLuint fbo, GLenum point, const GlTexture& tex, const RenderTarget& t) {
  const GLint level = GLint(t.level);
  const bool whole = t.layer == kLayered || tex.desc.kind != TextureKind::Tex2DArray;
  if (!dsa) {  // the FBO is bound to GL_FRAMEBUFFER (get())
    if (whole) {
      glFramebufferTexture(GL_FRAMEBUFFER, point, tex.name, level);
    } else {
      glFramebufferTextureLayer(GL_FRAMEBUFFER, point, tex.name, level, GLint(t.layer));
    }
  } else if (whole) {
    glNamedFramebufferTexture(fbo, point, tex.name, level);
  } else {
    glNamedFramebufferTextureLayer(fbo, point, tex.name, level, GLint(t.layer));
  }
}

}  // namespace

GlFramebuffer* FramebufferCache::get(const RenderTarget& t, const FrameResources& res, std::string_view where) {
  for (auto& f : fbos_)
    if (f->target == t) return f.get();
  const bool empty =
      t.depth == kNone && std::all_of(t.color.begin(), t.color.end(), [](ResourceId id) { return id == kNone; });
  if (empty) return nullptr;

  auto fb = std::make_unique<GlFramebuffer>();
  fb->target = t;
  fb->dsa = dsa_;
  if (dsa_) {
    glCreateFramebuffers(1, &fb->name);
  } else {
    // Bound for set-up; SetRenderTarget binds it to GL_DRAW_FRAMEBUFFER right after anyway.
    glGenFramebuffers(1, &fb->name);
    glBindFramebuffer(GL_FRAMEBUFFER, fb->name);
  }
  uint32_t layers = ~0u;
  for (uint32_t i = 0; i < uint32_t(kMaxColorAttachments); ++i) {
    const GlTexture* tex = res.texture(t.color[i]);
    if (tex == nullptr) continue;
    attach(dsa_, fb->name, GL_COLOR_ATTACHMENT0 + i, *tex, t);
    fb->attached |= uint8_t(1u << i);
    fb->colorFormat[i] = tex->desc.format;
    layers = std::min(layers, tex->desc.layers);
  }
  if (const GlTexture* depth = res.texture(t.depth)) {
    attach(dsa_, fb->name, GL_DEPTH_ATTACHMENT, *depth, t);
    layers = std::min(layers, depth->desc.layers);
  }
  fb->layerCount = layers == ~0u ? 1 : layers;
  // A new framebuffer's draw buffer 0 is COLOR_ATTACHMENT0 and the rest NONE (GL 4.6 §17.4.1);
  // make it the attached set explicitly.
  fb->drawMask = 0xff;  // unknown: forces the call below
  setDrawMask(*fb, fb->attached);
  // Nothing is read from the framebuffer (images are read from the textures), so no read buffer.
  // (GL 3.3 still checks the read buffer for completeness, §4.4.4.)
  if (dsa_) {
    glNamedFramebufferReadBuffer(fb->name, GL_NONE);
  } else {
    glReadBuffer(GL_NONE);
  }
  const GLenum status =
      dsa_ ? glCheckNamedFramebufferStatus(fb->name, GL_DRAW_FRAMEBUFFER) : glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    glDeleteFramebuffers(1, &fb->name);
    throw Error(std::string(where) + ": the render target is incomplete in GL: " + statusName(status));
  }
  fbos_.push_back(std::move(fb));
  return fbos_.back().get();
}

bool FramebufferCache::setDrawMask(GlFramebuffer& fb, uint8_t mask) {
  if (fb.drawMask == mask) return false;
  GLenum bufs[kMaxColorAttachments];
  for (uint32_t i = 0; i < uint32_t(kMaxColorAttachments); ++i)
    bufs[i] = (mask >> i & 1) ? GL_COLOR_ATTACHMENT0 + i : GL_NONE;
  if (fb.dsa) {
    glNamedFramebufferDrawBuffers(fb.name, kMaxColorAttachments, bufs);
  } else {
    glDrawBuffers(kMaxColorAttachments, bufs);  // fb is the bound draw framebuffer
  }
  fb.drawMask = mask;
  return true;
}

void FramebufferCache::releaseAll() {
  for (auto& f : fbos_) glDeleteFramebuffers(1, &f->name);
  fbos_.clear();
}

}  // namespace tessera::gl
