#include "gl/gl_resources.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "base/error.h"

#include "gl/gl_enums.h"

namespace tessera::gl {

namespace {

// EXT_texture_compression_s3tc's tokens (glcorearb.h has only core enums).
constexpr GLenum kCompressedRgbDxt1 = 0x83F0;   // GL_COMPRESSED_RGB_S3TC_DXT1_EXT
constexpr GLenum kCompressedRgbaDxt5 = 0x83F3;  // GL_COMPRESSED_RGBA_S3TC_DXT5_EXT

// The RGB variant of DXT1: its three-colour code 3 is opaque black, which the oracle decodes (spec-choices C2).
GLenum compressedInternal(BcFormat f) { return f == BcFormat::BC1 ? kCompressedRgbDxt1 : kCompressedRgbaDxt5; }

}  // namespace

void FrameResources::grow(ResourceId id) {
  const size_t n = size_t(id) + 1;
  if (textures_.size() < n) {
    textures_.resize(n);
    buffers_.resize(n, 0);
    samplers_.resize(n, 0);
  }
}

const uint8_t* FrameResources::zeros(size_t bytes) {
  if (zeros_.size() < bytes) zeros_.assign(bytes, 0);
  return zeros_.data();
}

void FrameResources::createTexture(ResourceId id, const TextureDesc& d) {
  grow(id);
  GlTexture& t = textures_[id];
  t.desc = d;
  t.target = glTarget(d.kind);
  const GlFormat f = glFormat(d.format);
  if (d.compression != BcFormat::None) {
    createCompressedTexture(id, t);
    return;
  }
  if (!dsa_) {
    createTextureBound(t, f);
    return;
  }
  glCreateTextures(t.target, 1, &t.name);
  if (d.kind == TextureKind::Buffer) {
    // GL 4.6 §8.9: the texels are the buffer's bytes, N = min(size / texelBytes, MAX_TEXTURE_BUFFER_SIZE),
    // the same N the oracle uses (sample.cpp fetchBase).
    glTextureBuffer(t.name, f.internal, buffer(d.buffer));
    return;
  }
  const GLsizei levels = GLsizei(d.levels), w = GLsizei(d.width), h = GLsizei(d.height);
  if (d.kind == TextureKind::Tex2DArray) {
    glTextureStorage3D(t.name, levels, f.internal, w, h, GLsizei(d.layers));
  } else {
    glTextureStorage2D(t.name, levels, f.internal, w, h);
  }
  // Immutable storage already clamps the effective max level to levels - 1 (GL 4.6 §8.17); set it
  // anyway so the texture is complete by the same rule on any implementation.
  glTextureParameteri(t.name, GL_TEXTURE_MAX_LEVEL, GLint(levels - 1));
  // The oracle's storage starts zeroed (TextureData); GL's is undefined until written (§8.19 allows
  // clearing with a NULL data pointer: every component becomes zero).
  for (GLint l = 0; l < levels; ++l) glClearTexImage(t.name, l, f.format, f.type, nullptr);
}

// The 3.3 path of createTexture: the texture on the scratch unit's target, every level specified
// with zeros (mutable storage, GL 3.3 §3.8.3; the oracle's storage starts zeroed).
void FrameResources::createTextureBound(GlTexture& t, const GlFormat& f) {
  const TextureDesc& d = t.desc;
  glGenTextures(1, &t.name);
  glBindTexture(t.target, t.name);  // kScratchUnit is the active unit between commands
  if (d.kind == TextureKind::Buffer) {
    glTexBuffer(GL_TEXTURE_BUFFER, f.internal, buffer(d.buffer));
    return;
  }
  const uint8_t* z = zeros(size_t(d.width) * d.height * d.layers * texelBytes(d.format));
  for (GLint l = 0; l < GLint(d.levels); ++l) {
    const GLsizei w = GLsizei(levelWidth(d, uint32_t(l))), h = GLsizei(levelHeight(d, uint32_t(l)));
    if (d.kind == TextureKind::Tex2DArray) {
      glTexImage3D(GL_TEXTURE_2D_ARRAY, l, GLint(f.internal), w, h, GLsizei(d.layers), 0, f.format, f.type, z);
    } else {
      glTexImage2D(GL_TEXTURE_2D, l, GLint(f.internal), w, h, 0, f.format, f.type, z);
    }
  }
  // Mutable storage is complete only up to GL_TEXTURE_MAX_LEVEL (default 1000): levels - 1.
  glTexParameteri(t.target, GL_TEXTURE_MAX_LEVEL, GLint(d.levels) - 1);
}

// A validated compressed texture is Tex2D (validate.cpp). Every level starts as zero blocks: a compressed
// format cannot be cleared (glClearTexImage refuses it), and zero blocks are what the oracle's storage holds
// decoded (TextureData).
void FrameResources::createCompressedTexture(ResourceId id, GlTexture& t) {
  const TextureDesc& d = t.desc;
  if (!s3tc_)
    throw Error("GL backend: texture " + std::to_string(id) + " is " + bcFormatName(d.compression) +
                "-compressed, but this context (" + renderer_ +
                ") lacks GL_EXT_texture_compression_s3tc, so it cannot upload S3TC blocks as they are; "
                "decoding them here would compare the oracle with itself (docs/gl-backend.md)");
  const GLenum internal = compressedInternal(d.compression);
  const GLsizei levels = GLsizei(d.levels);
  if (dsa_) {
    glCreateTextures(GL_TEXTURE_2D, 1, &t.name);
    glTextureStorage2D(t.name, levels, internal, GLsizei(d.width), GLsizei(d.height));
    glTextureParameteri(t.name, GL_TEXTURE_MAX_LEVEL, levels - 1);
  } else {
    glGenTextures(1, &t.name);
    glBindTexture(GL_TEXTURE_2D, t.name);  // kScratchUnit is the active unit between commands
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, levels - 1);
  }
  for (GLint l = 0; l < levels; ++l) {
    const GLsizei w = GLsizei(levelWidth(d, uint32_t(l))), h = GLsizei(levelHeight(d, uint32_t(l)));
    const GLsizei bytes = GLsizei(uploadBytes(d, uint32_t(l)));
    if (dsa_)
      glCompressedTextureSubImage2D(t.name, l, 0, 0, w, h, internal, bytes, zeros(size_t(bytes)));
    else
      glCompressedTexImage2D(GL_TEXTURE_2D, l, internal, w, h, 0, bytes, zeros(size_t(bytes)));
  }
}

