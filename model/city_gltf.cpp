// Writing a generated city as glTF 2.0: DIR/<name>.gltf (JSON), DIR/<name>.bin (positions, then
// texcoords, then uint32 indices, one bufferView each) and DIR/textures/tNNNNN.png|jpg.
// Textures are rendered and encoded in parallel (TBB), each into its own file, so the bytes do not
// depend on the schedule. Every file is written atomically (base/atomic_file.h); the .gltf comes
// last, so its presence means the rest is complete.
#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tiny_gltf.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/common.hpp>
#include <map>
#include <mutex>

#include "base/atomic_file.h"
#include "base/det_math.h"
#include "model/city_scene.h"
#include "model/gltf_graph.h"
#include "model/loaders.h"
#include "raster/command_list.h"
#include "raster/image_io.h"

namespace tessera::model::city {

namespace {

namespace fs = std::filesystem;

void writeBytes(const std::string& path, const void* data, size_t size) {
  writeFileAtomically(path, std::span<const uint8_t>(static_cast<const uint8_t*>(data), size));
}

void writeImageFile(const std::string& path, const TexSpec& t, const std::vector<uint8_t>& px, bool jpg) {
  Image8Options o;
  if (jpg)
    o.jpegQuality = 90;
  else
    o.pngCompressionLevel = 1;
  writeImage8(path, int(t.width), int(t.height), t.rgba() ? 4 : 3, px.data(), o);
}

uint64_t fileSize(const std::string& path);

constexpr const char* kLightMapName = "lightmap.png";
constexpr int kLightMapSize = 64;

// DIR/lightmap.png (CityOptions::lightMap): grey, 255 at row 0 (v = 0, the top of a texture repeat)
// falling linearly to 129 at the last row.
void writeLightMap(const CityOptions& o, CitySummary& s) {
  std::vector<uint8_t> px(size_t(kLightMapSize) * kLightMapSize * 3);
  for (int y = 0; y < kLightMapSize; ++y)
    for (int x = 0; x < kLightMapSize; ++x)
      for (int c = 0; c < 3; ++c) px[(size_t(y) * kLightMapSize + size_t(x)) * 3 + size_t(c)] = uint8_t(255 - 2 * y);
  Image8Options io;
  io.pngCompressionLevel = 1;
  const std::string path = o.outDir + "/" + kLightMapName;
  writeImage8(path, kLightMapSize, kLightMapSize, 3, px.data(), io);
  s.files.push_back(kLightMapName);
  s.bytesOnDisk += fileSize(path);
}

uint64_t fileSize(const std::string& path) {
  std::error_code ec;
  const auto n = fs::file_size(path, ec);
  return ec ? 0 : uint64_t(n);
}

template <class T>
void append(std::vector<uint8_t>& bin, const std::vector<T>& v) {
  const size_t at = bin.size();
  bin.resize(at + v.size() * sizeof(T));
  if (!v.empty()) std::memcpy(bin.data() + at, v.data(), v.size() * sizeof(T));
}

}  // namespace

namespace {

// Renders and writes every texture; returns the file names relative to the output directory.
std::vector<std::string> writeTextures(const Scene& scene, const CityOptions& o, CitySummary& s) {
  const std::string dir = o.outDir;
  std::error_code ec;
  fs::create_directories(dir + "/textures", ec);
  if (ec) throw Error(dir + "/textures: cannot create the output directory: " + ec.message());

  const bool jpg = o.format == CityImageFormat::Jpg;
  const size_t nt = scene.textures.size();
  std::vector<std::string> names(nt);
  std::vector<uint64_t> sizes(nt);
  const int digits = std::max<int>(5, int(std::to_string(nt).size()));
  for (size_t i = 0; i < nt; ++i)
    names[i] = fmt::format("textures/t{:0{}}.{}", i, digits, jpg && !scene.textures[i].rgba() ? "jpg" : "png");
  std::atomic<size_t> done{0};
  std::mutex printMutex;
  const bool progress = o.progress && nt >= 200;
  tbb::parallel_for(size_t(0), nt, [&](size_t i) {
    const TexSpec& t = scene.textures[i];
    const std::string path = dir + "/" + names[i];
    writeImageFile(path, t, renderTexture(t), names[i].ends_with(".jpg"));
    sizes[i] = fileSize(path);
    const size_t d = ++done;
    if (progress && (d % std::max<size_t>(nt / 20, 1) == 0 || d == nt)) {
      std::lock_guard<std::mutex> lock(printMutex);
      std::fprintf(stderr, "city: %s textures %zu/%zu\n", scene.name.c_str(), d, nt);
    }
  });
  for (size_t i = 0; i < nt; ++i) {
    const TexSpec& t = scene.textures[i];
    s.texelCount += uint64_t(t.width) * t.height;
    s.textureBytesRaw += uint64_t(t.width) * t.height * (t.rgba() ? 4 : 3);
    s.rgbaTextures += t.rgba();
    s.bytesOnDisk += sizes[i];
    s.files.push_back(names[i]);
  }
  s.textures = nt;
  return names;
}

// Writes dir/<scene.name>.gltf and .bin. Texture i of `scene` is image `imageUris[i]` and its material is
// named m<textureIds[i]> (the numbering of the whole city, which a part of it keeps).
// With o.lightMap, `lightMapUri` is the light map's image relative to the file.
std::string writeGltf(const Scene& scene, const std::vector<std::string>& imageUris,
                      const std::vector<uint32_t>& textureIds, const std::string& dir, const CityOptions& o,
                      CitySummary& s, const std::string& lightMapUri) {
  const bool jpg = o.format == CityImageFormat::Jpg;
  const size_t nt = scene.textures.size();
  // Geometry: three bufferViews (positions, texcoords, indices) in one .bin.
  std::vector<uint8_t> pos, uv, idx;
  nlohmann::json accessors = nlohmann::json::array(), meshes = nlohmann::json::array(), nodes = nlohmann::json::array();
  for (const Node& n : scene.nodes) {
    nlohmann::json jn = {{"name", n.name}};
    if (n.translation != std::array<double, 3>{0, 0, 0}) jn["translation"] = n.translation;
    if (n.yaw != 0.0)  // about +Y: (0, sin(yaw/2), 0, cos(yaw/2)), stored as float like every glTF number
      jn["rotation"] = {0.0, double(float(detSin(n.yaw / 2))), 0.0, double(float(detCos(n.yaw / 2)))};
    if (!n.children.empty()) jn["children"] = n.children;
    if (!n.primitives.empty()) {
      nlohmann::json prims = nlohmann::json::array();
      for (const Primitive& p : n.primitives) {
        glm::vec3 lo = p.positions.front(), hi = p.positions.front();
        for (const glm::vec3& v : p.positions)
          lo = glm::min(lo, v), hi = glm::max(hi, v);  // per component, as std::min / std::max
        const size_t a = accessors.size();
        accessors.push_back({{"bufferView", 0},
                             {"byteOffset", pos.size()},
                             {"componentType", 5126},
                             {"count", p.positions.size()},
                             {"type", "VEC3"},
                             {"min", {lo.x, lo.y, lo.z}},
                             {"max", {hi.x, hi.y, hi.z}}});
        const bool textured = !p.texcoords.empty();
        if (textured != (p.material < nt) || (textured && p.texcoords.size() != p.positions.size()))
          throw Error(n.name + ": texcoords do not match material " + std::to_string(p.material) +
                      " (internal error in the city generator)");
        nlohmann::json attributes = {{"POSITION", a}};
        if (textured) {
          attributes["TEXCOORD_0"] = accessors.size();
          accessors.push_back({{"bufferView", 1},
                               {"byteOffset", uv.size()},
                               {"componentType", 5126},
                               {"count", p.texcoords.size()},
                               {"type", "VEC2"}});
        }
        const size_t ia = accessors.size();
        accessors.push_back({{"bufferView", 2},
                             {"byteOffset", idx.size()},
                             {"componentType", 5125},
                             {"count", p.indices.size()},
                             {"type", "SCALAR"}});
        append(pos, p.positions), append(uv, p.texcoords), append(idx, p.indices);
        prims.push_back({{"attributes", attributes}, {"indices", ia}, {"material", p.material}, {"mode", 4}});
        s.triangles += p.indices.size() / 3;
        s.vertices += p.positions.size();
        ++s.primitives;
      }
      jn["mesh"] = meshes.size();
      meshes.push_back({{"name", n.name}, {"primitives", prims}});
    }
    nodes.push_back(jn);
  }
  nlohmann::json materials = nlohmann::json::array(), textures = nlohmann::json::array(),
                 images = nlohmann::json::array();
  // The light map is texture and image 0, so that a split city's parts, merged in order, number their
  // images as the one-file city does (the merge keeps each distinct image once, at its first use).
  const size_t first = o.lightMap ? 1 : 0;
  if (o.lightMap) {
    textures.push_back({{"source", 0}, {"sampler", 0}});
    images.push_back({{"uri", lightMapUri}});
  }
  for (size_t i = 0; i < nt; ++i) {
    const TexSpec& t = scene.textures[i];
    nlohmann::json m = {{"name", fmt::format("m{}", textureIds[i])},
                        {"pbrMetallicRoughness",
                         {{"baseColorTexture", {{"index", first + i}}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}};
    if (t.kind == TexKind::Fence || t.kind == TexKind::Tree)
      m["alphaMode"] = "MASK", m["alphaCutoff"] = 0.5, m["doubleSided"] = true;
    if (t.kind == TexKind::Glass) m["alphaMode"] = "BLEND", m["doubleSided"] = true;
    if (o.lightMap) m["occlusionTexture"] = {{"index", 0}, {"texCoord", 0}};
    materials.push_back(m);
    textures.push_back({{"source", first + i}, {"sampler", 0}});
    images.push_back({{"uri", imageUris[i]}});
  }
  for (const ColourMaterial& c : scene.colours)  // untextured: a base colour factor only
    materials.push_back({{"name", c.name},
                         {"pbrMetallicRoughness",
                          {{"baseColorFactor", {c.rgb[0], c.rgb[1], c.rgb[2], 1.0}},
                           {"metallicFactor", 0.0},
                           {"roughnessFactor", 1.0}}}});
  const std::string binName = scene.name + ".bin";
  const size_t binSize = pos.size() + uv.size() + idx.size();
  nlohmann::json root = {
      {"asset",
       {{"version", "2.0"},
        {"generator", fmt::format("tessera city --preset {} --buildings {} --seed {} --texture-size {} --format {}",
                                  cityPresetName(o.preset), scene.buildings, o.seed, o.textureSize,
                                  jpg ? "jpg" : "png")}}},
      {"scene", 0},
      {"scenes", {{{"name", scene.name}, {"nodes", scene.roots}}}},
      {"nodes", nodes},
      {"meshes", meshes},
      {"accessors", accessors},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", pos.size()}, {"byteStride", 12}, {"target", 34962}},
        {{"buffer", 0}, {"byteOffset", pos.size()}, {"byteLength", uv.size()}, {"byteStride", 8}, {"target", 34962}},
        {{"buffer", 0}, {"byteOffset", pos.size() + uv.size()}, {"byteLength", idx.size()}, {"target", 34963}}}},
      {"buffers", {{{"uri", binName}, {"byteLength", binSize}}}},
      {"materials", materials},
      {"textures", textures},
      {"images", images},
      {"samplers", {{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}}}}};
  std::vector<uint8_t> bin;
  bin.reserve(binSize);
  bin.insert(bin.end(), pos.begin(), pos.end());
  bin.insert(bin.end(), uv.begin(), uv.end());
  bin.insert(bin.end(), idx.begin(), idx.end());
  writeBytes(dir + "/" + binName, bin.data(), bin.size());
  const std::string json = root.dump() + "\n";
  const std::string gltf = dir + "/" + scene.name + ".gltf";
  writeBytes(gltf, json.data(), json.size());
  s.bytesOnDisk += bin.size() + json.size();
  return gltf;
}

// The part of `scene` that node `n` holds: its primitives at the origin of its own frame (no transform),
// with only the textures and colour materials they use, in order of first use.
struct Part {
  Scene scene;
  std::vector<std::string> imageUris;  // relative to the part's file
  std::vector<uint32_t> textureIds;
};

Part partOf(const Scene& scene, const Node& n, const std::vector<std::string>& names) {
  Part p;
  p.scene.name = n.name;
  p.scene.buildings = scene.buildings;
  p.scene.roots = {0};
  p.scene.nodes.push_back(Node{.name = n.name});
  const size_t nt = scene.textures.size();
  std::map<uint32_t, uint32_t> textures, colours;  // the city's index -> the part's
  for (const Primitive& prim : n.primitives) {
    if (prim.material < nt && textures.emplace(prim.material, uint32_t(textures.size())).second) {
      p.scene.textures.push_back(scene.textures[prim.material]);
      p.imageUris.push_back("../" + names[prim.material]);
      p.textureIds.push_back(prim.material);
    }
    if (prim.material >= nt && colours.emplace(prim.material, uint32_t(colours.size())).second)
      p.scene.colours.push_back(scene.colours[prim.material - nt]);
  }
  for (const Primitive& prim : n.primitives) {
    Primitive q = prim;
    q.material = prim.material < nt ? textures.at(prim.material) : uint32_t(textures.size()) + colours.at(prim.material);
    p.scene.nodes[0].primitives.push_back(std::move(q));
  }
  return p;
}

// The local transform of a city node exactly as the glTF loader reads the node this writer writes
// (gltf::nodeTransform on the same doubles), so a part placed by the manifest lands on the same bits.
glm::dmat4 localTransform(const Node& n) {
  tinygltf::Node t;
  if (n.translation != std::array<double, 3>{0, 0, 0}) t.translation = {n.translation[0], n.translation[1], n.translation[2]};
  if (n.yaw != 0.0) t.rotation = {0.0, double(float(detSin(n.yaw / 2))), 0.0, double(float(detCos(n.yaw / 2)))};
  return detail::gltf::nodeTransform(t);
}

}  // namespace

