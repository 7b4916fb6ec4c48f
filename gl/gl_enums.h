// Tessera's state vocabulary (raster/types.h) as GL enums. types.h was designed so that every enum
// maps one to one onto a GL enum; this file is that table and nothing else.
// Internal to gl/.
#pragma once

#include "gl/gl_api.h"
#include "raster/command_list.h"

namespace tessera::gl {

// Internal format plus the client format / type of uploads and read-backs (GL 4.6 Tables 8.2, 8.3,
// 8.12). Integer textures use GL_RED_INTEGER so that texels move as integers, never as floats.
struct GlFormat {
  GLenum internal, format, type;
};
GlFormat glFormat(Format f);
GLenum glTarget(TextureKind k);
GLenum glWrap(Wrap w);
GLenum glFilter(Filter f);
GLenum glCompareFunc(CompareFunc f);
GLenum glBlendEquation(BlendEq e);
GLenum glBlendFactor(BlendFactor f);
GLenum glIndexType(IndexType t);
uint32_t indexBytes(IndexType t);

}  // namespace tessera::gl
