// The GLSL dialect a twin is compiled in, and the rewrite of a `#version 450 core` twin into
// `#version 330 core` for contexts that are only OpenGL 3.3 core (Mesa softpipe in 22.3; see
// docs/gl-backend.md, "The 3.3 core path").
//
// Implements: choosing the dialect from the context (the GL path and the extensions it reports),
// and a line-based rewrite that keeps every line where it was (so compiler messages still carry the
// twin's own line numbers):
//   - `#version 450 core` -> `#version 330 core` plus an `#extension ... : require` for each
//     extension the twin needs and the context reports;
//   - `layout(location = N) uniform` -> `uniform` (the backend asks glGetUniformLocation for "u[k]");
//   - `layout(binding = N) uniform <sampler> name;` -> `uniform <sampler> name;`, returned as
//     (name, N) so the backend sets the unit with glUniform1i after linking;
//   - `layout(location = N)` on inter-stage varyings dropped (GLSL 3.30 matches them by name; only
//     vertex inputs and fragment outputs keep their locations);
//   - `in gl_PerVertex { ... } gl_in[];` dropped, `out gl_PerVertex { ... };` -> its members other
//     than gl_Position as plain `out` declarations (redeclaring the blocks is GLSL 4.10);
//   - `precise` kept with GL_ARB_gpu_shader5, else dropped (a recorded fallback: the compiler may
//     then reassociate or fuse);
//   - `dFdxCoarse` / `dFdyCoarse` kept with GL_ARB_derivative_control, else `dFdx` / `dFdy` (a
//     recorded fallback: the implementation may take fine derivatives);
//   - `const` locals with non-constant initialisers kept with GL_ARB_shading_language_420pack, else
//     the qualifier is dropped (no effect on the result);
//   - `double` needs GL_ARB_gpu_shader_fp64: without it the rewrite throws.
// Does not implement: compiling (gl_programs.h), general GLSL parsing: the rewrite relies on the
// twins' layout conventions (docs/gl-backend.md, "GLSL twins": one declaration per line).
// Internal to gl/.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tessera::gl {

struct GlslDialect {
  bool core450 = true;  // the twin as written; otherwise the 3.3 rewrite with these extensions:
  bool gpuShader5 = false, fp64 = false, derivativeControl = false, languagePack420 = false;

  // "450 core" or "330 core".
  std::string name() const;
  // The #extension directives the rewrite adds for a twin using every feature, and the features it
  // drops for lack of an extension (GlInfo::glslExtensions / glslFallbacks).
  std::vector<std::string> extensions() const;
  std::vector<std::string> fallbacks() const;
};

struct RewrittenTwin {
  std::string text;
  // Samplers whose `layout(binding = N)` was dropped: name and unit, for glUniform1i after linking.
  std::vector<std::pair<std::string, int>> samplerUnits;
};

// The twin `text` (whose first line is `#version 450 core`) in `dialect`. For a 450 dialect the
// text is returned unchanged. Throws Error naming `file` when the twin needs a feature the dialect
// lacks and that has no equivalent (double without GL_ARB_gpu_shader_fp64).
RewrittenTwin rewriteTwin(std::string_view file, std::string_view text, const GlslDialect& dialect);

}  // namespace tessera::gl