void writeSplitScene(const Scene& scene, const CityOptions& o, CitySummary& s) {
  const std::vector<std::string> names = writeTextures(scene, o, s);
  if (o.lightMap) writeLightMap(o, s);
  const std::string partsDir = o.outDir + "/parts";
  std::error_code ec;
  fs::create_directories(partsDir, ec);
  if (ec) throw Error(partsDir + ": cannot create the output directory: " + ec.message());
  // Nodes in the loader's depth-first pre-order with their world transforms (composed as the loader
  // composes them), so the manifest lists the parts in the order the one-file city's meshes come in.
  nlohmann::json models = nlohmann::json::array();
  struct Frame {
    uint32_t node;
    glm::dmat4 parent;
  };
  std::vector<Frame> stack;
  for (auto it = scene.roots.rbegin(); it != scene.roots.rend(); ++it) stack.push_back({*it, glm::dmat4(1.0)});
  while (!stack.empty()) {
    const Frame f = stack.back();
    stack.pop_back();
    const Node& n = scene.nodes.at(f.node);
    const glm::dmat4 world = detail::compose(f.parent, localTransform(n));
    for (auto it = n.children.rbegin(); it != n.children.rend(); ++it) stack.push_back({*it, world});
    if (n.primitives.empty()) continue;
    const Part p = partOf(scene, n, names);
    writeGltf(p.scene, p.imageUris, p.textureIds, partsDir, o, s, std::string("../") + kLightMapName);
    s.files.push_back("parts/" + n.name + ".bin");
    s.files.push_back("parts/" + n.name + ".gltf");
    nlohmann::json m = nlohmann::json::array();
    for (int i = 0; i < 16; ++i) m.push_back(world[i / 4][i % 4]);  // column-major, as the manifest reads it
    models.push_back({{"file", "parts/" + n.name + ".gltf"}, {"name", n.name}, {"transform", m}});
  }
  const nlohmann::json manifest = {
      {"schema", 1},
      {"comment", fmt::format("tessera city --preset {} --buildings {} --seed {} --texture-size {} --split-per-building",
                              cityPresetName(o.preset), scene.buildings, o.seed, o.textureSize)},
      {"models", models}};
  // One entry a line (nlohmann's indented dump puts every number of a matrix on its own line).
  std::string json = "{\n  \"schema\": 1,\n  \"comment\": " + manifest["comment"].dump() + ",\n  \"models\": [\n";
  for (size_t i = 0; i < models.size(); ++i) json += "    " + models[i].dump() + (i + 1 < models.size() ? ",\n" : "\n");
  json += "  ]\n}\n";
  s.gltf = o.outDir + "/" + scene.name + ".json";
  writeBytes(s.gltf, json.data(), json.size());  // last: its presence means the parts are complete
  s.files.push_back(scene.name + ".json");
  s.bytesOnDisk += json.size();
}

void writeScene(const Scene& scene, const CityOptions& o, CitySummary& s) {
  const std::vector<std::string> names = writeTextures(scene, o, s);
  if (o.lightMap) writeLightMap(o, s);
  std::vector<uint32_t> ids(names.size());
  for (size_t i = 0; i < ids.size(); ++i) ids[i] = uint32_t(i);
  s.gltf = writeGltf(scene, names, ids, o.outDir, o, s, kLightMapName);
  s.files.push_back(scene.name + ".bin");
  s.files.push_back(scene.name + ".gltf");
}

}  // namespace tessera::model::city
