#version 450 core
// GLSL twin of atlas_sprite_ao.cpp (program "atlas_sprite_ao"): atlas_sprite plus ambient occlusion and
// edge enhancement on the object's own atlas region (Trapp & Döllner 2010, Figure 3D).
// Attributes, units, discard and gl_FragDepth: as atlas_sprite.glsl. Uniforms: u[7] = RGBA tint;
// u[8] = (occlusion bias, edge depth step, -, -); u[9] = RGBA edge colour; u[10..11] = the occlusion
// factors f[0..4], f[k] = u[10 + k / 4][k % 4].
// Per covered fragment, centre depth texel (z, covered):
// k = number of kernel pairs (o, -o), o in (2, 0), (0, 2), (2, 2), (2, -2), with both texels covered and
// (z_o + z_-o) - (z + z) < -bias; edge = a 4-neighbour is uncovered or |z_e - z| > step;
// o_color = edge ? u[9] : (texel * tint) * (f[k], f[k], f[k], 1). Every subtraction and product is
// `precise` (GLSL 4.60 §4.7.1: correctly rounded, never fused), so on the same texels GL computes the
// C++'s floats and the same k and edge.
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

const ivec2 kPairs[4] = ivec2[4](ivec2(2, 0), ivec2(0, 2), ivec2(2, 2), ivec2(2, -2));
const ivec2 kEdge[4] = ivec2[4](ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));

// fetchQuad2DArray of the C++ (see atlas_sprite.glsl).
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
  // The shift is valid here: an invalid one fetched vec4(0) and discarded.
  int k = 0;
  for (int i = 0; i < 4; ++i) {
    const vec4 a = fetchAtlasDepth(p + kPairs[i], v_shift.z);
    const vec4 b = fetchAtlasDepth(p - kPairs[i], v_shift.z);
    precise float second = (a.x + b.x) - (d.x + d.x);
    if (a.y >= 0.5 && b.y >= 0.5 && second < -u[8].x) k += 1;
  }
  bool edge = false;
  for (int i = 0; i < 4; ++i) {
    const vec4 n = fetchAtlasDepth(p + kEdge[i], v_shift.z);
    precise float diff = n.x - d.x;
    edge = edge || !(n.y >= 0.5) || abs(diff) > u[8].y;
  }
  precise vec4 o = c * u[7];
  const float f = u[10 + k / 4][k % 4];
  precise vec3 shaded = o.rgb * f;
  o_color = edge ? u[9] : vec4(shaded, o.a);
  const float z = d.x;
  gl_FragDepth = z > 0.0 ? (z < 1.0 ? z : 1.0) : 0.0;
}
#endif
