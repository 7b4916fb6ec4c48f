#include "raster/clip.h"

#include <bit>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "raster/simd_targets.h"

namespace tessera::detail {
namespace {

constexpr int kFixedPlanes = kClipFixedPlanes;

// Signed distance of a vertex to plane `p` (>= 0 inside). Planes 0-5: near, far, the four guard-band
// sides; 6 + i: user clip distance i. Evaluated in double from float inputs, so the fixed planes
// are exact up to one rounding (GL 4.6 §13.7 clip volume; guard band: docs/spec-choices.md).
inline double planeDistance(const double* pos, const double* clip, int p) {
  const double x = pos[0], y = pos[1], z = pos[2], w = pos[3];
  switch (p) {
    case 0: return z + w;
    case 1: return w - z;
    case 2: return kGuardBand * w + x;
    case 3: return kGuardBand * w - x;
    case 4: return kGuardBand * w + y;
    case 5: return kGuardBand * w - y;
    default: return clip[p - kFixedPlanes];
  }
}

inline void toClipVertex(const VertexOut& v, int varyings, ClipVertex& o) {
  for (int k = 0; k < 4; ++k) o.pos[k] = v.pos[k];
  for (int k = 0; k < kMaxClipDistances; ++k) o.clip[k] = v.clip[k];
  for (int k = 0; k < varyings; ++k) o.var[k] = v.var[k];
}

inline bool planeEnabled(int p, uint8_t clipMask) {
  return p < kFixedPlanes || (clipMask >> (p - kFixedPlanes)) & 1;
}

}  // namespace

#if defined(__SSE2__)
// The six fixed planes' outside bits of one vertex (classifyTriangle's scalar steps below), or
// kNonFinite, with the distances in pairs of SSE2 lanes: each lane is the scalar code's double sum or
// difference (w - z and gw - x as w + (-z) and gw + (-x), the same IEEE result), and "outside" is
// the same !(d >= 0), NaN included. A third of the instructions of the scalar form, which was 7 % of a
// setup-bound frame.
constexpr uint32_t kNonFinite = ~0u;
inline uint32_t fixedPlanesOutside(const Vec4& pos) {
  const __m128 p = _mm_loadu_ps(pos.data());
  const __m128 abs = _mm_and_ps(p, _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff)));
  // std::isfinite: |v| <= FLT_MAX, false for infinities and NaN.
  if (_mm_movemask_ps(_mm_cmpnle_ps(abs, _mm_set1_ps(std::numeric_limits<float>::max())))) return kNonFinite;
  const __m128d xy = _mm_cvtps_pd(p), zw = _mm_cvtps_pd(_mm_movehl_ps(p, p));
  const __m128d negHi = _mm_castsi128_pd(_mm_set_epi64x(int64_t(0x8000000000000000u), 0));  // flips lane 1
  const __m128d ww = _mm_unpackhi_pd(zw, zw);
  const __m128d gw = _mm_mul_pd(_mm_set1_pd(kGuardBand), ww);
  const __m128d d0 = _mm_add_pd(zw, _mm_xor_pd(_mm_shuffle_pd(zw, zw, 1), negHi));  // z + w, w - z
  const __m128d d1 = _mm_add_pd(gw, _mm_xor_pd(_mm_unpacklo_pd(xy, xy), negHi));    // gw + x, gw - x
  const __m128d d2 = _mm_add_pd(gw, _mm_xor_pd(_mm_unpackhi_pd(xy, xy), negHi));    // gw + y, gw - y
  const __m128d zero = _mm_setzero_pd();
  return uint32_t(_mm_movemask_pd(_mm_cmpnge_pd(d0, zero))) | uint32_t(_mm_movemask_pd(_mm_cmpnge_pd(d1, zero))) << 2 |
         uint32_t(_mm_movemask_pd(_mm_cmpnge_pd(d2, zero))) << 4;
}
#endif

