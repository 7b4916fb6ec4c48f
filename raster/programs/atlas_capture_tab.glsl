#version 450 core
// GLSL twin of atlas_capture_tab.cpp (program "atlas_capture_tab"): atlas_capture for batched geometry,
// with texture-array batching's TAM lookup instead of one bound texture.
// Attributes: 0 = position, 1 = (s, t, indexTAM), 2 = object id (U32, arrives as float). Uniforms:
// u[0..3] = MVP, u[4].x = TAM layout (1 = materials), u[7] = tint (.rgb used). Units: 0 = TAM
// (samplerBuffer), 1..8 = TA0..TA7 (sampler2DArray), 9 = the record buffer (samplerBuffer, RGBA32F,
// texels 2 id = (a, b, c, d), 2 id + 1 = (tx, ty, layer, -)).
// Vertex and geometry stages: atlas_displace.glsl's with the records on unit 9 (tessera_boundUnits bit
// 9) and (s, t, indexTAM) passed through. Fragment: texarray_batch.glsl's lookup, factor, discard and
// forced alpha, then o_color = vec4(c.rgb * tint.rgb, 1.0) and o_depth = (gl_FragCoord.z, 1, 0, 1), as
// atlas_capture.glsl. See those twins for the reasons behind each step (the switch over arrayID, the
// derivatives taken first, the layer limit, the clip mask).
// Stage layout and uniform conventions: see flat_color.glsl.

layout(location = 0) uniform vec4 u[64];

#ifdef TESSERA_VERTEX_SHADER
layout(location = 0) in vec4 a_position;
layout(location = 1) in vec4 a_str;
layout(location = 2) in vec4 a_id;
// Redeclared as the geometry stage redeclares gl_in (GLSL 4.50 §7.1.1: the blocks must match).
out gl_PerVertex {
  vec4 gl_Position;
};
layout(location = 0) out vec3 v_str;
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
  v_str = a_str.xyz;
  v_id = toId(a_id.x);
}
#endif

#ifdef TESSERA_GEOMETRY_SHADER
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
layout(location = 0) in vec3 v_str[];
layout(location = 1) flat in uint v_id[];
in gl_PerVertex {
  vec4 gl_Position;
} gl_in[];
out gl_PerVertex {
  vec4 gl_Position;
  float gl_ClipDistance[8];
};
layout(location = 0) out vec3 g_str;

layout(binding = 9) uniform samplerBuffer records;
uniform uint tessera_layerLimit;
uniform uint tessera_boundUnits;
uniform uint tessera_clipMask;

// The distance of plane i if it is enabled, else 0 (inside).
float clipDistance(int i, float d) { return ((tessera_clipMask >> uint(i)) & 1u) != 0u ? d : 0.0; }

// fetchBuffer of sample.h at index 2 id + k (an int64 in the C++): no texture on unit 9 =
// incomplete (0, 0, 0, 1) (spec-choices T12); outside [0, N) = (0, 0, 0, 0) (T11).
vec4 fetchRecord(uint id, uint k) {
  if ((tessera_boundUnits & (1u << 9)) == 0u) return vec4(0.0, 0.0, 0.0, 1.0);
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
    g_str = v_str[i];
    EmitVertex();
  }
  EndPrimitive();
}
#endif

#ifdef TESSERA_FRAGMENT_SHADER
layout(binding = 0) uniform samplerBuffer TAM;
layout(binding = 1) uniform sampler2DArray TA0;
layout(binding = 2) uniform sampler2DArray TA1;
layout(binding = 3) uniform sampler2DArray TA2;
layout(binding = 4) uniform sampler2DArray TA3;
layout(binding = 5) uniform sampler2DArray TA4;
layout(binding = 6) uniform sampler2DArray TA5;
layout(binding = 7) uniform sampler2DArray TA6;
layout(binding = 8) uniform sampler2DArray TA7;
uniform uint tessera_boundUnits;

layout(location = 0) in vec3 g_str;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_depth;

// fetchBuffer of sample.h on unit 0: no texture = incomplete (0, 0, 0, 1) (spec-choices T12); an
// index outside [0, N) = (0, 0, 0, 0) (T11), where GL would be undefined without robust access.
vec4 fetchTam(int index) {
  if ((tessera_boundUnits & 1u) == 0u) return vec4(0.0, 0.0, 0.0, 1.0);
  return (index >= 0 && index < textureSize(TAM)) ? texelFetch(TAM, index) : vec4(0.0);
}

void main() {
  const vec2 st = g_str.xy;
  // The quad's coarse derivatives (spec-choices T1), before any branch.
  const vec2 dx = dFdxCoarse(st);
  const vec2 dy = dFdyCoarse(st);
  // int64(floor(double(z) + 0.5)) of the C++, in double too; anything beyond the largest buffer
  // (2^27 texels) or NaN is out of range like the C++'s out-of-range int64.
  const double zi = floor(double(g_str.z) + 0.5lf);
  const int index = (zi >= 0.0lf && zi < 134217728.0lf) ? int(zi) : -1;
  const bool materials = u[4].x == 1.0;
  // Layout 1: entry e is texels 2e and 2e + 1 (index < 2^27, so 2 * index + 1 fits an int).
  const vec4 tae = fetchTam(materials && index >= 0 ? 2 * index : index);
  const vec4 factor = materials ? fetchTam(index >= 0 ? 2 * index + 1 : -1) : vec4(1.0);
  const float arrayId = tae.x;
  vec4 c = vec4(0.0, 0.0, 0.0, 1.0);  // arrayID outside [0, 8): (0, 0, 0, 1), as the C++
  if (arrayId >= 0.0 && arrayId < 8.0) {
    const vec3 p = vec3(st, tae.y);
    switch (int(arrayId)) {  // int() truncates like the C++'s int(arrayId)
      case 0: c = textureGrad(TA0, p, dx, dy); break;
      case 1: c = textureGrad(TA1, p, dx, dy); break;
      case 2: c = textureGrad(TA2, p, dx, dy); break;
      case 3: c = textureGrad(TA3, p, dx, dy); break;
      case 4: c = textureGrad(TA4, p, dx, dy); break;
      case 5: c = textureGrad(TA5, p, dx, dy); break;
      case 6: c = textureGrad(TA6, p, dx, dy); break;
      default: c = textureGrad(TA7, p, dx, dy); break;
    }
  }
  if (materials) {
    precise vec4 m = c * factor;  // component-wise, as the C++'s c[k] * factor[k]
    if (tae.z > 0.0 && m.a < tae.z) discard;  // glTF MASK: alpha >= cutoff renders
    if (tae.w != 0.0) m.a = 1.0;  // OPAQUE / MASK: rendered fully opaque
    c = m;
  }
  precise vec3 rgb = c.rgb * u[7].rgb;  // component-wise, unfused, as the C++'s c[k] * tint[k]
  o_color = vec4(rgb, 1.0);
  o_depth = vec4(gl_FragCoord.z, 1.0, 0.0, 1.0);
}
#endif
