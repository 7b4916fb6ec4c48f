#version 450 core
// GLSL twin of atlas_capture.cpp (program "atlas_capture"): the render-to-texture-atlas capture pass
// (Trapp & Döllner 2010, §2.3, §3.1) with the window depth kept for compositing.
// Attributes: 0 = position, 1 = texcoord (s, t), 2 = object id (U32, arrives as float). Uniforms:
// u[0..3] = MVP, u[7] = RGBA tint. Unit 0: the record buffer (samplerBuffer, RGBA32F), two texels per
// object: record[2 id] = (a, b, c, d), record[2 id + 1] = (tx, ty, layer, -). Unit 1: the object's
// texture (sampler2D). atlas_displace's layout.
// Vertex and geometry stages: atlas_displace.glsl's, unchanged (copied: a twin is one file); see
// there for the backend uniforms and the layer / clip-distance rules.
// Outputs (layered target: 0 = RGBA8 array, 1 = RG32F array, depth D32F array):
// - o_color = vec4(texel.rgb * tint.rgb, 1.0): alpha forced to 1, the atlas clear alpha 0 being the
//   reserved empty / border value;
// - o_depth = (gl_FragCoord.z, 1.0, -, -): the window depth (GL 4.6 §15.2.2) and "covered"; the
//   target is cleared with (1, 0). The C++ reads the same quantity as Quad::z.
// Stage layout and uniform conventions: see flat_color.glsl.

layout(location = 0) uniform vec4 u[64];

#ifdef TESSERA_VERTEX_SHADER
layout(location = 0) in vec4 a_position;
layout(location = 1) in vec4 a_texcoord;
layout(location = 2) in vec4 a_id;
// Redeclared as the geometry stage redeclares gl_in (GLSL 4.50 §7.1.1: the blocks must match).
out gl_PerVertex {
  vec4 gl_Position;
};
layout(location = 0) out vec2 v_st;
layout(location = 1) flat out uint v_id;

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
  v_st = a_texcoord.xy;
  v_id = toId(a_id.x);
}
#endif

#ifdef TESSERA_GEOMETRY_SHADER
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
layout(location = 0) in vec2 v_st[];
layout(location = 1) flat in uint v_id[];
in gl_PerVertex {
  vec4 gl_Position;
} gl_in[];
out gl_PerVertex {
  vec4 gl_Position;
  float gl_ClipDistance[8];
};
layout(location = 0) out vec2 g_st;

layout(binding = 0) uniform samplerBuffer records;
uniform uint tessera_layerLimit;
uniform uint tessera_boundUnits;
uniform uint tessera_clipMask;

// The distance of plane i if it is enabled, else 0 (inside).
float clipDistance(int i, float d) { return ((tessera_clipMask >> uint(i)) & 1u) != 0u ? d : 0.0; }

// fetchBuffer of sample.h at index 2 id + k (an int64 in the C++): no texture on unit 0 =
// incomplete (0, 0, 0, 1) (spec-choices T12); outside [0, N) = (0, 0, 0, 0) (T11).
vec4 fetchRecord(uint id, uint k) {
  if ((tessera_boundUnits & 1u) == 0u) return vec4(0.0, 0.0, 0.0, 1.0);
  if (id >= 0x40000000u) return vec4(0.0);  // 2 id + k would not fit an int; far beyond any buffer
  const int i = int(id * 2u + k);
  return i < textureSize(records) ? texelFetch(records, i) : vec4(0.0);
}

void main() {
  const uint id = v_id[2];  // the provoking vertex: GL_LAST_VERTEX_CONVENTION
  const vec4 m = fetchRecord(id, 0u);
  const vec4 tr = fetchRecord(id, 1u);
  if (!(tr.z >= 0.0 && tr.z < 65536.0)) return;  // no layer: the C++ returns false
  const uint layer = uint(tr.z);
  if (layer >= tessera_layerLimit) return;
  for (int i = 0; i < 3; ++i) {
    const vec4 p = gl_in[i].gl_Position;
    const float x = p.x, y = p.y, w = p.w;
    precise float c0 = w + x, c1 = w - x, c2 = w + y, c3 = w - y;
    precise float px = (m.x * x + m.y * y) + tr.x * w;
    precise float py = (m.z * x + m.w * y) + tr.y * w;
    gl_ClipDistance[0] = clipDistance(0, c0);
    gl_ClipDistance[1] = clipDistance(1, c1);
    gl_ClipDistance[2] = clipDistance(2, c2);
    gl_ClipDistance[3] = clipDistance(3, c3);
    for (int k = 4; k < 8; ++k) gl_ClipDistance[k] = 0.0;  // the oracle's zeroed outputs
    gl_Position = vec4(px, py, p.z, w);
    gl_Layer = int(layer);
    g_st = v_st[i];
    EmitVertex();
  }
  EndPrimitive();
}
#endif

#ifdef TESSERA_FRAGMENT_SHADER
layout(binding = 1) uniform sampler2D tex1;
layout(location = 0) in vec2 g_st;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_depth;

void main() {
  const vec4 texel = texture(tex1, g_st);  // shader bias 0, as the C++ passes
  precise vec3 c = texel.rgb * u[7].rgb;   // component-wise, unfused, as the C++'s texel[k] * tint[k]
  o_color = vec4(c, 1.0);
  o_depth = vec4(gl_FragCoord.z, 1.0, 0.0, 1.0);
}
#endif
