// Textured scenes read from files: the input of the texture atlas tree (docs/model-import.md, docs/mta-build.md).
//
// Implements: an in-memory textured triangle scene (Model) read from glTF 2.0 (.gltf / .glb, embedded
// or external images), OBJ + MTL, AC3D (.ac, TORCS .acc; the project's own reader) and everything
// Assimp reads (COLLADA .dae, glTF 1.0, ...);
// lazy texture access: a Model only says where each image's bytes are, and loadTexture() /
// probeTexture() decode or measure one image at a time through OpenImageIO, so a consumer that works
// out of core never holds more than the textures it asked for.
// Does not implement: rendering, atlas building, skinning, morph targets, cameras, lights, or any
// material beyond the base colour (texture x factor, alpha mode). docs/model-import.md lists what each
// loader keeps and drops.
//
// Conventions (every loader produces them)
// - Positions are in the file's units with every node transform applied: the hierarchy is composed
//   in double and the result stored as float. glTF is Y-up; other formats keep their own axes.
// - Positions and normals are glm::vec3, texcoords glm::vec2 (x = u, y = v).
// - Texcoords are stored as float exactly as the file gives them after the texture transform (glTF
//   KHR_texture_transform, MTL -o/-s): never clamped or wrapped, so repeat counts in the thousands
//   survive. v follows glTF: v = 0 is the first (top) row of the image file. Loaders for formats
//   whose v points up (OBJ, Assimp) store 1 - v.
// - Image rows are in file order (top row first), which is RgbaImage's row 0 (base/rgba_image.h). With
//   the v convention above, uploading them to GL as-is (first file row = GL row 0, t = 0) maps every
//   texcoord to the texel the file meant.
// - Triangles are uint32 index triples, counter-clockwise front faces (a transform with a negative
//   determinant flips the winding back). Strips and fans are converted; points and lines are dropped
//   with a note.
// - Every mesh knows the scene-graph object it came from (Mesh::object, an index into Model::objects):
//   one instance of a glTF node, one AC3D object, one OBJ shape (`o` / `g`), one instance of an
//   Assimp node. The rule per format is in docs/model-import.md ("Objects"). A loader that splits one
//   object into several meshes (one per material / primitive) gives them all the same object; the
//   meshes of an object are consecutive in Model::meshes.
#pragma once

#include <array>
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <string>
#include <vector>

#include "base/resource_limits.h"
#include "base/rgba_image.h"

