#version 450 core
// GLSL twin of textured_layers.cpp (program "textured_layers"): texture(unit 0) modulated by
// texture(unit 1), f = (t1 - 1) * strength + 1 per RGB channel (or t1.r for all three), times the tint.
// Attributes: 0 = position, 1 = (s0, t0, s1, t1), both texcoords in one vec4. Uniforms: u[0..3] = MVP;
// u[4..6] = layer 0's texture matrix columns; u[7] = RGBA tint; u[8] = (LOD bias, alpha cutoff, opaque
// flag, -); u[9..11] = layer 1's texture matrix columns; u[12] = (strength, R-only flag, -, -). The same
// operations in the same order as the C++, each rounded once (`precise`: nothing is fused).
// Stage layout and uniform conventions: see flat_color.glsl.

layout(location = 0) uniform vec4 u[64];

#ifdef TESSERA_VERTEX_SHADER
layout(location = 0) in vec4 a_position;
layout(location = 1) in vec4 a_texcoord;
out gl_PerVertex {
  vec4 gl_Position;
  float gl_ClipDistance[8];
};
layout(location = 0) out vec2 v_st0;
layout(location = 1) out vec2 v_st1;

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
  const float s0 = a_texcoord.x, t0 = a_texcoord.y;
  precise float ms0 = (u[4].x * s0 + u[5].x * t0) + u[6].x;
  precise float mt0 = (u[4].y * s0 + u[5].y * t0) + u[6].y;
  const float s1 = a_texcoord.z, t1 = a_texcoord.w;
  precise float ms1 = (u[9].x * s1 + u[10].x * t1) + u[11].x;
  precise float mt1 = (u[9].y * s1 + u[10].y * t1) + u[11].y;
  v_st0 = vec2(ms0, mt0);
  v_st1 = vec2(ms1, mt1);
  for (int i = 0; i < 8; ++i) gl_ClipDistance[i] = 0.0;  // the oracle's zeroed outputs
}
#endif

#ifdef TESSERA_FRAGMENT_SHADER
layout(binding = 0) uniform sampler2D tex0;
layout(binding = 1) uniform sampler2D tex1;
layout(location = 0) in vec2 v_st0;
layout(location = 1) in vec2 v_st1;
layout(location = 0) out vec4 o_color;

void main() {
  // Implicit derivatives (the oracle's are coarse, spec-choices T1) plus the shader bias.
  const vec4 base = texture(tex0, v_st0, u[8].x);
  const vec4 layer = texture(tex1, v_st1, u[8].x);
  const vec3 occ = u[12].y != 0.0 ? vec3(layer.r) : layer.rgb;
  precise vec3 f = (occ - vec3(1.0)) * u[12].x + vec3(1.0);
  precise vec3 rgb = (base.rgb * f) * u[7].rgb;
  precise float a = base.a * u[7].a;
  o_color = vec4(rgb, a);
  if (u[8].y > 0.0 && o_color.a < u[8].y) discard;  // glTF MASK: alpha >= cutoff renders
  if (u[8].z != 0.0) o_color.a = 1.0;               // OPAQUE / MASK: rendered fully opaque
}
#endif
