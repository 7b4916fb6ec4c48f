#include "gl/gl_state.h"

#include "gl/gl_enums.h"

namespace tessera::gl {

void pinContextState(bool dsa) {
  glDisable(GL_DITHER);  // on by default (GL 4.6 §17.3.9); the oracle does not dither (F7)
  glDisable(GL_FRAMEBUFFER_SRGB);
  glDisable(GL_PRIMITIVE_RESTART);
  if (dsa) glDisable(GL_PRIMITIVE_RESTART_FIXED_INDEX);  // GL 4.3; GL 3.3 has no such mode
  glDisable(GL_DEPTH_CLAMP);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_COLOR_LOGIC_OP);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_RASTERIZER_DISCARD);
  glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
  glDisable(GL_SAMPLE_COVERAGE);
  if (dsa) glDisable(GL_SAMPLE_SHADING);  // GL 4.0; off by default
  glDisable(GL_MULTISAMPLE);  // every attachment is single-sampled anyway
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glProvokingVertex(GL_LAST_VERTEX_CONVENTION);
  if (dsa) glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);  // GL 4.5; GL 3.3's fixed convention
  if (!dsa) glActiveTexture(GL_TEXTURE0 + kScratchUnit);
  glDepthRange(0.0, 1.0);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
}

void resetFrameState(bool dsa) {
  applyViewport(Rect{});
  applyScissor(ScissorState{});
  applyDepth(DepthState{});
  applyBlend(BlendState{});
  applyRaster(RasterState{});
  unbindAllUnits(dsa);
  glUseProgram(0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
}

void unbindAllUnits(bool dsa) {
  if (dsa) {
    // One call each resets every unit's binding of every target (GL 4.6 §8.1: a NULL list binds 0).
    glBindTextures(0, kMaxTextureUnits, nullptr);
    glBindSamplers(0, kMaxTextureUnits, nullptr);
    return;
  }
  for (int u = 0; u < kMaxTextureUnits; ++u) {
    bindTextureOnUnit(false, u, GL_NONE, 0);
    glBindSampler(GLuint(u), 0);
  }
}

void bindTextureOnUnit(bool dsa, int unit, GLenum target, GLuint name) {
  if (dsa) {
    glBindTextureUnit(GLuint(unit), name);
    return;
  }
  glActiveTexture(GLenum(GL_TEXTURE0 + unit));
  if (name == 0) {
    // The command list's texture kinds are the only targets the backend ever binds.
    for (GLenum t : {GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY, GL_TEXTURE_BUFFER}) glBindTexture(t, 0);
  } else {
    glBindTexture(target, name);
  }
  glActiveTexture(GL_TEXTURE0 + kScratchUnit);
}

void applyViewport(const Rect& r) { glViewport(r.x, r.y, r.w, r.h); }

void applyScissor(const ScissorState& s) {
  if (s.enabled) {
    glEnable(GL_SCISSOR_TEST);
  } else {
    glDisable(GL_SCISSOR_TEST);
  }
  glScissor(s.rect.x, s.rect.y, s.rect.w, s.rect.h);
}

void applyDepth(const DepthState& d) {
  // GL 4.6 §17.3.4: with the test disabled the depth buffer is never written, whatever the mask:
  // the oracle's rule (F1), so the mask can follow `write` directly.
  if (d.test) {
    glEnable(GL_DEPTH_TEST);
  } else {
    glDisable(GL_DEPTH_TEST);
  }
  glDepthFunc(glCompareFunc(d.func));
  glDepthMask(d.write ? GL_TRUE : GL_FALSE);
}

void applyBlend(const BlendState& b) {
  // GL_BLEND applies to every draw buffer; integer attachments are never blended (GL 4.6 §17.3.6,
  // the oracle's F4).
  if (b.enabled) {
    glEnable(GL_BLEND);
  } else {
    glDisable(GL_BLEND);
  }
  glBlendEquationSeparate(glBlendEquation(b.eqRgb), glBlendEquation(b.eqAlpha));
  glBlendFuncSeparate(glBlendFactor(b.srcRgb), glBlendFactor(b.dstRgb), glBlendFactor(b.srcAlpha),
                      glBlendFactor(b.dstAlpha));
  glBlendColor(b.constant[0], b.constant[1], b.constant[2], b.constant[3]);
}

void applyRaster(const RasterState& r) {
  if (r.cull == CullMode::None) {
    glDisable(GL_CULL_FACE);
  } else {
    glEnable(GL_CULL_FACE);
    glCullFace(r.cull == CullMode::Back ? GL_BACK : GL_FRONT);
  }
  glFrontFace(r.frontCcw ? GL_CCW : GL_CW);
  for (int i = 0; i < kMaxClipDistances; ++i) {
    if (r.clipMask >> i & 1) {
      glEnable(GLenum(GL_CLIP_DISTANCE0 + i));
    } else {
      glDisable(GLenum(GL_CLIP_DISTANCE0 + i));
    }
  }
}

}  // namespace tessera::gl
