#version 450 core
// GLSL twin of atlas_sprite.cpp (program "atlas_sprite"): render-to-texture-atlas compositing
// (Trapp & Döllner 2010, §3.2, Figure 3), one sprite per object, texel for pixel.
// Attributes: 0 = position in clip space (gl_Position as is; two triangles per object, w = 1);
// 2 = (dx, dy, layer, -), floats holding integers, flat from the provoking (last) vertex: int()
// truncation inside (-2^24, 2^24), else INT_MIN (no texel). Uniforms: u[7] = RGBA tint. Unit 0: the
// atlas colour (sampler2DArray, RGBA8); unit 1: the atlas depth (sampler2DArray, RG32F: window depth,
// covered).
// Per fragment at ivec2(gl_FragCoord.xy) = (x, y): texelFetch of (x + dx, y + dy, layer), level 0,
// on both units, vec4(0) outside textureSize (the C++'s empty texel; GL would be undefined); discard
// unless depth.y >= 0.5; o_color = texel * tint (precise); gl_FragDepth = depth.x clamped to [0, 1] by
// hand (NaN -> 0, spec-choices F11), the clamp GL would apply to a float depth buffer in [0, 1].
// Stage layout and uniform conventions: see flat_color.glsl.

layout(location = 0) uniform vec4 u[64];

#ifdef TESSERA_VERTEX_SHADER
layout(location = 0) in vec4 a_position;
layout(location = 2) in vec4 a_shift;
out gl_PerVertex {
  vec4 gl_Position;
  float gl_ClipDistance[8];
};
layout(location = 0) flat out ivec3 v_shift;

// toShift of the C++: truncation toward zero inside (-2^24, 2^24), else INT_MIN (NaN too).
int toShift(float f) { return (f > -16777216.0 && f < 16777216.0) ? int(f) : int(0x80000000u); }

void main() {
  gl_Position = a_position;
  v_shift = ivec3(toShift(a_shift.x), toShift(a_shift.y), toShift(a_shift.z));
  for (int i = 0; i < 8; ++i) gl_ClipDistance[i] = 0.0;  // the oracle's zeroed outputs
}
#endif

#ifdef TESSERA_FRAGMENT_SHADER
layout(binding = 0) uniform sampler2DArray atlasColor;
layout(binding = 1) uniform sampler2DArray atlasDepth;
uniform uint tessera_boundUnits;
layout(location = 0) flat in ivec3 v_shift;
layout(location = 0) out vec4 o_color;

// fetchQuad2DArray of the C++: no texture = incomplete (0, 0, 0, 1); outside the level or the layers
// = (0, 0, 0, 0). Compared in int64 in the C++; here x + dx cannot overflow for |dx| < 2^24 and
// INT_MIN shifts are caught first.
vec4 fetchAtlasColor(ivec2 p, int layer) {
  if ((tessera_boundUnits & 1u) == 0u) return vec4(0.0, 0.0, 0.0, 1.0);
  const ivec3 size = textureSize(atlasColor, 0);
  if (any(lessThan(p, ivec2(0))) || p.x >= size.x || p.y >= size.y || layer < 0 || layer >= size.z) return vec4(0.0);
  return texelFetch(atlasColor, ivec3(p, layer), 0);
}
vec4 fetchAtlasDepth(ivec2 p, int layer) {
  if ((tessera_boundUnits & 2u) == 0u) return vec4(0.0, 0.0, 0.0, 1.0);
  const ivec3 size = textureSize(atlasDepth, 0);
  if (any(lessThan(p, ivec2(0))) || p.x >= size.x || p.y >= size.y || layer < 0 || layer >= size.z) return vec4(0.0);
  return texelFetch(atlasDepth, ivec3(p, layer), 0);
}

void main() {
  const bool valid = v_shift.x != int(0x80000000u) && v_shift.y != int(0x80000000u) && v_shift.z != int(0x80000000u);
  const ivec2 p = ivec2(gl_FragCoord.xy) + v_shift.xy;
  const vec4 d = valid ? fetchAtlasDepth(p, v_shift.z) : vec4(0.0);
  const vec4 c = valid ? fetchAtlasColor(p, v_shift.z) : vec4(0.0);
  if (!(d.y >= 0.5)) discard;  // empty atlas texel
  precise vec4 o = c * u[7];
  o_color = o;
  const float z = d.x;
  gl_FragDepth = z > 0.0 ? (z < 1.0 ? z : 1.0) : 0.0;
}
#endif
