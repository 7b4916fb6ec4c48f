// Deterministic synthetic city models after the two test scenes of Buchholz's thesis (§4.7), written
// as real glTF 2.0 files with their textures, for the atlas tree and its benchmarks.
//
// Implements:
// - "berlin" (§4.7.1): N block buildings on a grid of 105 m lots and 10 m streets, each with its own
//   facade texture (textureSize², RGB, windows and floors, a plaque with the building's number, as
//   the thesis labelled its 10,000 textures) repeated around the facade: u runs continuously around
//   the building, one repeat per 12 m (4 window columns), v one repeat per 4 floors. Roofs and ground
//   are untextured (base colour materials only), as the thesis kept "roofs and terrain" out of the
//   atlas tree; the facade textures are the whole textured workload. The lot pitch is calibrated so
//   that N = 10,000 at d_min = D/72 gives a tree of the thesis' size (city_gen.cpp). 10,000
//   buildings at 512² are 7.32 GiB of raw texels, the thesis' number.
// - "chemnitz" (§4.7.2): irregular detail. Per building: an extruded random star-shaped footprint
//   with walls split into floors and ~1.1 m segments (3 facade textures), a pyramid roof, small boxes
//   (balconies, chimneys), and sometimes a fence (RGBA, alpha MASK), trees (RGBA crossed quads,
//   MASK), a glass canopy (RGBA, BLEND) and a raised plaza with a pavement texture. One ground pair
//   of triangles spans the city with a tile texture repeated 2000 times across a single triangle.
//   Texture sizes are mixed (64..512, a few not powers of two). The default of 400 buildings gives
//   about 2,000 textures, ~36 M texels and ~300 k triangles, the thesis' figures; --buildings scales it.
// Output: DIR/<preset>.gltf, DIR/<preset>.bin, DIR/textures/tNNNNN.png|jpg; every file written to a
// temporary name and renamed. The bytes depend only on the options (no clock, no thread count):
// geometry uses IEEE arithmetic and detSin/detCos, textures integer arithmetic from per-texture seeds,
// and are encoded in parallel (TBB) into their own files.
// Does not implement: terrain relief, landmarks, aerial roof images, or loading (loadModel() reads the
// result).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tessera::model {

enum class CityPreset { Berlin, Chemnitz };
enum class CityImageFormat { Png, Jpg };

struct CityOptions {
  CityPreset preset = CityPreset::Berlin;
  uint32_t buildings = 0;  // 0 = the thesis' size: berlin 10,000, chemnitz 400 (~2,000 textures)
  uint64_t seed = 1;
  uint32_t textureSize = 512;  // berlin: facade size; chemnitz: every size is scaled by textureSize / 512
  // Png: zlib level 1 (fast; ~4x smaller than raw for these textures). Jpg: quality 90, RGB only;
  // RGBA textures (fences, trees, glass) are always PNG.
  CityImageFormat format = CityImageFormat::Png;
  std::string outDir;
  bool progress = true;  // progress lines on stderr for long runs
  // One glTF per building (and one for the ground) under DIR/parts/ plus the scene manifest
  // DIR/<preset>.json instead of DIR/<preset>.gltf; CitySummary::gltf is then the manifest.
  bool splitPerBuilding = false;
  // A light-map layer (issue 14 §5; thesis §5.1.3): one grey image DIR/lightmap.png, bright at the top
  // of each texture repeat and darker towards its bottom (v = 1), given to every textured material as its
  // glTF occlusionTexture on texCoord 0 (REPEAT, strength 1). It reads layer 0's own texcoords, so it is
  // a function of them and the atlas tree's layer-1 atlases are exact however often a facade repeats.
  bool lightMap = false;
};

struct CitySummary {
  std::string gltf;                // path of the .gltf file (splitPerBuilding: of the scene manifest)
  std::vector<std::string> files;  // every file written, relative to outDir
  uint32_t buildings = 0;
  uint64_t textures = 0, rgbaTextures = 0, triangles = 0, vertices = 0, primitives = 0;
  uint64_t textureBytesRaw = 0;  // width * height * channels summed over every texture
  uint64_t texelCount = 0;
  uint64_t bytesOnDisk = 0;  // of every file written
  double seconds = 0.0;      // wall time (the only field that varies between runs)
  nlohmann::json toJson() const;
};

// Parses "berlin" / "chemnitz"; throws Error naming the value otherwise.
CityPreset parseCityPreset(const std::string& name);
const char* cityPresetName(CityPreset p);
uint32_t defaultCityBuildings(CityPreset p);

// Generates the city into options.outDir (created if missing). Throws Error naming the file on any
// write failure; never leaves a partial file under a final name.
CitySummary generateCity(const CityOptions& options);

}  // namespace tessera::model
