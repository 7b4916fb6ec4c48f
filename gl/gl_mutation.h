// Deliberate, realistic faults for the GL backend (mutation testing, docs/mutants.md): each
// Mutation imitates one driver bug by a small change to a GLSL twin (a text substitution applied
// before the twin compiles) or to the GL state the backend sets, so that `tessera mutants` can show
// which of them the cross-check's verdict catches.
//
// Implements: the Mutation record, the catalogue, and the hooks the backend calls when
// GlOptions::mutation is set: applyToSource() on a twin's text before its stages compile
// (gl_programs.cpp), applyToState() after each command has set its GL state and on every sampler
// it creates, and applyToUpload() on the bytes of every texture upload (gl_backend.cpp). With no
// mutation the backend calls no hook, so it behaves exactly as without this file.
// Does not implement: running mutants or judging them (verify/mutants.h).
//
// Internal to gl/ and the mutation runner; a mutation never reaches a normal render.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "raster/command_list.h"

namespace tessera::gl {

// One substitution in one twin: every occurrence of `find` becomes `replace` in every stage's text.
struct SourceEdit {
  std::string_view program;  // the twin's program name (raster/programs/<program>.glsl)
  std::string_view find;
  std::string_view replace;
};

// The GL state faults (applied by applyToState).
enum class StateFault {
  None,
  FillRuleFlipped,        // viewport moved by one sub-pixel step (+1/256, -1/256) with glViewportIndexedf
  ViewportOffByOne,       // viewport origin y + 1
  ScissorOffByOne,        // scissor width + 1 (an inclusive right edge)
  DepthStrictSwapped,     // LESS <-> LEQUAL and GREATER <-> GEQUAL
  ProvokingFirst,         // glProvokingVertex(GL_FIRST_VERTEX_CONVENTION)
  FrontFaceFlipped,       // glFrontFace with CW and CCW exchanged
  BlendSubtractSwapped,   // SUBTRACT <-> REVERSE_SUBTRACT
  WrapRepeatMirrored,     // sampler: REPEAT <-> MIRRORED_REPEAT
  WrapEdgeBorder,         // sampler: CLAMP_TO_EDGE <-> CLAMP_TO_BORDER
  FilterNearestLinear,    // sampler: NEAREST <-> LINEAR in the mag filter and the min filter's texel part
  MipmapLinearNearest,    // sampler: *_MIPMAP_LINEAR -> *_MIPMAP_NEAREST
  SamplerLodBiasIgnored,  // sampler: TEXTURE_LOD_BIAS 0
  BorderColorIgnored,     // sampler: border colour (0, 0, 0, 0)
  Bc1EndpointsSwapped,    // upload: every BC1 block's color0 and color1 exchanged (codes unchanged)
};

// Uniforms a mutated twin may declare; applyToState sets them on the current program after every
// UseProgram, SetViewport and SetBlendState (a twin without them has location -1 and is untouched).
inline constexpr const char* kMutationViewportUniform = "tessera_mutViewport";  // vec4: GL_VIEWPORT
inline constexpr const char* kMutationBlendUniform = "tessera_mutBlend";        // float: 1 while GL_BLEND is on

struct Mutation {
  std::string_view name;        // stable, snake_case: the CLI's --mutants and the report use it
  std::string_view imitates;    // the driver bug it imitates
  std::string_view kind;        // "source" (a twin) or "state" (GL state)
  std::string_view change;      // what exactly changes, one sentence
  std::string_view equivalent;  // non-empty: why no GL-conforming frame can tell it apart (the argument)
  std::vector<SourceEdit> edits;
  StateFault state = StateFault::None;
  // Non-empty for an equivalent mutant that departs from a documented choice of the oracle where GL
  // leaves freedom (docs/crosscheck.md, "Assumptions"): the verdict judges GL against that choice,
  // so a kill is the pin working as documented, reported as such, not a verdict stricter than GL.
  std::string_view pin;

  // The twin's text as the mutant compiles it: `text` with this mutation's edits for `program`
  // applied. The text is the whole file, all stages: each pattern sits under one stage's #ifdef and
  // so changes that stage only. Throws Error when an edit for `program` finds nothing to replace
  // (the catalogue and the twin disagree: a silent no-op would count as a survivor).
  std::string applyToSource(std::string_view program, std::string_view text) const;
  // After the backend applied command `c` to GL: re-issues the state this mutation corrupts.
  void applyToState(const Command& c) const;
  // The sampler state the backend gives GL for a CreateSampler.
  SamplerState applyToState(const SamplerState& s) const;
  // The bytes the backend gives GL for an UploadTexture of a texture described by `d`: empty to upload
  // `bytes` unchanged, else the corrupted copy.
  std::vector<uint8_t> applyToUpload(const TextureDesc& d, std::span<const uint8_t> bytes) const;
};

// Every mutant, in a fixed order (the report's rows).
const std::vector<Mutation>& mutationCatalogue();
// nullptr when there is no mutant of that name.
const Mutation* findMutation(std::string_view name);

}  // namespace tessera::gl
