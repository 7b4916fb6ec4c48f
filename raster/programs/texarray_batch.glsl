#version 450 core
// GLSL twin of texarray_batch.cpp (program "texarray_batch"): texture-array batching (Trapp &
// Döllner 2015, Listing 1), with glTF materials per TAM entry.
// Attributes: 0 = position, 1 = (s, t, indexTAM). Uniforms: u[0..3] = MVP; u[4].x = TAM layout.
// Unit 0: the texture-array mapping TAM, a buffer texture (samplerBuffer), in one of two layouts:
// - u[4].x != 1: RG32F, entry e = texel e = (arrayID, layerID); colour = the texel.
// - u[4].x == 1 (materials): RGBA32F, entry e = texels 2e = (arrayID, layerID, alphaCutoff,
//   opaqueFlag) and 2e + 1 = base-colour factor; colour = texel * factor, discard iff alphaCutoff > 0
//   and colour.a < alphaCutoff, then opaqueFlag != 0 forces colour.a = 1. The same order as the C++ and as
//   textured.glsl; `precise` keeps the product unfused.
// Units 1..8: the texture arrays TA0..TA7 (sampler2DArray).
// Backend uniform tessera_boundUnits (never set by a command list): bit u = unit u has a texture.
//
// Why a switch and not `uniform sampler2DArray TA[8]` indexed by arrayID: GLSL 4.50 §4.1.7 allows
// only dynamically uniform sampler-array indices, and llvmpipe silently returns texels of the wrong
// array for a per-pixel index (docs/gl-backend.md, "texarray_batch"). So the derivatives are taken first, in uniform
// control flow (GLSL 4.50 §8.14.1: derivatives are undefined in non-uniform flow), and each case
// samples one named sampler with textureGrad and those derivatives: the same lookup per pixel as the
// C++, which also uses one quad's derivatives for every pixel whatever array it names.
// Stage layout and uniform conventions: see flat_color.glsl.

layout(location = 0) uniform vec4 u[64];

#ifdef TESSERA_VERTEX_SHADER
layout(location = 0) in vec4 a_position;
layout(location = 1) in vec4 a_str;
out gl_PerVertex {
  vec4 gl_Position;
  float gl_ClipDistance[8];
};
layout(location = 0) out vec3 v_str;

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
  v_str = a_str.xyz;
  for (int i = 0; i < 8; ++i) gl_ClipDistance[i] = 0.0;  // the oracle's zeroed outputs
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

layout(location = 0) in vec3 v_str;
layout(location = 0) out vec4 o_color;

// fetchBuffer of sample.h on unit 0: no texture = incomplete (0, 0, 0, 1) (spec-choices T12); an
// index outside [0, N) = (0, 0, 0, 0) (T11), where GL would be undefined without robust access.
vec4 fetchTam(int index) {
  if ((tessera_boundUnits & 1u) == 0u) return vec4(0.0, 0.0, 0.0, 1.0);
  return (index >= 0 && index < textureSize(TAM)) ? texelFetch(TAM, index) : vec4(0.0);
}

void main() {
  const vec2 st = v_str.xy;
  // The quad's coarse derivatives (spec-choices T1), before any branch.
  const vec2 dx = dFdxCoarse(st);
  const vec2 dy = dFdyCoarse(st);
  // int64(floor(double(z) + 0.5)) of the C++, in double too; anything beyond the largest buffer
  // (2^27 texels) or NaN is out of range like the C++'s out-of-range int64.
  const double zi = floor(double(v_str.z) + 0.5lf);
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
  o_color = c;
}
#endif
