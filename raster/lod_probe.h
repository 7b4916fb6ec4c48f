// The LOD probe: per pixel, the level of detail of each texture lookup made by the fragment whose colour
// the pixel holds, as the oracle's own sampler computed it (docs/texel.md).
//
// Implements: the records (LodLookup, LodPixel, LodMap), the per-quad log the sampler appends to when a
// probe is active on the calling thread (setLodQuadLog; sample.cpp fills it in sampleQuad2D,
// sampleQuad2DArray and sampleGrad2DArray, the lookups with a LOD), and lodMap(), which replays a list
// with RenderOptions::lodProbe and returns the map of its presented image.
// Which fragment: the last fragment written to a pixel (after coverage, depth test and discard, in
// submission order within the tile that owns the pixel) replaces the pixel's record; a colour clear of
// attachment 0 empties it. So the record describes the fragment whose colour is stored (with blending,
// the last one blended), and it is the same at any thread count.
// Does not implement: texelFetch (no LOD, never recorded), sampleAtLambda (explicit LOD, unused by the
// programs), provenance mode (the probe is ignored there), or a comparison (verify/lod_compare.h).
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "raster/command_list.h"

namespace tessera {

struct TexUnit;

// One texture lookup with a LOD, for one fragment.
struct LodLookup {
  uint32_t width = 0, height = 0;  // level 0 of the texture sampled (0 x 0: no texture bound)
  uint32_t layers = 0;             // array layers (1 for a 2D texture)
  int32_t lambda8 = 0;             // lambda after bias and clamps, 8.8 (kLodMinusInf: rho == 0)
  uint8_t unit = 0;                // texture unit the program sampled
  uint8_t levels = 0;              // mip levels read: 1 or 2; 0 for an incomplete texture (no LOD used)
  uint8_t grad = 0;                // 1: textureGrad (explicit derivatives), 0: implicit (quad differences)
  double rho2 = 0.0;               // rho^2 in texels of level 0 (GL 4.6 §8.14.1), as the sampler computed it
  bool operator==(const LodLookup&) const = default;
};

constexpr int kLodLookupsPerPixel = 4;

struct LodPixel {
  uint8_t count = 0;  // lookups the fragment made (may exceed kLodLookupsPerPixel; the first ones are kept)
  std::array<LodLookup, kLodLookupsPerPixel> look{};
  int recorded() const { return count < kLodLookupsPerPixel ? count : kLodLookupsPerPixel; }
  bool operator==(const LodPixel&) const = default;
};

// The probe's result for one image: pixels row by row, row 0 at the bottom (GL window coordinates,
// like TextureData); a pixel no fragment wrote (or a clear emptied) has count 0.
struct LodMap {
  int32_t width = 0, height = 0;
  std::vector<LodPixel> pixels;
  const LodPixel& at(int32_t x, int32_t y) const { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
  LodPixel& at(int32_t x, int32_t y) { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
};

// What the sampler appends during one fragment-program call on one quad (all four pixels share the
// lookups; the texarray_batch per-pixel fallback therefore lists each pixel's lookup for all four).
struct LodQuadLog {
  static constexpr int kCapacity = 16;
  struct Entry {
    const TexUnit* unit = nullptr;  // the rasterizer turns it into the unit index
    LodLookup look;
  };
  int count = 0;  // may exceed kCapacity; only the first kCapacity entries are stored
  std::array<Entry, kCapacity> e{};
};

// Sets the calling thread's log (nullptr: no probe). The sampler tests it once per quad lookup.
void setLodQuadLog(LodQuadLog* log);

// Replays `list` on the oracle with the probe (threads: 0 = all) and returns the map of its first
// presented image (attachment 0 of the final target at its level and layer). Throws Error (prefixed
// with frameName) if the list is invalid or presents nothing.
LodMap lodMap(const CommandList& list, int threads = 0, std::string_view frameName = "frame");
// The same on `probe`, a backend made with RenderOptions::lodProbe (Error otherwise), into `out`. A
// caller probing a sequence of frames keeps both, so each frame reuses the storage of the last (the
// backend's textures and maps, and out's pixels: a map is about 42 MB at 640x480).
class CpuBackend;
void lodMap(CpuBackend& probe, const CommandList& list, LodMap& out, std::string_view frameName = "frame");

}  // namespace tessera
