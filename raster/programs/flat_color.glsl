#version 450 core
// GLSL twin of flat_color.cpp (program "flat_color"): one uniform colour.
// Attributes: 0 = position (xyz[w]). Uniforms: u[0..3] = MVP (column-major), u[4] = RGBA.
//
// How a twin is laid out (docs/gl-backend.md, "GLSL twins"): the backend compiles this one file once
// per stage, inserting `#define TESSERA_VERTEX_SHADER 1` (or _GEOMETRY_ / _FRAGMENT_) and `#line 2`
// right after the #version line; each stage is the code under its #ifdef. A twin has a geometry
// stage iff it contains an #ifdef of TESSERA_GEOMETRY_SHADER. Uniform slots are `u[64]` at explicit location 0,
// so slot k is location k (glProgramUniform4fv(program, k, ...)); samplers get the C++ program's
// unit numbers with layout(binding = n), fixed at link time.

layout(location = 0) uniform vec4 u[64];

#ifdef TESSERA_VERTEX_SHADER
layout(location = 0) in vec4 a_position;
out gl_PerVertex {
  vec4 gl_Position;
  float gl_ClipDistance[8];
};

// mulMat4 of common.h: ((c0*x + c1*y) + c2*z) + c3*w per component. `precise` (GLSL 4.50 §4.7.1)
// keeps this order and forbids fusing a multiply into an add (FMA), so each step rounds to float
// as the C++ does.
vec4 mulMat4(int base, vec4 v) {
  precise vec4 acc = u[base] * v.x;
  acc = acc + u[base + 1] * v.y;
  acc = acc + u[base + 2] * v.z;
  acc = acc + u[base + 3] * v.w;
  return acc;
}

void main() {
  gl_Position = mulMat4(0, a_position);
  // The oracle's vertex outputs start zeroed, so an enabled clip plane this program does not compute
  // sees 0 (inside): write that instead of leaving it undefined.
  for (int i = 0; i < 8; ++i) gl_ClipDistance[i] = 0.0;
}
#endif

#ifdef TESSERA_FRAGMENT_SHADER
layout(location = 0) out vec4 o_color;

void main() { o_color = u[4]; }
#endif
