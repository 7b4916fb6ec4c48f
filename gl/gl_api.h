// The one include for GL in the backend: GL 4.5 core prototypes straight from libOpenGL (libglvnd
// exports every core entry point, DSA included), so no loader is involved (docs/gl-backend.md, "EGL setup").
// The 3.3 core path calls only the GL 3.3 subset of them (docs/gl-backend.md, "The 3.3 core path").
// Internal to gl/: public headers never include it.
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES
#endif
#include <GL/glcorearb.h>
