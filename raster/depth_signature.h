// Depth-writer signatures (provenance mode): a 64-bit hash of everything that determines a fragment's
// window depth in GL, so that the judge knows when a depth test meets an *exact* tie.
//
// GL 4.6 Appendix A: Rule 1 (the same command on the same state gives the same result), Rule 2 (a
// change of framebuffer contents, write masks, scissor or clear values has no side effects; depth-test
// parameters are "strongly suggested" there, pinned here, docs/crosscheck.md DEPTH_NEAR_EQUAL) and
// Rule 4 (the same shader gives the same result for the same input). So two primitives of the same
// program, uniforms, texture bindings, viewport, raster state (clip planes), depth-test enable,
// depth epoch and position inputs give bit-identical gl_Position, clipped polygons and window depth
// at every pixel, and a depth test of one against the other's stored depth is an exact equality.
// What is hashed per primitive: the inputs the built-in vertex stages compute gl_Position and
// gl_ClipDistance from (attribute 0, the uniforms; GLSL 4.60 §4.8: variance is a property of an
// expression and the inputs it consumes), and the oracle's post-vertex-stage positions and clip
// distances bitwise (a second guard). Programs with a geometry stage get no signature (0): their
// positions may depend on buffer contents that are not hashed.
//
// The depth epoch changes at every clear, render-target change and texture upload: a signature
// compares equal only within one epoch, where every depth write of the target goes through the
// provenance rasterizer.
//
// Implements: the hash. Does not implement: its use (rast_provenance.cpp) or the state capture
// (cpu_backend.cpp).
#pragma once

#include <cstdint>
#include <cstring>

namespace tessera::detail {

// Mixes 64 bits into a running hash (splitmix64 finalizer over a rotated xor).
inline uint64_t sigMix(uint64_t h, uint64_t v) {
  h ^= v + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
  h *= 0xbf58476d1ce4e5b9ull;
  h ^= h >> 31;
  h *= 0x94d049bb133111ebull;
  h ^= h >> 29;
  return h;
}

// Mixes the bit patterns of `n` floats.
inline uint64_t sigMixFloats(uint64_t h, const float* f, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    uint32_t u;
    std::memcpy(&u, &f[i], 4);
    h = sigMix(h, u);
  }
  return h;
}

// 0 is reserved for "no signature".
inline uint64_t sigFinish(uint64_t h) { return h == 0 ? 1 : h; }

}  // namespace tessera::detail
