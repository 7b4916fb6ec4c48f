#include "gl/glsl_dialect.h"

#include <regex>

#include "base/error.h"

namespace tessera::gl {

std::string GlslDialect::name() const { return core450 ? "450 core" : "330 core"; }

std::vector<std::string> GlslDialect::extensions() const {
  std::vector<std::string> e;
  if (core450) return e;
  if (gpuShader5) e.emplace_back("GL_ARB_gpu_shader5");
  if (fp64) e.emplace_back("GL_ARB_gpu_shader_fp64");
  if (derivativeControl) e.emplace_back("GL_ARB_derivative_control");
  if (languagePack420) e.emplace_back("GL_ARB_shading_language_420pack");
  return e;
}

std::vector<std::string> GlslDialect::fallbacks() const {
  std::vector<std::string> f;
  if (core450) return f;
  if (!gpuShader5) f.emplace_back("precise dropped (no GL_ARB_gpu_shader5): the compiler may reassociate or fuse");
  if (!derivativeControl)
    f.emplace_back("dFdxCoarse/dFdyCoarse -> dFdx/dFdy (no GL_ARB_derivative_control): derivatives may be fine");
  if (!fp64) f.emplace_back("no GL_ARB_gpu_shader_fp64: twins that compute in double do not compile");
  return f;
}

namespace {

enum class Section { None, Vertex, Geometry, Fragment };

}  // namespace

RewrittenTwin rewriteTwin(std::string_view file, std::string_view text, const GlslDialect& d) {
  RewrittenTwin out;
  if (d.core450) {
    out.text = std::string(text);
    return out;
  }
  const size_t eol = text.find('\n');
  if (eol == std::string_view::npos || text.substr(0, eol).rfind("#version 450 core", 0) != 0)
    throw Error(std::string(file) + ": the first line must be '#version 450 core'");
  const std::string body(text.substr(eol + 1));

  static const std::regex uniformLocation(R"(^(\s*)layout\s*\(\s*location\s*=\s*\d+\s*\)\s*uniform\b)");
  static const std::regex samplerBinding(
      R"(^(\s*)layout\s*\(\s*binding\s*=\s*(\d+)\s*\)\s*uniform\s+(\w+)\s+(\w+)\s*;(.*)$)");
  static const std::regex varyingLocation(
      R"(^(\s*)layout\s*\(\s*location\s*=\s*\d+\s*\)\s*((?:(?:flat|smooth|noperspective)\s+)?(in|out)\b.*)$)");
  static const std::regex perVertexBegin(R"(^\s*(in|out)\s+gl_PerVertex\s*\{)");
  static const std::regex member(R"(^\s*(\w+)\s+(gl_\w+(?:\[\d*\])?)\s*;)");
  static const std::regex constLocal(R"(^(\s+)const\s+)");
  static const std::regex precise(R"(\bprecise\s+)");
  static const std::regex coarseX(R"(\bdFdxCoarse\b)"), coarseY(R"(\bdFdyCoarse\b)");
  static const std::regex usesDouble(R"(\bdouble\b)");

  const bool needsFp64 = std::regex_search(body, usesDouble);
  if (needsFp64 && !d.fp64)
    throw Error(std::string(file) +
                ": computes in double, which GLSL 3.30 lacks and the context does not offer GL_ARB_gpu_shader_fp64");
  bool usesPrecise = false, usesCoarse = false, usesConstLocal = false;

  std::string result;
  Section section = Section::None;
  int depth = 0;  // #if nesting; the stage section is the one open at depth 1
  bool inBlock = false, blockIsOut = false;
  std::string blockMembers;
  size_t pos = 0;
  int lineNo = 1;
  while (pos <= body.size()) {
    size_t end = body.find('\n', pos);
    const bool last = end == std::string::npos;
    if (last) end = body.size();
    std::string line = body.substr(pos, end - pos);
    pos = end + 1;
    ++lineNo;

    if (line.rfind("#if", 0) == 0) {
      ++depth;
      if (depth == 1) {
        if (line.find("TESSERA_VERTEX_SHADER") != std::string::npos) section = Section::Vertex;
        if (line.find("TESSERA_GEOMETRY_SHADER") != std::string::npos) section = Section::Geometry;
        if (line.find("TESSERA_FRAGMENT_SHADER") != std::string::npos) section = Section::Fragment;
      }
    } else if (line.rfind("#endif", 0) == 0) {
      if (--depth == 0) section = Section::None;
    }

    std::smatch m;
    if (inBlock) {
      // Inside a gl_PerVertex redeclaration: collect the members, keep the line count.
      if (std::regex_search(line, m, member) && m[2] != "gl_Position")
        blockMembers += "out " + m[1].str() + " " + m[2].str() + "; ";
      if (line.find('}') != std::string::npos) {
        inBlock = false;
        line = blockIsOut ? blockMembers : "";
      } else {
        line.clear();
      }
    } else if (std::regex_search(line, m, perVertexBegin)) {
      inBlock = line.find('}') == std::string::npos;
      blockIsOut = m[1] == "out";
      blockMembers.clear();
      if (!inBlock)
        throw Error(std::string(file) + ":" + std::to_string(lineNo) + ": a gl_PerVertex block must span lines");
      line.clear();
    } else if (std::regex_search(line, m, samplerBinding)) {
      out.samplerUnits.emplace_back(m[4].str(), std::stoi(m[2].str()));
      line = m[1].str() + "uniform " + m[3].str() + " " + m[4].str() + ";" + m[5].str();
    } else if (std::regex_search(line, m, uniformLocation)) {
      line = std::regex_replace(line, uniformLocation, "$1uniform", std::regex_constants::format_first_only);
    } else if (std::regex_search(line, m, varyingLocation)) {
      const bool keep = (section == Section::Vertex && m[3] == "in") || (section == Section::Fragment && m[3] == "out");
      if (!keep) line = m[1].str() + m[2].str();
    }
    if (std::regex_search(line, precise)) {
      usesPrecise = true;
      if (!d.gpuShader5) line = std::regex_replace(line, precise, "");
    }
    if (std::regex_search(line, coarseX) || std::regex_search(line, coarseY)) {
      usesCoarse = true;
      if (!d.derivativeControl) line = std::regex_replace(std::regex_replace(line, coarseX, "dFdx"), coarseY, "dFdy");
    }
    if (std::regex_search(line, constLocal)) {
      usesConstLocal = true;
      if (!d.languagePack420) line = std::regex_replace(line, constLocal, "$1");
    }
    result += line;
    if (!last) result += '\n';
  }

  std::string header = "#version 330 core\n";
  if (usesPrecise && d.gpuShader5) header += "#extension GL_ARB_gpu_shader5 : require\n";
  if (needsFp64) header += "#extension GL_ARB_gpu_shader_fp64 : require\n";
  if (usesCoarse && d.derivativeControl) header += "#extension GL_ARB_derivative_control : require\n";
  if (usesConstLocal && d.languagePack420) header += "#extension GL_ARB_shading_language_420pack : require\n";
  // The compiler inserts the stage define and `#line 2` after the first line; the extensions must
  // precede any non-preprocessor token, so they go into the first "line" as well.
  header.pop_back();
  out.text = header + "\n" + result;
  return out;
}

}  // namespace tessera::gl
