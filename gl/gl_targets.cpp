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

void attach(GLuint fbo, GLenum point, const GlTexture& tex, const RenderTarget& t) {
  const GLint level = GLint(t.level);
  if (t.layer == kLayered || tex.desc.kind != TextureKind::Tex2DArray) {
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
  glCreateFramebuffers(1, &fb->name);
  uint32_t layers = ~0u;
  for (uint32_t i = 0; i < uint32_t(kMaxColorAttachments); ++i) {
    const GlTexture* tex = res.texture(t.color[i]);
    if (tex == nullptr) continue;
    attach(fb->name, GL_COLOR_ATTACHMENT0 + i, *tex, t);
    fb->attached |= uint8_t(1u << i);
    fb->colorFormat[i] = tex->desc.format;
    layers = std::min(layers, tex->desc.layers);
  }
  if (const GlTexture* depth = res.texture(t.depth)) {
    attach(fb->name, GL_DEPTH_ATTACHMENT, *depth, t);
    layers = std::min(layers, depth->desc.layers);
  }
  fb->layerCount = layers == ~0u ? 1 : layers;
  // A new framebuffer's draw buffer 0 is COLOR_ATTACHMENT0 and the rest NONE (GL 4.6 §17.4.1);
  // make it the attached set explicitly.
  fb->drawMask = 0xff;  // unknown: forces the call below
  setDrawMask(*fb, fb->attached);
  // Nothing is read from the framebuffer (images are read from the textures), so no read buffer.
  glNamedFramebufferReadBuffer(fb->name, GL_NONE);
  const GLenum status = glCheckNamedFramebufferStatus(fb->name, GL_DRAW_FRAMEBUFFER);
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
  glNamedFramebufferDrawBuffers(fb.name, kMaxColorAttachments, bufs);
  fb.drawMask = mask;
  return true;
}

void FramebufferCache::releaseAll() {
  for (auto& f : fbos_) glDeleteFramebuffers(1, &f->name);
  fbos_.clear();
}

}  // namespace tessera::gl
