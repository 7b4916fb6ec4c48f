#include "gl/gl_enums.h"

namespace tessera::gl {

// Every switch covers every valid enumerator; validation (raster/validate.h) rejects the rest
// before a list reaches the backend, so the fallbacks below are never reached for a valid list.

GlFormat glFormat(Format f) {
  switch (f) {
    case Format::RGBA8:
      return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE};
    case Format::R8:
      return {GL_R8, GL_RED, GL_UNSIGNED_BYTE};
    case Format::RG32F:
      return {GL_RG32F, GL_RG, GL_FLOAT};
    case Format::RGBA32F:
      return {GL_RGBA32F, GL_RGBA, GL_FLOAT};
    case Format::R32UI:
      return {GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT};
    case Format::D32F:
      return {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT};
    default:
      return {GL_NONE, GL_NONE, GL_NONE};
  }
}

GLenum glTarget(TextureKind k) {
  switch (k) {
    case TextureKind::Tex2D:
      return GL_TEXTURE_2D;
    case TextureKind::Tex2DArray:
      return GL_TEXTURE_2D_ARRAY;
    case TextureKind::Buffer:
      return GL_TEXTURE_BUFFER;
    default:
      return GL_NONE;
  }
}

GLenum glWrap(Wrap w) {
  switch (w) {
    case Wrap::Repeat:
      return GL_REPEAT;
    case Wrap::MirroredRepeat:
      return GL_MIRRORED_REPEAT;
    case Wrap::ClampToEdge:
      return GL_CLAMP_TO_EDGE;
    case Wrap::ClampToBorder:
      return GL_CLAMP_TO_BORDER;
    default:
      return GL_REPEAT;
  }
}

GLenum glFilter(Filter f) {
  switch (f) {
    case Filter::Nearest:
      return GL_NEAREST;
    case Filter::Linear:
      return GL_LINEAR;
    case Filter::NearestMipmapNearest:
      return GL_NEAREST_MIPMAP_NEAREST;
    case Filter::LinearMipmapNearest:
      return GL_LINEAR_MIPMAP_NEAREST;
    case Filter::NearestMipmapLinear:
      return GL_NEAREST_MIPMAP_LINEAR;
    case Filter::LinearMipmapLinear:
      return GL_LINEAR_MIPMAP_LINEAR;
    default:
      return GL_NEAREST;
  }
}

GLenum glCompareFunc(CompareFunc f) {
  switch (f) {
    case CompareFunc::Never:
      return GL_NEVER;
    case CompareFunc::Less:
      return GL_LESS;
    case CompareFunc::Equal:
      return GL_EQUAL;
    case CompareFunc::LEqual:
      return GL_LEQUAL;
    case CompareFunc::Greater:
      return GL_GREATER;
    case CompareFunc::NotEqual:
      return GL_NOTEQUAL;
    case CompareFunc::GEqual:
      return GL_GEQUAL;
    case CompareFunc::Always:
      return GL_ALWAYS;
    default:
      return GL_LESS;
  }
}

GLenum glBlendEquation(BlendEq e) {
  switch (e) {
    case BlendEq::Add:
      return GL_FUNC_ADD;
    case BlendEq::Subtract:
      return GL_FUNC_SUBTRACT;
    case BlendEq::ReverseSubtract:
      return GL_FUNC_REVERSE_SUBTRACT;
    case BlendEq::Min:
      return GL_MIN;
    case BlendEq::Max:
      return GL_MAX;
    default:
      return GL_FUNC_ADD;
  }
}

GLenum glBlendFactor(BlendFactor f) {
  switch (f) {
    case BlendFactor::Zero:
      return GL_ZERO;
    case BlendFactor::One:
      return GL_ONE;
    case BlendFactor::SrcColor:
      return GL_SRC_COLOR;
    case BlendFactor::OneMinusSrcColor:
      return GL_ONE_MINUS_SRC_COLOR;
    case BlendFactor::DstColor:
      return GL_DST_COLOR;
    case BlendFactor::OneMinusDstColor:
      return GL_ONE_MINUS_DST_COLOR;
    case BlendFactor::SrcAlpha:
      return GL_SRC_ALPHA;
    case BlendFactor::OneMinusSrcAlpha:
      return GL_ONE_MINUS_SRC_ALPHA;
    case BlendFactor::DstAlpha:
      return GL_DST_ALPHA;
    case BlendFactor::OneMinusDstAlpha:
      return GL_ONE_MINUS_DST_ALPHA;
    case BlendFactor::ConstantColor:
      return GL_CONSTANT_COLOR;
    case BlendFactor::OneMinusConstantColor:
      return GL_ONE_MINUS_CONSTANT_COLOR;
    case BlendFactor::ConstantAlpha:
      return GL_CONSTANT_ALPHA;
    case BlendFactor::OneMinusConstantAlpha:
      return GL_ONE_MINUS_CONSTANT_ALPHA;
    case BlendFactor::SrcAlphaSaturate:
      return GL_SRC_ALPHA_SATURATE;
    default:
      return GL_ONE;
  }
}

GLenum glIndexType(IndexType t) { return t == IndexType::U16 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT; }
uint32_t indexBytes(IndexType t) { return t == IndexType::U16 ? 2 : 4; }

}  // namespace tessera::gl
