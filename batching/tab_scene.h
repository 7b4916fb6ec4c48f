// The result of texture-array batching (Trapp & Döllner 2015, §3): what `tessera tab build` writes to a
// .tab file (docs/tab-format.md) and what the recorders draw (tab_record.h).
//
// Implements: the data only — the distinct textures with their mip chains, the texture arrays (lists of
// texture indices, one per layer), the output batches B_O = ({G}, TA, TAM), the vertices, and one record
// per input mesh so the unbatched baseline draws exactly the same triangles in the same order.
// Does not implement: building it (batcher.h), reading / writing it (tab_file.h), rendering (tab_record.h).
//
// Conventions
// - Vertices are non-indexed, 3 per triangle, as in the paper (§5.1: "all input meshes are not
//   indexed"): position (x, y, z) and (s, t, i_TAM), 6 floats. i_TAM is the mesh's first TAM entry in its
//   output batch's TAM; unit u of the mesh uses entry i_TAM + u. Untextured and BLEND meshes carry 0.
// - An array's layer l holds texture `layers[l]`; its mip chain is that texture's chain, so a texture
//   array needs no texels of its own and the baseline and the batched frame sample identical texels.
// - All arrays are RGBA8 (the only colour format the importer produces); `format` is kept in the key
//   and the file so that another format would make a different array.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tessera::batching {

// The arrays one output batch may bind: the width of texarray_batch's switch over named samplers (units
// 1-8; at most 15 under kMaxTextureUnits = 16, unit 0 holding the TAM).
constexpr uint32_t kMaxTabArrays = 8;
// i_TAM travels as a float texcoord: integers up to 2^24 are exact.
constexpr uint32_t kMaxTamIndex = 1u << 24;

// glTF 2.0 material.alphaMode, as model::AlphaMode.
enum class AlphaMode : uint8_t { Opaque = 0, Mask = 1, Blend = 2 };
// Sampler wrap modes (glTF wrapS / wrapT), as model::Wrap.
enum class WrapMode : uint8_t { Repeat = 0, ClampToEdge = 1, MirroredRepeat = 2 };
// Texel formats of arrays. One value today.
enum class TexelFormat : uint8_t { RGBA8 = 0 };

struct Vertex {
  float x, y, z;
  float s, t, index;  // index = i_TAM (exact: < 2^24)
};
static_assert(sizeof(Vertex) == 24);

// One distinct original texture: RGBA8 mip chain, level 0 first, rows bottom first (as uploaded).
struct TabTexture {
  std::string name;  // the model's image name or uri, for reports
  uint32_t width = 0, height = 0;
  TexelFormat format = TexelFormat::RGBA8;
  WrapMode wrapS = WrapMode::Repeat, wrapT = WrapMode::Repeat;  // the sampler of the meshes using it
  std::vector<std::vector<uint8_t>> levels;                      // full chain (fullMipCount levels)
  uint64_t bytes() const;
};

// The key of matchTextureArray: resolution, format and sampler state (wrap modes live in the sampler
// of the array's unit, so two textures with different wrap modes cannot share an array).
struct ArrayKey {
  uint32_t width = 0, height = 0;
  TexelFormat format = TexelFormat::RGBA8;
  WrapMode wrapS = WrapMode::Repeat, wrapT = WrapMode::Repeat;
  auto operator<=>(const ArrayKey&) const = default;
};

struct TextureArray {
  ArrayKey key;
  std::vector<uint32_t> layers;  // texture index per layer, at most d_max
};

// One texture-array entry TAE = (TA, l) plus the mesh's material (base-colour factor, alpha test).
struct TamEntry {
  uint32_t array = 0;  // index into the output batch's `arrays` (0 .. a_max - 1): the program's arrayID
  uint32_t layer = 0;
  std::array<float, 4> factor{1, 1, 1, 1};  // glTF baseColorFactor
  float alphaCutoff = 0.0f;                 // MASK: discard iff alpha < cutoff; 0 otherwise
  bool opaque = true;                       // OPAQUE / MASK: output alpha forced to 1
};

struct GeometryBatch {
  uint32_t firstVertex = 0, vertexCount = 0;  // into TabScene::vertices: one draw
  uint32_t firstMesh = 0, meshCount = 0;      // into TabScene::meshes (consecutive)
};

struct OutputBatch {
  std::vector<uint32_t> arrays;  // indices into TabScene::arrays, at most a_max
  std::vector<TamEntry> tam;     // this batch's texture-array mapping
  std::vector<GeometryBatch> geometry;
};

enum class MeshKind : uint8_t { Batched = 0, Untextured = 1, Blend = 2 };

// One input mesh (input batch B_I), in drawing order: batched meshes in batching order, then the
// untextured ones (one flat-colour draw for all), then the BLEND ones (drawn last, sorted per frame).
struct TabMesh {
  std::string name;
  MeshKind kind = MeshKind::Batched;
  uint32_t modelMesh = 0;  // index into the source model's meshes
  uint32_t firstVertex = 0, vertexCount = 0;
  std::vector<uint32_t> textures;  // texture index per texture unit (empty for untextured meshes)
  std::array<float, 4> factor{1, 1, 1, 1};
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  uint32_t outputBatch = 0, tamIndex = 0;  // Batched only: where its entries are (i_TAM)
};

struct TabParams {
  uint32_t bMax = 1u << 20;  // vertices per geometry batch (> 3)
  uint32_t dMax = 256;       // layers per array (> 0, <= kMaxArrayLayers)
  uint32_t aMax = 8;         // arrays per output batch (> 0, <= kMaxTabArrays)
  bool operator==(const TabParams&) const = default;
};

struct TabScene {
  TabParams params;
  std::string source;  // the model file's name (no directory), for reports
  std::array<float, 6> bounds{};  // min x, y, z, max x, y, z of every vertex
  std::vector<TabTexture> textures;
  std::vector<TextureArray> arrays;
  std::vector<OutputBatch> batches;
  std::vector<TabMesh> meshes;
  std::vector<Vertex> vertices;
  // Untextured meshes: their vertices are meshes[i].firstVertex.. like the others; the flat-colour
  // draw takes each vertex's colour from its mesh's factor.
};

}  // namespace tessera::batching
