// The GLSL twins of the built-in programs: compiling raster/programs/<name>.glsl (embedded at build
// time, glsl_sources.h) into GL program objects with the same attributes, uniform slots, texture
// units and outputs as the C++ program of that name (raster/program.h).
//
// Source layout of a twin (docs/gl-backend.md, "GLSL twins"): the file starts with the line
// `#version 450 core`; the backend compiles the whole file once per stage, inserting after that
// line `#define TESSERA_VERTEX_SHADER 1`, `TESSERA_GEOMETRY_SHADER` or `TESSERA_FRAGMENT_SHADER`
// and `#line 2`, so compiler messages carry the file's own line numbers. A twin has a geometry
// stage iff its text contains `#ifdef TESSERA_GEOMETRY_SHADER`.
//
// On the 3.3 core path (configure(dsa = false)) the twin is first rewritten to `#version 330 core`
// (glsl_dialect.h): uniform slots then come from glGetUniformLocation("u[k]") and sampler units are
// set with glUniform1i after linking; uniforms are written with glUniform* on the current program
// instead of glProgramUniform*.
//
// Internal to gl/.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "gl/gl_api.h"
#include "gl/gl_mutation.h"
#include "gl/glsl_dialect.h"
#include "raster/program.h"

namespace tessera::gl {

// Names of the uniforms the backend sets itself (never through SetUniforms): they pin GL to a
// choice of the oracle that GL leaves open (docs/gl-backend.md, "Pinning").
inline constexpr const char* kLayerLimitUniform = "tessera_layerLimit";  // uint: layers of a layered target
inline constexpr const char* kBoundUnitsUniform = "tessera_boundUnits";  // uint: bit u = unit u has a texture
inline constexpr const char* kClipMaskUniform = "tessera_clipMask";      // uint: RasterState::clipMask

// One GL program object. Uniform values are state of the program object (GL 4.6 §7.6), as in the
// oracle, so every CreateProgram command gets its own object.
struct LinkedProgram {
  GLuint name = 0;
  const Program* cpu = nullptr;  // the C++ program of the same name
  int colorOutputs = 1;
  GLint layerLimitLocation = -1;  // -1: the twin does not use it
  GLint boundUnitsLocation = -1;
  GLint clipMaskLocation = -1;
  // Last values written to the backend's own uniforms (uniforms start at 0 after linking, which is
  // not always what the backend wants, hence the flags).
  bool layerLimitSet = false, boundUnitsSet = false, clipMaskSet = false;
  uint32_t layerLimit = 0, boundUnits = 0, clipMask = 0;
  // The location of u[k] (3.3 path: glGetUniformLocation, -1 beyond the array the linker kept);
  // empty on the 4.5 path, where `layout(location = 0)` makes slot k location k.
  std::vector<GLint> slotLocations;
  GLint slotLocation(uint32_t slot) const { return slotLocations.empty() ? GLint(slot) : slotLocations[slot]; }
};

// glProgramUniform4fv / 1ui with DSA; otherwise glUniform4fv / 1ui, which write the current program:
// the caller makes `program` current first (the replay only writes the program in use).
void uniform4fv(bool dsa, GLuint program, GLint location, GLsizei count, const float* values);
void uniform1ui(bool dsa, GLuint program, GLint location, GLuint value);

class ProgramCompiler {
 public:
  ProgramCompiler() = default;
  ~ProgramCompiler();
  // The dialect twins are compiled in, whether DSA entry points may be used, and whether the
  // context has glGetProgramInterfaceiv (GL 4.3 / ARB_program_interface_query) to count outputs.
  void configure(const GlslDialect& dialect, bool dsa, bool interfaceQuery) {
    dialect_ = dialect;
    dsa_ = dsa;
    interfaceQuery_ = interfaceQuery;
  }
  ProgramCompiler(const ProgramCompiler&) = delete;
  ProgramCompiler& operator=(const ProgramCompiler&) = delete;

  // A program object for the twin `name` in its just-linked state (every uniform 0). Programs
  // given back with recycle() are reused: llvmpipe keeps its JIT-compiled shader variants with the
  // program object, so relinking every frame would recompile them every frame. A reused program's
  // u[64] is zeroed with one glProgramUniform4fv; `resetCalls` counts those calls.
  // Throws Error naming the .glsl file and stage with the compiler log, or when the twin disagrees
  // with the C++ program (outputs, geometry stage).
  LinkedProgram acquire(std::string_view name, uint64_t& resetCalls);
  // Gives a program back for reuse by a later acquire() of the same name.
  void recycle(const LinkedProgram& p);
  // Deletes every cached program and shader object (needs the context current).
  void release();
  // Program and shader objects held.
  size_t objectCount() const;
  // Twins compile with this mutation's source edits from now on (nullptr: as written); releases
  // every cached program and shader so that nothing compiled before is reused.
  void setMutation(const Mutation* mutation);

 private:
  struct Stages {
    GLuint vs = 0, gs = 0, fs = 0;
    std::vector<std::pair<std::string, int>> samplerUnits;  // 3.3 path: set with glUniform1i after linking
  };
  const Stages& stages(std::string_view name);
  LinkedProgram link(std::string_view name);
  std::map<std::string, Stages, std::less<>> cache_;
  std::map<std::string, std::vector<LinkedProgram>, std::less<>> free_;
  GlslDialect dialect_;
  bool dsa_ = true, interfaceQuery_ = true;
  const Mutation* mutation_ = nullptr;
};

}  // namespace tessera::gl
