// GL objects of one frame by command-list id: textures, buffers and samplers, created, zeroed and
// uploaded with DSA (GL 4.5 §6, §8), and deleted at the end of the frame. On the 3.3 path
// (configure(false)) the same through bind points: textures on kScratchUnit (gl_state.h), buffers on
// GL_COPY_WRITE_BUFFER, mutable storage zeroed by uploading zeros (GL 3.3 has neither immutable
// storage nor clears of textures and buffers).
//
// Pinned to the oracle (docs/gl-backend.md): storage is immutable (glTextureStorage*,
// glNamedBufferStorage) and starts zeroed like the oracle's, because GL leaves fresh storage
// undefined; every level is uploaded by the list (never glGenerateMipmap, spec-choices T13);
// GL_TEXTURE_MAX_LEVEL = levels - 1; a texture's own sampling parameters stay GL's defaults, which
// equal SamplerState{} (the oracle's rule for a unit without a sampler). A compressed texture
// (TextureDesc::compression) has the S3TC internal format, starts as all-zero blocks (what the oracle's
// storage decodes to) and receives the list's blocks as they are (glCompressedTextureSubImage2D); a context
// without EXT_texture_compression_s3tc refuses it with an Error.
// Internal to gl/.
#pragma once

#include <span>
#include <string>
#include <utility>
#include <vector>

#include "gl/gl_api.h"
#include "gl/gl_enums.h"
#include "raster/command_list.h"

namespace tessera::gl {

struct GlTexture {
  GLuint name = 0;
  GLenum target = GL_NONE;
  TextureDesc desc;
};

class FrameResources {
 public:
  // s3tc: the context has GL_EXT_texture_compression_s3tc (named with `renderer` when it has not).
  void configure(bool dsa, bool s3tc = false, std::string renderer = {}) {
    dsa_ = dsa;
    s3tc_ = s3tc;
    renderer_ = std::move(renderer);
  }
  void createTexture(ResourceId id, const TextureDesc& desc);
  void uploadTexture(const UploadTexture& u, std::span<const uint8_t> texels);
  void createBuffer(ResourceId id, uint64_t size);
  void uploadBuffer(const UploadBuffer& u, std::span<const uint8_t> bytes);
  void createSampler(ResourceId id, const SamplerState& s);

  // nullptr / 0 for ids that name no such object.
  const GlTexture* texture(ResourceId id) const;
  GLuint buffer(ResourceId id) const;
  GLuint sampler(ResourceId id) const;

  // Deletes every object except the textures listed in `keep` (the presented images).
  void releaseExcept(std::span<const ResourceId> keep);
  void releaseAll() { releaseExcept({}); }
  // GL names currently held (for leak tests).
  size_t liveObjects() const;

 private:
  void grow(ResourceId id);
  void createTextureBound(GlTexture& t, const GlFormat& f);
  void createCompressedTexture(ResourceId id, GlTexture& t);
  std::vector<GlTexture> textures_;  // indexed by id
  std::vector<GLuint> buffers_, samplers_;
  bool dsa_ = true;
  bool s3tc_ = false;
  std::string renderer_;
  std::vector<uint8_t> zeros_;  // 3.3 path: the zero bytes new storage is initialised with
  const uint8_t* zeros(size_t bytes);
};

}  // namespace tessera::gl
