#version 450 core
// GLSL twin of vertex_color.cpp (program "vertex_color"): perspective-correct per-vertex colour.
// Attributes: 0 = position, 1 = RGBA. Uniforms: u[0..3] = MVP; u[8..15] = user clip planes P_i in
// object space, gl_ClipDistance[i] = ((P.x*x + P.y*y) + P.z*z) + P.w*w (only planes enabled in
// RasterState::clipMask take effect, through GL_CLIP_DISTANCEi).
// Backend uniform (never set by a command list): tessera_clipMask = RasterState::clipMask. A disabled
// plane's distance is written as 0 (inside) because llvmpipe (Mesa 22.3) clips by every distance the
// shader writes, enabled or not, where GL 4.6 §13.7.1 ignores disabled ones (docs/gl-backend.md).
// Stage layout and uniform conventions: see flat_color.glsl.

layout(location = 0) uniform vec4 u[64];

#ifdef TESSERA_VERTEX_SHADER
layout(location = 0) in vec4 a_position;
layout(location = 1) in vec4 a_color;
out gl_PerVertex {
  vec4 gl_Position;
  float gl_ClipDistance[8];
};
layout(location = 0) out vec4 v_color;
uniform uint tessera_clipMask;

// mulMat4 of common.h, in its order, unfused (`precise`).
vec4 mulMat4(int base, vec4 v) {
  precise vec4 acc = u[base] * v.x;
  acc = acc + u[base + 1] * v.y;
  acc = acc + u[base + 2] * v.z;
  acc = acc + u[base + 3] * v.w;
  return acc;
}

void main() {
  gl_Position = mulMat4(0, a_position);
  v_color = a_color;
  const vec4 p = a_position;
  for (int c = 0; c < 8; ++c) {
    const vec4 pl = u[8 + c];
    precise float d = ((pl.x * p.x + pl.y * p.y) + pl.z * p.z) + pl.w * p.w;
    gl_ClipDistance[c] = ((tessera_clipMask >> uint(c)) & 1u) != 0u ? d : 0.0;
  }
}
#endif

#ifdef TESSERA_FRAGMENT_SHADER
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o_color;

void main() { o_color = v_color; }
#endif