namespace tessera::model {

struct Bounds {
  glm::vec3 min{1e30f, 1e30f, 1e30f}, max{-1e30f, -1e30f, -1e30f};
  bool empty() const { return min.x > max.x; }
  void add(const glm::vec3& p);
};

// How the base colour's alpha is used (glTF 2.0 material.alphaMode).
enum class AlphaMode : uint8_t { Opaque, Mask, Blend };
// Texture address modes (glTF sampler wrapS / wrapT).
enum class Wrap : uint8_t { Repeat, ClampToEdge, MirroredRepeat };

struct Material {
  std::string name;
  int32_t baseColorTexture = -1;                                 // index into Model::textures, -1 = untextured
  std::array<float, 4> baseColorFactor{1.0f, 1.0f, 1.0f, 1.0f};  // multiplies the texture (linear)
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;  // Mask only
  bool doubleSided = false;
  Wrap wrapS = Wrap::Repeat, wrapT = Wrap::Repeat;
  // glTF occlusionTexture (a second texture layer, thesis §5.1.3; R holds the occlusion): index into
  // Model::textures or -1, its strength, its sampler's wrap modes. Read from its own texCoord set
  // (Mesh::occlusionTexcoords). Formats without one leave it at -1.
  int32_t occlusionTexture = -1;
  float occlusionStrength = 1.0f;
  Wrap occlusionWrapS = Wrap::Repeat, occlusionWrapT = Wrap::Repeat;
};

// One material's triangles. texcoords and normals are either empty or one per position.
struct Mesh {
  std::string name;
  uint32_t material = 0;  // index into Model::materials (always valid)
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> texcoords;  // the set the material's texture uses (TEXCOORD_n / UV channel n)
  std::vector<glm::vec2> occlusionTexcoords;  // the set its occlusionTexture uses; empty without one
  std::vector<glm::vec3> normals;
  std::vector<uint32_t> indices;  // 3 per triangle
  uint32_t object = 0;            // index into Model::objects: the scene-graph object this mesh came from
  size_t triangleCount() const { return indices.size() / 3; }
};

// One scene-graph object that produced meshes: the unit RTTA's `--objects node` groups by
// (model/object_groups.h). A node that the graph reaches twice (glTF instancing) is two objects with
// the same `node` and instance 0 and 1: an object is an instance, since its two copies sit at two
// places on screen.
struct SceneObject {
  std::string name;       // the node's / object's / shape's name, or "<kind><index>" when the file gives none
  int32_t node = -1;      // the file's index of it: glTF node index, AC3D object (file order, the world
                          // object 0), OBJ shape, Assimp node in depth-first pre-order (root 0)
  uint32_t instance = 0;  // 0 for the first object made from `node`, 1 for the second instance, ...
};

// What an image's header says (probeTexture()).
struct TextureInfo {
  uint32_t width = 0, height = 0;
  int channels = 0;
  std::string format;  // OIIO's format name: "png", "jpeg", "targa", "sgi", "dds", ...
};

// Where one image's encoded bytes are. Nothing is decoded until loadTexture().
struct TextureRef {
  enum class Source : uint8_t {
    File,       // the whole file `path` is the image (PNG, JPEG, TGA, SGI, DDS, ...)
    FileRange,  // bytes [offset, offset + size) of `path` (an image inside a .glb or an external .bin)
    Memory,     // `bytes` (a data: URI, or an image Assimp embedded); `rawRGBA`: bytes are RGBA8 texels
  };
  Source source = Source::File;
  std::string name;  // the image's name, or its file name
  std::string uri;   // as the model file wrote it (for messages); empty for embedded images
  std::string path;  // File / FileRange: the file to read
  uint64_t offset = 0, size = 0;
  std::string mimeType;  // "image/png", "image/jpeg", ... when the model says; else guessed from bytes
  std::shared_ptr<const std::vector<uint8_t>> bytes;  // Memory only
  bool rawRGBA = false;                               // Memory only: bytes are width x height RGBA8
  uint32_t rawWidth = 0, rawHeight = 0;
  // The header as loadModel() read it to check the texture budget; width 0 when it could not be read
  // (loadTexture() / probeTexture() then say why). probeTexture() returns it without reopening the image.
  TextureInfo header;
};

struct Model {
  std::vector<Material> materials;
  std::vector<Mesh> meshes;
  // In the order of their first mesh; each has at least one mesh and its meshes are consecutive, so
  // Mesh::object never decreases along `meshes`.
  std::vector<SceneObject> objects;
  std::vector<TextureRef> textures;  // one per distinct image
  Bounds bounds;                     // of every position of every mesh
  std::string source;                // the file it was read from
  std::string loader;                // "gltf", "obj", "ac3d" or "assimp:<format>"
  std::vector<std::string> notes;    // what was dropped or assumed (points/lines, unsupported maps, ...)

  size_t triangleCount() const;
};

// A decoded texture: an RgbaImage whose row 0 is the file's top row (file order), plus what the file said.
struct Image : RgbaImage {
  int fileChannels = 0;    // channels the file stores (1 grey, 2 grey+alpha, 3 RGB, 4 RGBA)
  bool usesAlpha = false;  // some texel has alpha < 255
};

// Reads a model file, or a scene of several: a scene manifest (a .json file) or a directory of model
// files, merged into one Model (model/scene_manifest.h, docs/model-import.md "Scenes of several files").
// The loader of a file is chosen by content first (a .glb / glTF 1.0 / glTF 2.0 header, an
// AC3D header), then by extension: .gltf / .glb -> tinygltf (glTF 1.0 goes to Assimp), .obj ->
// tinyobjloader, .ac / .acc / .ac3d -> the AC3D reader, anything else -> Assimp. Image files are
// checked to exist and their headers are read (not decoded).
// `limits` (base/resource_limits.h, docs/limits.md) bounds the instances after expanding the node graph,
// the nesting of the graph, the triangles and vertices over all instances (each checked before that
// geometry is read) and the decoded RGBA8 bytes of all textures (from their headers).
// Throws Error naming the file and what is wrong: the JSON pointer for malformed glTF
// ("/accessors/3/bufferView: ..."), file:line for OBJ / MTL, the model and the missing path for a missing
// texture, overLimitMessage() for a model over `limits`.
Model loadModel(const std::string& path, const ResourceLimits& limits = {});

// Decodes texture `index` of `model` to RGBA8: grey is replicated, a missing alpha becomes 255,
// 16-bit channels are rounded to 8 bits, alpha is read unassociated (as stored).
// Throws Error naming the model, the texture index and its uri on failure. loadTexture() and probeTexture()
// may run concurrently on one Model: each call opens its own reader.
Image loadTexture(const Model& model, size_t index);

// The size and channel count of texture `index`, read from the image header only (OIIO's spec); the
// header loadModel() already read when it could.
TextureInfo probeTexture(const Model& model, size_t index);

}  // namespace tessera::model
