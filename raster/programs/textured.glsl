#version 450 core
// GLSL twin of textured.cpp (program "textured"): texture(unit 0, M * (s, t, 1), bias) * tint.
// Attributes: 0 = position, 1 = texcoord (s, t). Uniforms: u[0..3] = MVP; u[4], u[5], u[6] = the
// columns of the 3x3 texture matrix M in .xyz (applied per vertex, as in the C++); u[7] = RGBA tint;
// u[8].x = shader LOD bias; u[8].y = alpha cutoff (discard iff > 0 and (texel * tint).a < it);
// u[8].z = opaque flag (!= 0: output alpha 1 after the test). The same order as the C++ and as
// texarray_batch.glsl's materials. Unit 0: the texture (sampler2D).
// Stage layout and uniform conventions: see flat_color.glsl.

layout(location = 0) uniform vec4 u[64];

#ifdef TESSERA_VERTEX_SHADER
layout(location = 0) in vec4 a_position;
layout(location = 1) in vec4 a_texcoord;
out gl_PerVertex {
  vec4 gl_Position;
  float gl_ClipDistance[8];
};
layout(location = 0) out vec2 v_st;

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
  const float s = a_texcoord.x, t = a_texcoord.y;
  precise float ms = (u[4].x * s + u[5].x * t) + u[6].x;
  precise float mt = (u[4].y * s + u[5].y * t) + u[6].y;
  v_st = vec2(ms, mt);
  for (int i = 0; i < 8; ++i) gl_ClipDistance[i] = 0.0;  // the oracle's zeroed outputs
}
#endif

#ifdef TESSERA_FRAGMENT_SHADER
layout(binding = 0) uniform sampler2D tex0;
layout(location = 0) in vec2 v_st;
layout(location = 0) out vec4 o_color;

void main() {
  // Implicit derivatives (the oracle's are coarse, spec-choices T1) plus the shader bias.
  const vec4 texel = texture(tex0, v_st, u[8].x);
  // One rounded multiply per component (nothing to fuse); the test reads the product back.
  o_color = texel * u[7];
  if (u[8].y > 0.0 && o_color.a < u[8].y) discard;  // glTF MASK: alpha >= cutoff renders
  if (u[8].z != 0.0) o_color.a = 1.0;               // OPAQUE / MASK: rendered fully opaque
}
#endif
