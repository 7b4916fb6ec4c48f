// Plain value types shared by the command list, the CPU backend and (later) the GL backend:
// formats, sampler / blend / depth / raster state, vertex layout.
//
// Implements: the vocabulary of a frame. Every enum maps one to one onto a GL enum so that a
// recorded frame can be replayed on OpenGL without interpretation.
// Does not implement: any behaviour (see sample.h, fragops.h, setup.h).
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

namespace tessera {

// Texel / render-target formats. Sizes in bytes per texel are fixed (texelBytes()).
enum class Format : uint8_t {
  RGBA8 = 0,    // GL_RGBA8, unsigned normalized
  R8 = 1,       // GL_R8
  RG32F = 2,    // GL_RG32F
  RGBA32F = 3,  // GL_RGBA32F
  R32UI = 4,    // GL_R32UI, integer: NEAREST only, never blended
  D32F = 5,     // GL_DEPTH_COMPONENT32F, depth attachments only
  Count
};
constexpr int kFormatCount = static_cast<int>(Format::Count);

inline constexpr uint32_t texelBytes(Format f) {
  switch (f) {
    case Format::RGBA8: return 4;
    case Format::R8: return 1;
    case Format::RG32F: return 8;
    case Format::RGBA32F: return 16;
    case Format::R32UI: return 4;
    case Format::D32F: return 4;
    default: return 0;
  }
}
inline constexpr int channelCount(Format f) {
  switch (f) {
    case Format::RGBA8: return 4;
    case Format::R8: return 1;
    case Format::RG32F: return 2;
    case Format::RGBA32F: return 4;
    case Format::R32UI: return 1;
    case Format::D32F: return 1;
    default: return 0;
  }
}
inline constexpr bool isUnorm(Format f) { return f == Format::RGBA8 || f == Format::R8; }
inline constexpr bool isFloat(Format f) { return f == Format::RG32F || f == Format::RGBA32F || f == Format::D32F; }
inline constexpr bool isInteger(Format f) { return f == Format::R32UI; }
std::string_view formatName(Format f);

enum class TextureKind : uint8_t { Tex2D = 0, Tex2DArray = 1, Buffer = 2, Count };

enum class Wrap : uint8_t { Repeat = 0, MirroredRepeat = 1, ClampToEdge = 2, ClampToBorder = 3, Count };
enum class Filter : uint8_t {
  Nearest = 0,
  Linear = 1,
  NearestMipmapNearest = 2,
  LinearMipmapNearest = 3,
  NearestMipmapLinear = 4,
  LinearMipmapLinear = 5,
  Count
};
inline constexpr bool usesMipmaps(Filter f) { return f >= Filter::NearestMipmapNearest; }

// GL sampler object state (GL 4.6 §8.2). LOD values are floats as in GL; the sampler
// quantizes them to 8 fractional bits once (docs/spec-choices.md, "LOD").
struct SamplerState {
  Wrap wrapS = Wrap::Repeat;
  Wrap wrapT = Wrap::Repeat;
  Filter minFilter = Filter::NearestMipmapLinear;  // GL default
  Filter magFilter = Filter::Linear;               // GL default; only Nearest/Linear are legal
  float minLod = -1000.0f;
  float maxLod = 1000.0f;
  float lodBias = 0.0f;
  std::array<float, 4> borderColor{0, 0, 0, 0};
  bool operator==(const SamplerState&) const = default;
};

enum class CompareFunc : uint8_t { Never = 0, Less, Equal, LEqual, Greater, NotEqual, GEqual, Always, Count };

struct DepthState {
  bool test = false;
  bool write = true;  // glDepthMask default GL_TRUE; only effective when test is enabled (GL §17.3.4)
  CompareFunc func = CompareFunc::Less;
  bool operator==(const DepthState&) const = default;
};

enum class BlendEq : uint8_t { Add = 0, Subtract, ReverseSubtract, Min, Max, Count };
enum class BlendFactor : uint8_t {
  Zero = 0, One, SrcColor, OneMinusSrcColor, DstColor, OneMinusDstColor, SrcAlpha, OneMinusSrcAlpha,
  DstAlpha, OneMinusDstAlpha, ConstantColor, OneMinusConstantColor, ConstantAlpha, OneMinusConstantAlpha,
  SrcAlphaSaturate, Count
};

struct BlendState {
  bool enabled = false;
  BlendEq eqRgb = BlendEq::Add, eqAlpha = BlendEq::Add;
  BlendFactor srcRgb = BlendFactor::One, dstRgb = BlendFactor::Zero;
  BlendFactor srcAlpha = BlendFactor::One, dstAlpha = BlendFactor::Zero;
  std::array<float, 4> constant{0, 0, 0, 0};
  bool operator==(const BlendState&) const = default;
};

enum class CullMode : uint8_t { None = 0, Back, Front, Count };

// Rasterizer state that is not depth or blend: culling, winding, enabled user clip distances.
struct RasterState {
  CullMode cull = CullMode::None;
  bool frontCcw = true;      // glFrontFace(GL_CCW)
  uint8_t clipMask = 0;      // bit i = GL_CLIP_DISTANCE0 + i enabled
  bool operator==(const RasterState&) const = default;
};

struct Rect {
  int32_t x = 0, y = 0, w = 0, h = 0;
  bool operator==(const Rect&) const = default;
};

struct ScissorState {
  bool enabled = false;
  Rect rect{};
  bool operator==(const ScissorState&) const = default;
};

enum class AttribType : uint8_t { F32 = 0, U32 = 1, Count };

// One vertex attribute (glVertexAttribPointer / glVertexAttribIPointer with a buffer offset).
// U32 attributes reach programs as exactly representable floats, so values must stay < 2^24.
struct VertexAttrib {
  uint8_t location = 0;
  uint8_t components = 0;  // 0 = disabled, else 1..4
  AttribType type = AttribType::F32;
  uint32_t offset = 0;  // bytes from the start of a vertex
  bool operator==(const VertexAttrib&) const = default;
};

constexpr int kMaxAttribs = 8;
struct VertexLayout {
  uint32_t stride = 0;  // bytes
  std::array<VertexAttrib, kMaxAttribs> attribs{};
  bool operator==(const VertexLayout&) const = default;
};

enum class IndexType : uint8_t { U16 = 0, U32 = 1, Count };

}  // namespace tessera
