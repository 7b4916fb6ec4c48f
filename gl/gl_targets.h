// Render targets as GL framebuffer objects: one FBO per distinct RenderTarget of a frame, created on
// first use, checked for completeness, deleted at the end of the frame.
//
// Attachments follow the target exactly (GL 4.6 §9.2.8): layer == kLayered attaches whole array
// textures (glNamedFramebufferTexture: a layered framebuffer, gl_Layer selects the layer, §9.8); a
// fixed layer of an array uses glNamedFramebufferTextureLayer; a 2D texture uses
// glNamedFramebufferTexture. Draw buffer i is COLOR_ATTACHMENTi for every attached colour i.
// The 3.3 path (configure(false)) makes the same calls on the bound framebuffer: a new FBO is bound
// to GL_FRAMEBUFFER while it is set up, and draw-buffer changes apply to the bound draw framebuffer,
// which is always the one changed (the replay binds a target before clearing or drawing into it).
// Internal to gl/.
#pragma once

#include <memory>
#include <string_view>
#include <vector>

#include "gl/gl_api.h"
#include "gl/gl_resources.h"

namespace tessera::gl {

struct GlFramebuffer {
  RenderTarget target;
  GLuint name = 0;
  uint8_t attached = 0;     // bit i: color[i] is attached
  uint8_t drawMask = 0;     // bit i: draw buffer i is currently COLOR_ATTACHMENTi (else GL_NONE)
  uint32_t layerCount = 1;  // layered targets: the fewest layers of any attachment (GL 4.6 §9.8)
  Format colorFormat[kMaxColorAttachments] = {};
  bool dsa = true;          // made by the 4.5 path; else edited through the draw-framebuffer binding
};

class FramebufferCache {
 public:
  void configure(bool dsa) { dsa_ = dsa; }
  // The FBO of `t`, created on first use. Throws Error naming the frame, the command and the GL
  // status when GL calls it incomplete. Returns nullptr for the empty target (no attachments).
  GlFramebuffer* get(const RenderTarget& t, const FrameResources& res, std::string_view where);
  // Points draw buffer i at COLOR_ATTACHMENTi for each bit i of `mask` (GL_NONE elsewhere), if not so
  // already. Returns whether a GL call was made.
  static bool setDrawMask(GlFramebuffer& fb, uint8_t mask);
  void releaseAll();
  size_t size() const { return fbos_.size(); }

 private:
  std::vector<std::unique_ptr<GlFramebuffer>> fbos_;  // few per frame: a linear search is enough
  bool dsa_ = true;
};

}  // namespace tessera::gl
