#include "gl/gl_programs.h"

#include <vector>

#include "gl/glsl_sources.h"
#include "raster/command_list.h"

namespace tessera::gl {
namespace {

std::string fileOf(std::string_view name) { return "raster/programs/" + std::string(name) + ".glsl"; }

std::string shaderLog(GLuint shader) {
  GLint n = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &n);
  std::string log(size_t(n > 0 ? n : 0), '\0');
  if (n > 0) glGetShaderInfoLog(shader, n, nullptr, log.data());
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log;
}

std::string programLog(GLuint program) {
  GLint n = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &n);
  std::string log(size_t(n > 0 ? n : 0), '\0');
  if (n > 0) glGetProgramInfoLog(program, n, nullptr, log.data());
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log;
}

GLuint compile(std::string_view name, std::string_view text, GLenum stage, const char* define, const char* label) {
  // The first line must be the #version directive: it has to precede everything else in the
  // shader (GLSL 4.50 §3.3), so the stage define goes right after it, and after the #extension
  // lines the 3.3 rewrite adds (they too must precede every other token, GLSL 3.30 §3.3).
  size_t eol = text.find('\n');
  const std::string_view first = text.substr(0, eol);
  if ((first.rfind("#version 450 core", 0) != 0 && first.rfind("#version 330 core", 0) != 0) ||
      eol == std::string_view::npos)
    throw Error(fileOf(name) + ": the first line must be '#version 450 core'");
  while (text.substr(eol + 1).rfind("#extension ", 0) == 0) eol = text.find('\n', eol + 1);
  const std::string header = std::string(text.substr(0, eol)) + "\n#define " + define + " 1\n#line 2\n";
  const std::string_view body = text.substr(eol + 1);
  const GLchar* strings[2] = {header.data(), body.data()};
  const GLint lengths[2] = {GLint(header.size()), GLint(body.size())};
  const GLuint s = glCreateShader(stage);
  glShaderSource(s, 2, strings, lengths);
  glCompileShader(s);
  GLint ok = GL_FALSE;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    const std::string log = shaderLog(s);
    glDeleteShader(s);
    throw Error(fileOf(name) + " (" + label + " stage) does not compile: " + log);
  }
  return s;
}

// Runs `f` with `program` current and restores the previous program (3.3 path: no glProgramUniform).
template <class F>
void withProgram(GLuint program, F f) {
  GLint previous = 0;
  glGetIntegerv(GL_CURRENT_PROGRAM, &previous);
  if (GLuint(previous) != program) glUseProgram(program);
  f();
  if (GLuint(previous) != program) glUseProgram(GLuint(previous));
}

}  // namespace

void uniform4fv(bool dsa, GLuint program, GLint location, GLsizei count, const float* values) {
  if (dsa) {
    glProgramUniform4fv(program, location, count, values);
  } else {
    glUniform4fv(location, count, values);
  }
}

void uniform1ui(bool dsa, GLuint program, GLint location, GLuint value) {
  if (dsa) {
    glProgramUniform1ui(program, location, value);
  } else {
    glUniform1ui(location, value);
  }
}

ProgramCompiler::~ProgramCompiler() = default;  // release() runs while the context is current

void ProgramCompiler::release() {
  for (auto& [name, list] : free_)
    for (const LinkedProgram& p : list) glDeleteProgram(p.name);
  free_.clear();
  for (auto& [name, s] : cache_) {
    glDeleteShader(s.vs);
    glDeleteShader(s.gs);  // deleting 0 is silently ignored (GL 4.6 §7.1)
    glDeleteShader(s.fs);
  }
  cache_.clear();
}

void ProgramCompiler::setMutation(const Mutation* mutation) {
  release();
  mutation_ = mutation;
}

size_t ProgramCompiler::objectCount() const {
  size_t n = 0;
  for (const auto& [name, s] : cache_) n += size_t(s.vs != 0) + size_t(s.gs != 0) + size_t(s.fs != 0);
  for (const auto& [name, list] : free_) n += list.size();
  return n;
}

LinkedProgram ProgramCompiler::acquire(std::string_view name, uint64_t& resetCalls) {
  auto it = free_.find(name);
  if (it == free_.end() || it->second.empty()) return link(name);
  LinkedProgram p = it->second.back();
  it->second.pop_back();
  // Back to the state of a fresh link: u[64] all zero (GL 4.6 §7.6: uniforms start at 0), and the
  // backend's own uniforms unknown, so they are set again before the next draw.
  static const float zeros[kMaxUniformSlots * 4] = {};
  if (dsa_) {
    glProgramUniform4fv(p.name, 0, kMaxUniformSlots, zeros);
  } else if (p.slotLocation(0) >= 0) {
    withProgram(p.name, [&] { glUniform4fv(p.slotLocation(0), kMaxUniformSlots, zeros); });
  }
  ++resetCalls;
  p.layerLimitSet = p.boundUnitsSet = p.clipMaskSet = false;
  return p;
}

void ProgramCompiler::recycle(const LinkedProgram& p) {
  if (p.name == 0 || p.cpu == nullptr) return;
  free_[std::string(p.cpu->name())].push_back(p);
}

