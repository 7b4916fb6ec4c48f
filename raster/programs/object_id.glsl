#version 450 core
// GLSL twin of object_id.cpp (program "object_id"): the object id to attachment 0 and gl_PrimitiveID
// (the triangle's index within the draw) to attachment 1, both R32UI (uvec4 outputs; .yzw = 0).
// Attributes: 0 = position, 2 = object id (U32, arrives as float). Uniforms: u[0..3] = MVP; u[8..15] =
// user clip planes, gl_ClipDistance[i] = ((P.x*x + P.y*y) + P.z*z) + P.w*w as in vertex_color.glsl.
// Backend uniform tessera_clipMask (never set by a command list): bit i = plane i enabled.
// Stage layout and uniform conventions: see flat_color.glsl.

layout(location = 0) uniform vec4 u[64];

#ifdef TESSERA_VERTEX_SHADER
layout(location = 0) in vec4 a_position;
layout(location = 2) in vec4 a_id;
out gl_PerVertex {
  vec4 gl_Position;
  float gl_ClipDistance[8];
};
layout(location = 0) flat out uint v_id;
uniform uint tessera_clipMask;

// mulMat4 of common.h, in its order, unfused (`precise`).
vec4 mulMat4(int base, vec4 v) {
  precise vec4 acc = u[base] * v.x;
  acc = acc + u[base + 1] * v.y;
  acc = acc + u[base + 2] * v.z;
  acc = acc + u[base + 3] * v.w;
  return acc;
}

// toId of common.h: a non-negative float below 2^32 truncated, anything else (NaN too) 0xffffffff.
uint toId(float f) { return (f >= 0.0 && f < 4294967296.0) ? uint(f) : 0xffffffffu; }

void main() {
  gl_Position = mulMat4(0, a_position);
  v_id = toId(a_id.x);
  const vec4 p = a_position;
  for (int c = 0; c < 8; ++c) {
    const vec4 pl = u[8 + c];
    precise float d = ((pl.x * p.x + pl.y * p.y) + pl.z * p.z) + pl.w * p.w;
    gl_ClipDistance[c] = ((tessera_clipMask >> uint(c)) & 1u) != 0u ? d : 0.0;
  }
}
#endif

#ifdef TESSERA_FRAGMENT_SHADER
layout(location = 0) flat in uint v_id;  // from the provoking (last) vertex
layout(location = 0) out uvec4 o_id;
layout(location = 1) out uvec4 o_primitive;

void main() {
  o_id = uvec4(v_id, 0u, 0u, 0u);
  o_primitive = uvec4(uint(gl_PrimitiveID), 0u, 0u, 0u);
}
#endif
