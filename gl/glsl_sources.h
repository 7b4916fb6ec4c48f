// The GLSL twins of the built-in programs, embedded at build time (gl/embed_glsl.cmake turns
// raster/programs/<name>.glsl into raw string literals), so the backend never reads shader files.
//
// Implements: lookup of a twin's text by program name. Does not implement: compiling it
// (gl_programs.h).
#pragma once

#include <string_view>
#include <vector>

namespace tessera::gl {

// The text of raster/programs/<program>.glsl, or an empty view when there is no twin.
std::string_view glslSource(std::string_view program);
// Names of every embedded twin, sorted.
std::vector<std::string_view> glslSourceNames();

}  // namespace tessera::gl