const ProgramCompiler::Stages& ProgramCompiler::stages(std::string_view name) {
  if (auto it = cache_.find(name); it != cache_.end()) return it->second;
  const std::string_view source = glslSource(name);
  if (source.empty())
    throw Error("program \"" + std::string(name) + "\" has no GLSL twin (" + fileOf(name) + " is not embedded)");
  // A mutation edits the 4.50 twin as written (gl_mutation.h); the dialect rewrite then applies to it.
  const std::string twin = mutation_ ? mutation_->applyToSource(name, source) : std::string(source);
  RewrittenTwin rewritten = rewriteTwin(fileOf(name), twin, dialect_);
  const std::string_view text = rewritten.text;
  Stages s;
  s.samplerUnits = std::move(rewritten.samplerUnits);
  try {
    s.vs = compile(name, text, GL_VERTEX_SHADER, "TESSERA_VERTEX_SHADER", "vertex");
    if (text.find("#ifdef TESSERA_GEOMETRY_SHADER") != std::string_view::npos)
      s.gs = compile(name, text, GL_GEOMETRY_SHADER, "TESSERA_GEOMETRY_SHADER", "geometry");
    s.fs = compile(name, text, GL_FRAGMENT_SHADER, "TESSERA_FRAGMENT_SHADER", "fragment");
  } catch (...) {
    glDeleteShader(s.vs);
    glDeleteShader(s.gs);
    throw;
  }
  return cache_.emplace(std::string(name), s).first->second;
}

LinkedProgram ProgramCompiler::link(std::string_view name) {
  const Program* cpu = findProgram(name);
  if (cpu == nullptr) throw Error("program \"" + std::string(name) + "\" is not in the program registry");
  const Stages& s = stages(name);
  if ((s.gs != 0) != cpu->hasGeometryStage())
    throw Error(fileOf(name) + ": the twin " + (s.gs ? "has" : "lacks") + " a geometry stage but the C++ program " +
                (cpu->hasGeometryStage() ? "has" : "lacks") + " one");

  LinkedProgram p;
  p.cpu = cpu;
  p.name = glCreateProgram();
  glAttachShader(p.name, s.vs);
  if (s.gs) glAttachShader(p.name, s.gs);
  glAttachShader(p.name, s.fs);
  glLinkProgram(p.name);
  // Detaching keeps the shaders' lifetime with the cache only (GL 4.6 §7.3: a shader attached to a
  // program is not deleted until detached).
  glDetachShader(p.name, s.vs);
  if (s.gs) glDetachShader(p.name, s.gs);
  glDetachShader(p.name, s.fs);
  GLint ok = GL_FALSE;
  glGetProgramiv(p.name, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = programLog(p.name);
    glDeleteProgram(p.name);
    throw Error(fileOf(name) + " does not link: " + log);
  }
  // The twin must write exactly the C++ program's colour outputs: the backend masks draw buffers
  // by this number, as the oracle writes only attachments < colorOutputs().
  // Without glGetProgramInterfaceiv (a 3.3 context without ARB_program_interface_query) the check
  // is skipped; the 4.5 path always makes it.
  GLint outputs = cpu->colorOutputs();
  if (interfaceQuery_) {
    glGetProgramInterfaceiv(p.name, GL_PROGRAM_OUTPUT, GL_ACTIVE_RESOURCES, &outputs);
    // gl_FragDepth is an active output too (GL 4.6 §7.3.1.1 lists built-in outputs), but no colour
    // output: a program that writes depth (Program::writesDepth, spec-choices F11) has one more.
    if (cpu->writesDepth()) outputs -= 1;
  }
  p.colorOutputs = cpu->colorOutputs();
  if (outputs != p.colorOutputs) {
    glDeleteProgram(p.name);
    throw Error(fileOf(name) + ": the twin has " + std::to_string(outputs) + " active outputs, the C++ program " +
                std::to_string(p.colorOutputs));
  }
  p.layerLimitLocation = glGetUniformLocation(p.name, kLayerLimitUniform);
  p.boundUnitsLocation = glGetUniformLocation(p.name, kBoundUnitsUniform);
  p.clipMaskLocation = glGetUniformLocation(p.name, kClipMaskUniform);
  if (!dsa_) {
    // GLSL 3.30 has no explicit uniform locations or sampler bindings (GL 4.3 / 4.2): ask for each
    // slot's location and set each sampler's unit once; both are program state, kept on reuse.
    p.slotLocations.resize(kMaxUniformSlots);
    for (uint32_t k = 0; k < uint32_t(kMaxUniformSlots); ++k)
      p.slotLocations[k] = glGetUniformLocation(p.name, ("u[" + std::to_string(k) + "]").c_str());
    withProgram(p.name, [&] {
      for (const auto& [sampler, unit] : s.samplerUnits) {
        const GLint at = glGetUniformLocation(p.name, sampler.c_str());
        if (at >= 0) glUniform1i(at, unit);
      }
    });
  }
  return p;
}

}  // namespace tessera::gl