void FrameResources::uploadTexture(const UploadTexture& u, std::span<const uint8_t> texels) {
  const GlTexture& t = textures_[u.id];
  if (t.desc.compression != BcFormat::None) {
    // The blocks as recorded: GL decodes them by its own rounding, which the cross-check bounds (BC_INTERPOLANT).
    const GLenum internal = compressedInternal(t.desc.compression);
    const GLsizei w = GLsizei(levelWidth(t.desc, u.level)), h = GLsizei(levelHeight(t.desc, u.level));
    if (dsa_) {
      glCompressedTextureSubImage2D(t.name, GLint(u.level), 0, 0, w, h, internal, GLsizei(texels.size()), texels.data());
    } else {
      glBindTexture(GL_TEXTURE_2D, t.name);
      glCompressedTexSubImage2D(GL_TEXTURE_2D, GLint(u.level), 0, 0, w, h, internal, GLsizei(texels.size()),
                                texels.data());
    }
    return;
  }
  const GlFormat f = glFormat(t.desc.format);
  const GLsizei w = GLsizei(levelWidth(t.desc, u.level)), h = GLsizei(levelHeight(t.desc, u.level));
  if (!dsa_) {
    glBindTexture(t.target, t.name);
    if (t.desc.kind == TextureKind::Tex2DArray) {
      glTexSubImage3D(GL_TEXTURE_2D_ARRAY, GLint(u.level), 0, 0, GLint(u.layer), w, h, 1, f.format, f.type,
                      texels.data());
    } else {
      glTexSubImage2D(GL_TEXTURE_2D, GLint(u.level), 0, 0, w, h, f.format, f.type, texels.data());
    }
    return;
  }
  // Rows bottom first and tightly packed: GL's order with GL_UNPACK_ALIGNMENT 1 (gl_state.cpp).
  if (t.desc.kind == TextureKind::Tex2DArray) {
    glTextureSubImage3D(t.name, GLint(u.level), 0, 0, GLint(u.layer), w, h, 1, f.format, f.type, texels.data());
  } else {
    glTextureSubImage2D(t.name, GLint(u.level), 0, 0, w, h, f.format, f.type, texels.data());
  }
}

