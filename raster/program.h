// Programs: the C++ vertex / geometry / fragment stages, each program under a stable name so the
// GL backend can supply a GLSL twin with the same name, uniforms and attributes.
//
// Common principles
// - Uniforms are vec4 slots (kMaxUniformSlots); a program documents its slot layout in its file.
// - Vertex attributes arrive as vec4 floats, missing components filled with (0, 0, 0, 1) as GL does.
// - Smooth varyings are perspective-correct; flat varyings are unsigned integers taken from the
//   provoking vertex (the last vertex, GL's default GL_LAST_VERTEX_CONVENTION).
// - Fragment programs run on batches of 2x2 quads (helper pixels included), so implicit-LOD
//   texture lookups take their derivatives from the quad, like GLSL's texture().
// - Stages are called once per batch (vertices of a draw, quads of a triangle in a tile), never per
//   pixel through a virtual call.
// - Fragment depth: every quad carries its window depth per pixel (Quad::z, gl_FragCoord.z). A
//   program that declares writesDepth() sets QuadOut::depth (gl_FragDepth); the depth test and the
//   depth write then use that value, clamped to the depth range (docs/spec-choices.md F11).
// Does not implement: the pipeline around them (cpu_backend.h).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "raster/limits.h"
#include "raster/sample.h"

namespace tessera {

using Vec4 = std::array<float, 4>;

struct ShadeContext {
  const Vec4* uniforms = nullptr;  // kMaxUniformSlots slots
  std::array<TexUnit, kMaxTextureUnits> units{};
};

struct VertexIn {
  Vec4 attr[kMaxAttribs];
  uint32_t vertexId;  // gl_VertexID (the index value for indexed draws)
};

struct VertexOut {
  Vec4 pos;                                  // gl_Position, clip space
  float clip[kMaxClipDistances];             // gl_ClipDistance (only enabled planes are used)
  float var[kMaxVaryings];                   // smooth varyings
  uint32_t flat[kMaxFlatVaryings];           // flat integer varyings
};

// One 2x2 quad of fragments. Pixel p of the quad sits at (x + (p & 1), y + (p >> 1)) in GL window
// coordinates (y up). Helper pixels (coverage bit clear) are shaded too; their outputs are dropped.
struct Quad {
  int32_t x, y;
  uint8_t coverage;                  // bit p: pixel p is inside the primitive
  // gl_FragCoord.z per pixel: the window depth z_w of GL 4.6 §15.2.2 ("Shader Inputs": gl_FragCoord
  // holds (x_w, y_w, z_w, 1/w_c)), i.e. exactly the value the depth test compares (§17.3.4) when the
  // program writes no depth: interpolated without perspective (§14.6.1) from the vertices' z_w of
  // §13.8.1, depth range [0, 1]. Helper pixels get the same plane extrapolated.
  float z[4];
  float var[4][kMaxVaryings];        // interpolated varyings per pixel
};

struct QuadOut {
  // Per attachment, per pixel, RGBA as float bits or uint (decided by the attachment's format).
  union Value { float f[4]; uint32_t u[4]; };
  Value color[kMaxColorAttachments][4];
  // gl_FragDepth per pixel, read only for a program whose writesDepth() is true. The pipeline presets
  // it to Quad::z before the call, so a pixel the program leaves alone keeps the interpolated depth
  // (GL leaves it undefined, GL 4.6 §15.2.3; docs/spec-choices.md F11).
  float depth[4];
  uint8_t discard;  // bit p: pixel p discarded by the program
};

struct QuadBatch {
  const Quad* quads;
  QuadOut* out;
  size_t count;
  uint32_t flat[kMaxFlatVaryings];  // from the provoking vertex
  uint32_t primitiveId;             // gl_PrimitiveID: triangle index within the draw
  uint32_t layer;                   // gl_Layer
  bool frontFacing;
};

class Program {
 public:
  virtual ~Program() = default;
  virtual std::string_view name() const = 0;
  virtual int varyingCount() const = 0;      // smooth varyings used, <= kMaxVaryings
  virtual int colorOutputs() const { return 1; }
  virtual bool hasGeometryStage() const { return false; }
  // The fragment stage writes QuadOut::depth (gl_FragDepth): the depth test runs after shading, on
  // that value (docs/spec-choices.md F11). Programs that do not write depth keep the early test.
  virtual bool writesDepth() const { return false; }
  // The fragment stage reads Quad::z (gl_FragCoord.z). Provenance mode then runs its lower- and
  // upper-bound passes on z -/+ the depth precision (docs/crosscheck.md, DEPTH_NEAR_EQUAL), so the
  // program must be monotone (non-decreasing) in z, as it must be in what it samples.
  virtual bool readsFragDepth() const { return false; }
  // The program's outputs are non-decreasing in every value it samples, so its runs on the sampler's
  // lower and upper bounds bound every legal output (docs/crosscheck.md). A program that is not
  // (atlas_sprite_ao: occlusion counts depth comparisons) gets, in provenance mode, the whole output
  // range at every fragment that read a texel carrying an interval (INPUT_INTERVAL); where every texel
  // it read is exact, its single result is exact.
  virtual bool monotoneInSamples() const { return true; }
  // The fragment stage may set QuadOut::discard under the draw's uniforms (ctx). False lets the
  // rasterizer shade only the fragments that stay visible at the end of a run of such draws
  // (rast.cpp, "visibility runs"); a program that can discard must keep the default, since its
  // fragments' depth writes then depend on shading.
  virtual bool mayDiscard(const ShadeContext& ctx) const {
    (void)ctx;
    return true;
  }

  // The vertex attribute locations shadeVertices reads, one bit per location (bit l: location l). The
  // vertex stage fetches only these (cpu_backend.cpp, fetchGroup); the others keep GL's default
  // (0, 0, 0, 1), which the program never reads, so its outputs are those of a full fetch. The default,
  // every location, is always right; a program that declares fewer must read nothing else
  // (ProgramAttributes.* shades every built-in program with and without the undeclared ones).
  virtual uint32_t attributesRead() const { return ~0u; }
  virtual void shadeVertices(std::span<const VertexIn> in, std::span<VertexOut> out, const ShadeContext& ctx) const = 0;
  // Optional geometry stage, once per triangle after vertex shading and before clipping. May change
  // positions, clip distances and varyings, and choose the output layer. Returns false to drop it.
  virtual bool shadeTriangle(VertexOut (&v)[3], uint32_t primitiveId, uint32_t& layer, const ShadeContext& ctx) const {
    (void)v, (void)primitiveId, (void)layer, (void)ctx;
    return true;
  }
  virtual void shadeQuads(const QuadBatch& batch, const ShadeContext& ctx) const = 0;
};

// The registry of built-in programs (programs/*.cpp). nullptr for an unknown name.
const Program* findProgram(std::string_view name);
std::vector<std::string_view> programNames();

}  // namespace tessera