uint32_t classifyVertex(const VertexOut& o, uint8_t clipMask) {
#if defined(__SSE2__)
  if (simd::kernelsOn()) {  // "reference" runs the scalar steps
    uint32_t m = fixedPlanesOutside(o.pos);
    if (m == kNonFinite) return kClipNonFinite;
    // The enabled planes only (usually none): testing all eight per vertex was a sixth of
    // classifyTriangle's instructions (callgrind: 229 per triangle, 190 without).
    for (uint32_t planes = clipMask; planes; planes &= planes - 1) {
      const int k = std::countr_zero(planes);
      if (!(double(o.clip[k]) >= 0.0)) m |= 1u << (kFixedPlanes + k);
    }
    return m;
  }
#endif
  if (!std::isfinite(o.pos[0]) || !std::isfinite(o.pos[1]) || !std::isfinite(o.pos[2]) || !std::isfinite(o.pos[3]))
    return kClipNonFinite;
  const double x = o.pos[0], y = o.pos[1], z = o.pos[2], w = o.pos[3];
  const double gw = kGuardBand * w;
  uint32_t m = 0;
  m |= uint32_t(!(z + w >= 0.0)) << 0;
  m |= uint32_t(!(w - z >= 0.0)) << 1;
  m |= uint32_t(!(gw + x >= 0.0)) << 2;
  m |= uint32_t(!(gw - x >= 0.0)) << 3;
  m |= uint32_t(!(gw + y >= 0.0)) << 4;
  m |= uint32_t(!(gw - y >= 0.0)) << 5;
  // NaN clip distances count as outside: GL leaves them undefined, the oracle drops that side.
  for (int k = 0; k < kMaxClipDistances; ++k)
    if ((clipMask >> k & 1) && !(double(o.clip[k]) >= 0.0)) m |= 1u << (kFixedPlanes + k);
  return m;
}

ClipResult classifyTriangle(const VertexOut* const (&v)[3], uint8_t clipMask) {
  uint32_t out[3];
  for (int i = 0; i < 3; ++i)
    if ((out[i] = classifyVertex(*v[i], clipMask)) == kClipNonFinite) return ClipResult::Outside;
  return classifyCodes(out[0], out[1], out[2]);
}

int clipTriangle(const VertexOut (&v)[3], uint8_t clipMask, int varyings, ClipVertex (&out)[kMaxClipPolygon]) {
  ClipVertex bufA[kMaxClipPolygon], bufB[kMaxClipPolygon];
  ClipVertex* in = bufA;
  ClipVertex* next = bufB;
  int n = 3;
  for (int i = 0; i < 3; ++i) toClipVertex(v[i], varyings, in[i]);

  for (int p = 0; p < kFixedPlanes + kMaxClipDistances && n > 0; ++p) {
    if (!planeEnabled(p, clipMask)) continue;
    double d[kMaxClipPolygon];
    bool anyOut = false;
    for (int i = 0; i < n; ++i) {
      d[i] = planeDistance(in[i].pos, in[i].clip, p);
      if (!(d[i] >= 0.0)) anyOut = true;
    }
    if (!anyOut) continue;
    int m = 0;
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n;
      const bool inI = d[i] >= 0.0, inJ = d[j] >= 0.0;
      if (inI) next[m++] = in[i];
      if (inI != inJ) {
        // Always interpolate from the inside vertex towards the outside one, so an edge shared by
        // two triangles yields the same new vertex whichever direction each triangle walks it.
        const ClipVertex& a = inI ? in[i] : in[j];
        const ClipVertex& b = inI ? in[j] : in[i];
        const double da = inI ? d[i] : d[j], db = inI ? d[j] : d[i];
        const double t = da / (da - db);
        ClipVertex& o = next[m++];
        for (int k = 0; k < 4; ++k) o.pos[k] = a.pos[k] + t * (b.pos[k] - a.pos[k]);
        for (int k = 0; k < kMaxClipDistances; ++k) o.clip[k] = a.clip[k] + t * (b.clip[k] - a.clip[k]);
        for (int k = 0; k < varyings; ++k) o.var[k] = a.var[k] + t * (b.var[k] - a.var[k]);
      }
    }
    n = m;
    ClipVertex* tmp = in;
    in = next;
    next = tmp;
  }
  if (n < 3) return 0;
  for (int i = 0; i < n; ++i) out[i] = in[i];
  return n;
}

}  // namespace tessera::detail