void FrameResources::createBuffer(ResourceId id, uint64_t size) {
  grow(id);
  if (!dsa_) {
    // Binding creates the object (GL 3.3 §2.9); GL_COPY_WRITE_BUFFER disturbs no vertex or index
    // binding. glBufferData with zeros: the oracle's buffers start zeroed.
    glGenBuffers(1, &buffers_[id]);
    glBindBuffer(GL_COPY_WRITE_BUFFER, buffers_[id]);
    glBufferData(GL_COPY_WRITE_BUFFER, GLsizeiptr(size), size ? zeros(size_t(size)) : nullptr, GL_DYNAMIC_DRAW);
    return;
  }
  glCreateBuffers(1, &buffers_[id]);
  // A zero-size buffer keeps GL's initial empty data store (glNamedBufferStorage rejects size 0), so
  // a buffer texture over it has 0 texels, like the oracle's.
  if (size == 0) return;
  glNamedBufferStorage(buffers_[id], GLsizeiptr(size), nullptr, GL_DYNAMIC_STORAGE_BIT);
  // Zero it like the oracle (GL 4.6 §6.7: NULL data clears to zero).
  glClearNamedBufferData(buffers_[id], GL_R8, GL_RED, GL_UNSIGNED_BYTE, nullptr);
}

void FrameResources::uploadBuffer(const UploadBuffer& u, std::span<const uint8_t> bytes) {
  if (bytes.empty()) return;
  if (!dsa_) {
    glBindBuffer(GL_COPY_WRITE_BUFFER, buffers_[u.id]);
    glBufferSubData(GL_COPY_WRITE_BUFFER, GLintptr(u.offset), GLsizeiptr(bytes.size()), bytes.data());
    return;
  }
  glNamedBufferSubData(buffers_[u.id], GLintptr(u.offset), GLsizeiptr(bytes.size()), bytes.data());
}

void FrameResources::createSampler(ResourceId id, const SamplerState& s) {
  grow(id);
  GLuint& n = samplers_[id];
  if (dsa_) {
    glCreateSamplers(1, &n);
  } else {
    glGenSamplers(1, &n);  // GL 3.3 §3.8.2: GenSamplers creates the objects
  }
  // GL 4.6 §8.2, Table 23.18: every parameter the oracle's SamplerState holds, nothing else (the
  // rest keeps GL's defaults: no compare mode, no anisotropy, wrap R unused by 2D lookups).
  glSamplerParameteri(n, GL_TEXTURE_WRAP_S, GLint(glWrap(s.wrapS)));
  glSamplerParameteri(n, GL_TEXTURE_WRAP_T, GLint(glWrap(s.wrapT)));
  glSamplerParameteri(n, GL_TEXTURE_MIN_FILTER, GLint(glFilter(s.minFilter)));
  glSamplerParameteri(n, GL_TEXTURE_MAG_FILTER, GLint(glFilter(s.magFilter)));
  glSamplerParameterf(n, GL_TEXTURE_MIN_LOD, s.minLod);
  glSamplerParameterf(n, GL_TEXTURE_MAX_LOD, s.maxLod);
  glSamplerParameterf(n, GL_TEXTURE_LOD_BIAS, s.lodBias);
  // Float border (fv): for R32UI the oracle reads borderColor[0]'s bits as the integer, which is
  // what Mesa does with a border set through the float entry point (spec-choices T14).
  glSamplerParameterfv(n, GL_TEXTURE_BORDER_COLOR, s.borderColor.data());
}

const GlTexture* FrameResources::texture(ResourceId id) const {
  return id < textures_.size() && textures_[id].name != 0 ? &textures_[id] : nullptr;
}
GLuint FrameResources::buffer(ResourceId id) const { return id < buffers_.size() ? buffers_[id] : 0; }
GLuint FrameResources::sampler(ResourceId id) const { return id < samplers_.size() ? samplers_[id] : 0; }

void FrameResources::releaseExcept(std::span<const ResourceId> keep) {
  std::vector<GlTexture> kept(textures_.size());
  for (ResourceId id = 0; id < textures_.size(); ++id) {
    GlTexture& t = textures_[id];
    if (t.name == 0) continue;
    if (std::find(keep.begin(), keep.end(), id) != keep.end()) {
      kept[id] = t;
    } else {
      glDeleteTextures(1, &t.name);
    }
  }
  // Deleting a buffer still used by a kept buffer texture only removes its name; the data store
  // lives on with the texture (GL 4.6 §5.1.2). Presented images are never buffer textures anyway.
  for (GLuint& b : buffers_)
    if (b != 0) glDeleteBuffers(1, &b);
  for (GLuint& s : samplers_)
    if (s != 0) glDeleteSamplers(1, &s);
  textures_ = std::move(kept);
  buffers_.assign(textures_.size(), 0);
  samplers_.assign(textures_.size(), 0);
}

size_t FrameResources::liveObjects() const {
  size_t n = 0;
  for (const GlTexture& t : textures_) n += t.name != 0;
  for (GLuint b : buffers_) n += b != 0;
  for (GLuint s : samplers_) n += s != 0;
  return n;
}

}  // namespace tessera::gl
